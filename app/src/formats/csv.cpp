#include "formats/csv.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "support/errors.h"

namespace app {

std::string CsvField(std::string_view text) {
    if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
    std::string out = "\"";
    for (char c : text) {
        if (c == '"') out += '"';
        out += c;
    }
    return out + "\"";
}

std::string CsvNumber(double value) { return std::isfinite(value) ? fmt::format("{}", value) : std::string(); }

std::string CsvRow(const std::vector<std::string>& fields) {
    std::string row;
    for (size_t k = 0; k < fields.size(); ++k) row += (k ? "," : "") + fields[k];
    return row + "\n";
}

std::vector<std::vector<std::string>> ParseCsv(std::string_view text) {
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> row;
    std::string field;
    bool quoted = false, any = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                field += c;
            }
            continue;
        }
        any = true;
        if (c == '"') quoted = true;
        else if (c == ',') row.push_back(std::move(field)), field.clear();
        else if (c == '\n') {
            row.push_back(std::move(field));
            field.clear();
            rows.push_back(std::move(row));
            row.clear();
            any = false;
        } else if (c != '\r') field += c;
    }
    if (any || !field.empty()) {
        row.push_back(std::move(field));
        rows.push_back(std::move(row));
    }
    return rows;
}

CsvLog::CsvLog(const std::string& path, const std::vector<std::string>& header) : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) throw UsageError("cannot open " + Quote(path) + ": " + std::strerror(errno));
    struct stat info {};
    fstat(fd_, &info);
    if (!S_ISREG(info.st_mode)) {
        ::close(fd_);
        fd_ = -1;
        throw UsageError(Quote(path) + " is not a regular file");
    }
    if (info.st_size == 0) {
        std::vector<std::string> fields;
        for (const auto& h : header) fields.push_back(CsvField(h));
        Append(fields);
    }
}

CsvLog::~CsvLog() {
    if (fd_ >= 0) ::close(fd_);
}

CsvLog::CsvLog(CsvLog&& other) noexcept : path_(std::move(other.path_)), fd_(other.fd_) { other.fd_ = -1; }

CsvLog& CsvLog::operator=(CsvLog&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        path_ = std::move(other.path_);
        fd_ = other.fd_;
        other.fd_ = -1;
    }
    return *this;
}

void CsvLog::Append(const std::vector<std::string>& fields) {
    const std::string row = CsvRow(fields);
    const off_t before = lseek(fd_, 0, SEEK_END);
    size_t written = 0;
    while (written < row.size()) {
        const ssize_t n = ::write(fd_, row.data() + written, row.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            // A part of a row is taken back: the log stays whole rows.
            const int code = n < 0 ? errno : ENOSPC;
            if (before >= 0 && ftruncate(fd_, before) != 0) {}
            ThrowWriteError("cannot write " + Quote(path_), code);
        }
        written += static_cast<size_t>(n);
    }
}

}  // namespace app
