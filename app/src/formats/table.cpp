#include "formats/table.h"

#include <cmath>
#include <stdexcept>

#include "formats/csv.h"
#include "support/errors.h"
#include "formats/files.h"

namespace app {

namespace {

// A column named twice would make a read by name mean one of two things.
std::string ColumnNamedTwice(const std::vector<std::string>& columns) {
    for (size_t a = 0; a < columns.size(); ++a)
        for (size_t b = a + 1; b < columns.size(); ++b)
            if (columns[a] == columns[b]) return columns[a];
    return "";
}

}  // namespace

Table::Table(std::vector<std::string> columns) : columns_(std::move(columns)) {
    if (const std::string twice = ColumnNamedTwice(columns_); !twice.empty()) throw std::logic_error("a table with two columns named " + twice);
}

void Table::AddRow(std::vector<std::string> fields) {
    if (fields.size() != columns_.size())
        throw std::logic_error("a row of " + std::to_string(fields.size()) + " fields in a table of " + std::to_string(columns_.size()) + " columns");
    rows_.push_back(std::move(fields));
}

std::string Table::Csv() const {
    auto line = [](const std::vector<std::string>& fields) {
        std::vector<std::string> quoted;
        quoted.reserve(fields.size());
        for (const auto& f : fields) quoted.push_back(CsvField(f));
        return CsvRow(quoted);
    };
    std::string text = line(columns_);
    for (const auto& row : rows_) text += line(row);
    return text;
}

Table Table::Parse(std::string_view text, const std::string& source) {
    auto rows = ParseCsv(text);
    if (rows.empty()) throw UsageError(Quote(source) + " is empty: a table needs a header row naming its columns");
    if (const std::string twice = ColumnNamedTwice(rows.front()); !twice.empty())
        throw UsageError(Quote(source) + " names the column " + Quote(twice) + " twice: a table is read by column name");
    Table table(std::move(rows.front()));
    table.source_ = source;
    for (size_t k = 1; k < rows.size(); ++k) {
        if (rows[k].size() != table.columns_.size())
            throw UsageError(Quote(source) + ": row " + std::to_string(k + 1) + " has " + std::to_string(rows[k].size()) + " fields, the header " +
                             std::to_string(table.columns_.size()));
        table.rows_.push_back(std::move(rows[k]));
    }
    return table;
}

Table Table::Read(const std::string& path) { return Parse(ReadInputFile(path), path); }

bool Table::Has(std::string_view column) const {
    for (const auto& c : columns_)
        if (c == column) return true;
    return false;
}

size_t Table::Index(std::string_view column) const {
    for (size_t k = 0; k < columns_.size(); ++k)
        if (columns_[k] == column) return k;
    throw UsageError(Quote(source_.empty() ? "the table" : source_) + " has no column " + Quote(column));
}

const std::string& Table::Text(size_t row, std::string_view column) const { return rows_.at(row)[Index(column)]; }

double Table::Number(size_t row, std::string_view column) const {
    const std::string& field = Text(row, column);
    if (field.empty()) return NAN;
    size_t used = 0;
    double value = NAN;
    try {
        value = std::stod(field, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != field.size())
        throw UsageError(Quote(source_) + ": row " + std::to_string(row + 2) + ", column " + Quote(column) + ": " + Quote(field) + " is not a number");
    return value;
}

std::vector<double> Table::Numbers(std::string_view column) const {
    std::vector<double> values;
    values.reserve(rows_.size());
    for (size_t row = 0; row < rows_.size(); ++row) values.push_back(Number(row, column));
    return values;
}

}  // namespace app
