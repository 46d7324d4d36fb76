// A table with named columns: what results.csv, logbook.csv, comparison.csv and the Pareto fronts
// are. Written through one writer (Csv) and read back by column name, never by position: a column
// added or moved cannot make a reader take one quantity for another.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace app {

class Table {
public:
    Table() = default;
    explicit Table(std::vector<std::string> columns);

    // A row of fields as they are to be read back (numbers formatted with CsvNumber, so that they
    // read back as the same double); as many as there are columns.
    void AddRow(std::vector<std::string> fields);
    // The table as CSV (RFC 4180), header first.
    std::string Csv() const;

    // Reads CSV text whose first row names the columns. `source` names it in messages (a path).
    // Throws UsageError for a table without a header or with rows of another width.
    static Table Parse(std::string_view text, const std::string& source);
    static Table Read(const std::string& path);

    const std::vector<std::string>& Columns() const { return columns_; }
    size_t Rows() const { return rows_.size(); }
    bool Has(std::string_view column) const;
    // The field of `row` in the named column. Throws UsageError naming the table and the column
    // when there is no such column.
    const std::string& Text(size_t row, std::string_view column) const;
    // The same, as a number: an empty field is NaN, text that is not a number is a UsageError.
    double Number(size_t row, std::string_view column) const;
    // The whole column as numbers.
    std::vector<double> Numbers(std::string_view column) const;

private:
    size_t Index(std::string_view column) const;

    std::string source_;
    std::vector<std::string> columns_;
    std::vector<std::vector<std::string>> rows_;
};

}  // namespace app
