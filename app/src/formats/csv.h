// CSV as RFC 4180 has it: a field with a comma, quote or line break is quoted, its quotes doubled.
// Numbers are written with the shortest text that reads back as the same double; a non-finite
// number is an empty field. Rows are appended to a log with one write() each, so a run cut off at
// any moment leaves whole rows.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace app {

std::string CsvField(std::string_view text);
std::string CsvNumber(double value);
// One row with its line ending, each field already formatted (CsvField or CsvNumber).
std::string CsvRow(const std::vector<std::string>& fields);

// The fields of one line of CSV text (for tests and resume).
std::vector<std::vector<std::string>> ParseCsv(std::string_view text);

// An append-only CSV file: the header is written when the file is created.
class CsvLog {
public:
    CsvLog() = default;
    // Opens `path` for appending; a missing or empty file gets `header` first. Throws UsageError.
    CsvLog(const std::string& path, const std::vector<std::string>& header);
    ~CsvLog();
    CsvLog(CsvLog&& other) noexcept;
    CsvLog& operator=(CsvLog&& other) noexcept;

    void Append(const std::vector<std::string>& fields);
    bool IsOpen() const { return fd_ >= 0; }

private:
    std::string path_;
    int fd_ = -1;
};

}  // namespace app
