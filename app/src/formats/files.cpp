#include "formats/files.h"

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <sstream>

#include "support/errors.h"
#include "support/number_expression.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// Temporaries in flight or staged in an OutputBatch, kept where a signal handler can reach them
// without allocating: each slot holds a heap copy of the path, published with one atomic store.
constexpr int kTemporarySlots = 4096;
std::array<std::atomic<char*>, kTemporarySlots> gTemporaries{};
std::atomic<void (*)()> gRestore{nullptr};
std::atomic<unsigned> gTemporaryCounter{0};

int Register(const std::string& path) {
    char* copy = strdup(path.c_str());
    if (!copy) return -1;
    for (int k = 0; k < kTemporarySlots; ++k) {
        char* expected = nullptr;
        if (gTemporaries[k].load() == nullptr && gTemporaries[k].compare_exchange_strong(expected, copy)) return k;
    }
    free(copy);
    return -1;  // more than 4,096 at once: this one is removed by the next run in its folder, not on a signal
}

void Unregister(int slot) {
    if (slot >= 0) free(gTemporaries[slot].exchange(nullptr));
}

// The open OutputBatch's files: written, waiting for their rename.
struct StagedFile {
    std::string temporary, target;
    int slot = -1;
};
std::mutex gBatchMutex;
std::vector<StagedFile>* gBatch = nullptr;

void OnInterrupt(int signal) {
    for (auto& slot : gTemporaries)
        if (const char* path = slot.load()) unlink(path);
    if (auto restore = gRestore.load()) restore();
    ::signal(signal, SIG_DFL);
    raise(signal);
}

std::string Reason() { return std::strerror(errno); }

}  // namespace

bool IsTemporaryName(const std::string& name) {
    return name.rfind(".act", 0) == 0 && name.size() > 8 && name.compare(name.size() - 4, 4, ".tmp") == 0;
}

std::string ReadInputFile(const std::string& path, std::uintmax_t maxBytes) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw UsageError("cannot open " + Quote(path) + ": " + Reason());
    struct stat info {};
    fstat(fd, &info);
    if (S_ISDIR(info.st_mode)) {
        ::close(fd);
        throw UsageError("cannot read " + Quote(path) + ": it is a folder");
    }
    if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode)) {
        // /dev/zero would fill memory: a device is not an input file.
        ::close(fd);
        throw UsageError("cannot read " + Quote(path) + ": it is a device, not a file");
    }
    auto tooLarge = [&] {
        ::close(fd);
        return UsageError(Quote(path) + " is larger than " + std::to_string(maxBytes >> 20) + " MiB, the limit for an input file");
    };
    if (S_ISREG(info.st_mode) && static_cast<std::uintmax_t>(info.st_size) > maxBytes) throw tooLarge();
    std::string contents;
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const std::string reason = Reason();
            ::close(fd);
            throw UsageError("cannot read " + Quote(path) + ": " + reason);
        }
        if (n == 0) break;
        contents.append(buffer, static_cast<size_t>(n));
        if (contents.size() > maxBytes) throw tooLarge();
    }
    ::close(fd);
    return contents;
}

