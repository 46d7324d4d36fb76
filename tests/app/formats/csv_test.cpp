// CSV fields as RFC 4180 has them, and numbers that read back as the same doubles.
#include "formats/csv.h"
#include "formats/table.h"
#include "support/errors.h"

#include <gtest/gtest.h>

#include <cmath>

TEST(Csv, QuotesWhatNeedsQuotingAndRoundTrips) {
    const std::vector<std::string> fields{"plain", "a,b", "say \"hi\"", "two\nlines", "", "cr\r"};
    std::vector<std::string> cells;
    for (const auto& f : fields) cells.push_back(app::CsvField(f));
    EXPECT_EQ(cells[0], "plain");
    EXPECT_EQ(cells[1], "\"a,b\"");
    EXPECT_EQ(cells[2], "\"say \"\"hi\"\"\"");
    const auto rows = app::ParseCsv(app::CsvRow(cells) + app::CsvRow({"1", "2"}));
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0], fields);
    EXPECT_EQ(rows[1], (std::vector<std::string>{"1", "2"}));
}

TEST(Csv, NumbersAreShortestRoundTripAndNonFiniteIsEmpty) {
    EXPECT_EQ(app::CsvNumber(4.1), "4.1");
    EXPECT_EQ(std::stod(app::CsvNumber(0.1 + 0.2)), 0.1 + 0.2);
    EXPECT_EQ(app::CsvNumber(NAN), "");
    EXPECT_EQ(app::CsvNumber(INFINITY), "");
}

// A table is read by column name, so a name may stand for one column only.
TEST(Table, AColumnNamedTwiceIsRefused) {
    EXPECT_THROW(app::Table({"evaluation", "fibre_angle_deg", "fibre_angle_deg"}), std::logic_error);
    try {
        app::Table::Parse("a,b,a\n1,2,3\n", "x.csv");
        ADD_FAILURE() << "a header naming a column twice was read";
    } catch (const app::UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("'a' twice"), std::string::npos) << e.what();
    }
    const app::Table ok = app::Table::Parse("a,b\n1,2\n", "y.csv");
    EXPECT_EQ(ok.Number(0, "b"), 2);
}
