#include "formats/results_folder.h"

#include "support/errors.h"
#include "formats/files.h"
#include "formats/json_out.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstring>

#include "support/errors.h"
#include "formats/files.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// For the interrupt handler: put the set-aside folder back (two renames, async-signal-safe).
char gRestoreFrom[PATH_MAX];
char gRestoreTo[PATH_MAX];
char gRestorePartial[PATH_MAX];

void RestoreSetAside() {
    if (!gRestoreFrom[0]) return;
    rename(gRestoreTo, gRestorePartial);
    rename(gRestoreFrom, gRestoreTo);
}

void CopyPath(char* into, const fs::path& path) {
    const std::string text = path.string();
    const size_t n = std::min(text.size(), size_t(PATH_MAX - 1));
    std::memcpy(into, text.c_str(), n);
    into[n] = 0;
}

// Takes DIR/.lock or throws naming the holder.
int Lock(const fs::path& dir, const std::string& command) {
    const fs::path path = dir / ".lock";
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw UsageError("cannot lock " + Quote(dir.string()) + ": " + std::strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        char holder[256] = {0};
        const ssize_t n = pread(fd, holder, sizeof holder - 1, 0);
        ::close(fd);
        std::string text = n > 0 ? std::string(holder, static_cast<size_t>(n)) : std::string("another process");
        while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
        throw UsageError(Quote(dir.string()) + " is in use by " + text + "; wait for it to finish or choose another --out");
    }
    const std::string owner = "pid " + std::to_string(getpid()) + " (actuator " + command + ")\n";
    if (ftruncate(fd, 0) != 0 || pwrite(fd, owner.data(), owner.size(), 0) < 0) {
        // The lock holds whatever the file says; the text only helps the message above.
    }
    return fd;
}

}  // namespace

bool HoldsResults(const fs::path& dir) {
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name != ".lock" && !IsTemporaryName(name)) return true;
    }
    return false;
}

ResultsFolder::ResultsFolder(const fs::path& dir, FolderMode mode, const std::string& command) : dir_(dir), mode_(mode) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(dir, ec);
    if (fs::exists(status) && !fs::is_directory(fs::status(dir, ec)))
        throw UsageError("--out: " + Quote(dir.string()) + " exists and is not a folder");
    if (!fs::exists(status)) {
        if (mode == FolderMode::Resume) throw UsageError("--resume: " + Quote(dir.string()) + " does not exist; nothing to resume");
        fs::create_directories(dir, ec);
        if (!fs::is_directory(dir, ec)) throw UsageError("--out: cannot create folder " + Quote(dir.string()) + (ec ? ": " + ec.message() : ""));
    }
    if (access(dir.c_str(), W_OK) != 0) throw UsageError("--out: cannot write in " + Quote(dir.string()));
    lockFd_ = Lock(dir, command);
    // A constructor that throws runs no destructor: let go of the lock here.
    struct Release {
        int& fd;
        bool armed = true;
        ~Release() {
            if (armed && fd >= 0) ::close(fd), fd = -1;
        }
    } release{lockFd_};
    RemoveStaleTemporaries(dir);
    const bool holds = HoldsResults(dir);
    if (mode == FolderMode::Fresh && holds)
        throw UsageError(Quote(dir.string()) + " already holds results; add --resume to continue that run or --overwrite to replace it");
    if (mode == FolderMode::Resume && !holds) throw UsageError("--resume: " + Quote(dir.string()) + " holds no earlier run to resume");
    if (mode == FolderMode::Overwrite && holds) {
        // Set the old results aside under a sibling name; they come back if this run fails first.
        setAside_ = dir.parent_path() / (dir.filename().string() + ".replaced-" + std::to_string(getpid()));
        fs::rename(dir, setAside_, ec);
        if (ec) throw UsageError("--overwrite: cannot set " + Quote(dir.string()) + " aside: " + ec.message());
        ::close(lockFd_);
        lockFd_ = -1;
        fs::create_directories(dir, ec);
        if (ec) {
            fs::rename(setAside_, dir, ec);
            throw UsageError("--overwrite: cannot create folder " + Quote(dir.string()));
        }
        lockFd_ = Lock(dir, command);
        CopyPath(gRestoreFrom, setAside_);
        CopyPath(gRestoreTo, dir);
        CopyPath(gRestorePartial, dir.parent_path() / (dir.filename().string() + ".interrupted-" + std::to_string(getpid())));
        SetInterruptRestore(&RestoreSetAside);
    }
    release.armed = false;
}

void ResultsFolder::FirstResultDone() {
    if (setAside_.empty()) return;
    SetInterruptRestore(nullptr);
    gRestoreFrom[0] = 0;
    std::error_code ec;
    fs::remove_all(setAside_, ec);
    setAside_.clear();
}

ResultsFolder::~ResultsFolder() {
    if (!setAside_.empty()) {
        // This run ended (an error or exception) before its first result: put the old results back.
        SetInterruptRestore(nullptr);
        gRestoreFrom[0] = 0;
        std::error_code ec;
        if (lockFd_ >= 0) ::close(lockFd_);
        lockFd_ = -1;
        fs::remove_all(dir_, ec);
        fs::rename(setAside_, dir_, ec);
    }
    if (lockFd_ >= 0) ::close(lockFd_);  // the lock file stays; the lock goes with the descriptor
}

nlohmann::ordered_json RunRecord(const std::filesystem::path& record, FolderMode mode, const std::vector<RunSetting>& settings) {
    nlohmann::ordered_json now = nlohmann::ordered_json::object();
    for (const RunSetting& s : settings) now[s.key] = s.value;
    if (mode != FolderMode::Resume) return now;
    std::error_code ec;
    if (!std::filesystem::exists(record, ec))
        throw UsageError("--resume: " + Quote(record.parent_path().string()) + " holds no " + record.filename().string() + ": it holds no run of this command");
    nlohmann::ordered_json saved;
    try {
        saved = ParseJson(ReadInputFile(record.string()), record.string());
    } catch (const nlohmann::ordered_json::exception&) {
        saved = nullptr;
    }
    for (const RunSetting& s : settings)
        if (!saved.is_object() || !saved.contains(s.key)) throw UsageError(Quote(record.string()) + " is damaged (no " + s.key + "); start afresh with --overwrite");
    for (const RunSetting& s : settings)
        if (s.given && s.value != saved[s.key])
            throw UsageError("--resume: " + s.option + " " + Quote(s.value.dump()) + " is not what " + Quote(record.parent_path().string()) +
                             " was started with (" + Quote(saved[s.key].dump()) + "); a resumed run keeps it (leave it out, or start afresh with --overwrite)");
    return saved;
}

}  // namespace app