std::vector<double> ReadNumberFile(const std::string& path) {
    std::vector<double> values;
    std::istringstream lines(ReadInputFile(path));
    std::string line;
    for (int lineNumber = 1; std::getline(lines, line); ++lineNumber) {
        if (auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream words(line);
        for (std::string word; words >> word;) values.push_back(ParseNumber(word, path + ":" + std::to_string(lineNumber)));
    }
    return values;
}

void CheckNewOrEmptyFolder(const std::string& folder, const std::string& what) {
    std::error_code ec;
    if (folder.empty()) throw UsageError(what + ": the folder's name is empty");
    if (fs::exists(folder, ec) && !(fs::is_directory(folder, ec) && fs::is_empty(folder, ec)))
        throw UsageError(what + " " + Quote(folder) + " exists and is not an empty folder; give a new or empty one");
}

void CheckOutputPath(const std::string& path, const std::string& what) {
    if (path.empty()) throw UsageError(what + ": empty file name");
    const fs::path target(path);
    if (target.filename().string().size() > NAME_MAX)
        throw UsageError(what + ": the file name " + Quote(target.filename().string()) + " is longer than " + std::to_string(NAME_MAX) + " bytes");
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(target, ec);
    if (fs::exists(status)) {
        if (fs::is_directory(status)) throw UsageError(what + ": " + Quote(path) + " is a folder");
        if (fs::is_symlink(status)) throw UsageError(what + ": " + Quote(path) + " is a symbolic link; give the file it points to, or another name");
        if (!fs::is_regular_file(status)) throw UsageError(what + ": " + Quote(path) + " is not a regular file (a device, pipe or socket); give a file name");
    }
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    if (!fs::is_directory(folder, ec)) throw UsageError(what + ": folder " + Quote(folder.string()) + " does not exist");
    if (access(folder.c_str(), W_OK) != 0) throw UsageError(what + ": cannot write in " + Quote(folder.string()));
}

void RefuseOutputThatIsInput(const std::string& output, const std::string& outputWhat, const std::vector<std::string>& inputs) {
    std::error_code ec;
    for (const std::string& input : inputs) {
        if (input.empty()) continue;
        const bool same = fs::exists(output, ec) && fs::exists(input, ec) ? fs::equivalent(output, input, ec)
                                                                         : fs::weakly_canonical(output, ec) == fs::weakly_canonical(input, ec);
        if (same) throw UsageError(outputWhat + ": " + Quote(output) + " is also an input of this command; write to another file");
    }
}

std::string FolderNameError(const std::string& name) {
    if (name.empty()) return "is empty";
    if (name == "." || name == "..") return "is " + Quote(name) + ", which names no folder of its own";
    if (name.size() > 100) return "is longer than 100 bytes";
    for (const unsigned char c : name) {
        if (c == '/' || c == '\\') return "contains " + Quote(std::string(1, static_cast<char>(c))) + ", a path separator";
        if (c < 0x20 || c == 0x7f) return "contains a control character";
    }
    return "";
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
    CheckOutputPath(path, "cannot write " + Quote(path));
    const fs::path target(path);
    const std::string temporary =
        (target.parent_path() / (".act" + std::to_string(getpid()) + "-" + std::to_string(gTemporaryCounter++) + ".tmp")).string();
    const int slot = Register(temporary);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int code = errno;
        Unregister(slot);
        ThrowWriteError("cannot write " + Quote(path), code);
    }
    size_t written = 0;
    int code = 0;
    while (written < contents.size()) {
        const ssize_t n = ::write(fd, contents.data() + written, contents.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            code = n < 0 ? errno : ENOSPC;
            break;
        }
        written += static_cast<size_t>(n);
    }
    if (code == 0 && fsync(fd) != 0) code = errno;
    if (::close(fd) != 0 && code == 0) code = errno;
    if (code == 0) {
        std::lock_guard lock(gBatchMutex);
        if (gBatch) {
            gBatch->push_back({temporary, path, slot});
            return;
        }
    }
    if (code == 0 && std::rename(temporary.c_str(), path.c_str()) != 0) code = errno;
    if (code != 0) {
        unlink(temporary.c_str());
        Unregister(slot);
        ThrowWriteError("cannot write " + Quote(path), code);
    }
    Unregister(slot);
}

OutputBatch::OutputBatch() {
    std::lock_guard lock(gBatchMutex);
    if (gBatch) throw std::logic_error("one OutputBatch at a time");
    gBatch = new std::vector<StagedFile>;
}

OutputBatch::~OutputBatch() {
    std::lock_guard lock(gBatchMutex);
    if (!gBatch) return;
    for (const StagedFile& f : *gBatch) {
        unlink(f.temporary.c_str());
        Unregister(f.slot);
    }
    delete gBatch;
    gBatch = nullptr;
}

void OutputBatch::Commit() {
    std::lock_guard lock(gBatchMutex);
    std::vector<StagedFile> files = std::move(*gBatch);
    delete gBatch;
    gBatch = nullptr;
    // A rename within a folder needs no space; should one fail all the same, what was renamed goes
    // again, so that none of the batch appears.
    size_t renamed = 0;
    int code = 0;
    for (; renamed < files.size() && code == 0; ++renamed)
        if (std::rename(files[renamed].temporary.c_str(), files[renamed].target.c_str()) != 0) code = errno;
    for (size_t k = 0; k < files.size(); ++k) {
        if (code != 0) unlink(k < renamed - 1 ? files[k].target.c_str() : files[k].temporary.c_str());
        Unregister(files[k].slot);
    }
    if (code != 0) ThrowWriteError("cannot write " + Quote(files[renamed - 1].target), code);
}

void CreatedFolders::Create(const fs::path& folder, const std::string& what) {
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path p = folder; !p.empty() && !fs::exists(fs::symlink_status(p, ec)); p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path()) break;
    }
    fs::create_directories(folder, ec);
    if (!fs::is_directory(folder, ec)) throw UsageError(what + ": cannot create folder " + Quote(folder.string()));
    created_.insert(created_.end(), missing.rbegin(), missing.rend());
}

CreatedFolders::~CreatedFolders() {
    std::error_code ec;
    for (auto it = created_.rbegin(); it != created_.rend(); ++it)
        if (fs::is_empty(*it, ec)) fs::remove(*it, ec);
}

void InstallInterruptCleanup() {
    struct sigaction action {};
    action.sa_handler = OnInterrupt;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

void SetInterruptRestore(void (*restore)()) { gRestore.store(restore); }

void RemoveStaleTemporaries(const fs::path& folder) {
    std::error_code ec;
    for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!IsTemporaryName(name)) continue;
        const long pid = std::strtol(name.c_str() + 4, nullptr, 10);
        if (pid > 0 && pid != getpid() && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove(it->path(), ec);
    }
}

bool CloseStdout() {
    const bool flushed = std::fflush(stdout) == 0 && !std::ferror(stdout);
    return std::fclose(stdout) == 0 && flushed;
}

}  // namespace app
