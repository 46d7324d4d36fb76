// Number expressions as users write them, and the limits that keep hostile text from crashing.
#include "support/number_expression.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

#include "support/errors.h"

using ::testing::HasSubstr;

namespace {

std::string Refusal(const std::string& text) {
    try {
        app::ParseNumber(text, "--x");
    } catch (const app::UsageError& error) {
        return error.what();
    }
    return "accepted";
}

}  // namespace

TEST(ParseNumber, AcceptsPlainNumbersAndMultiplesOfPi) {
    EXPECT_EQ(app::ParseNumber("4.1", "x"), 4.1);
    EXPECT_EQ(app::ParseNumber("-2.5e-3", "x"), -2.5e-3);
    EXPECT_EQ(app::ParseNumber("pi", "x"), std::numbers::pi);
    EXPECT_EQ(app::ParseNumber("4pi", "x"), 4 * std::numbers::pi);
    EXPECT_EQ(app::ParseNumber("pi-0.5", "x"), std::numbers::pi - 0.5);
    EXPECT_EQ(app::ParseNumber("0.5*pi", "x"), 0.5 * std::numbers::pi);
    EXPECT_EQ(app::ParseNumber("(8/3)pi", "x"), 8.0 / 3 * std::numbers::pi);
    EXPECT_EQ(app::ParseNumber("-pi/2", "x"), -std::numbers::pi / 2);
    EXPECT_EQ(app::ParseNumber(" 2 + 3 * 4 ", "x"), 14);
}

TEST(ParseNumber, RefusesJunkAndNonFiniteValuesNamingTheOption) {
    for (const char* junk : {"", "abc", "nan", "inf", "0x10", "1..2", "2pi pi", "(1", "1)", "1/0", "1e400"})
        EXPECT_THAT(Refusal(junk), HasSubstr("--x: '")) << junk;
}

TEST(ParseNumber, DeepNestingIsRefusedNotACrash) {
    EXPECT_THAT(Refusal(std::string(70000, '-') + "1"), HasSubstr("nests deeper than"));
    EXPECT_THAT(Refusal(std::string(300000, '(') + "1" + std::string(300000, ')')), HasSubstr("nests deeper than"));
    // A reasonable depth still works.
    EXPECT_EQ(app::ParseNumber(std::string(20, '(') + "1" + std::string(20, ')'), "x"), 1);
}

TEST(ParseNumber, MessagesQuoteAtMost80CharactersOfTheInput) {
    const std::string message = Refusal(std::string(10'000'000, '7') + "x");
    EXPECT_LT(message.size(), 200u);
    EXPECT_THAT(message, HasSubstr("(10000001 characters)"));
}

TEST(ParseInteger, ChecksRangeAndQuotesTheValueGiven) {
    EXPECT_EQ(app::ParseInteger("42", "--n", 0, 100), 42);
    EXPECT_EQ(app::ParseInteger("+7", "--n", 0, 100), 7);
    auto refusal = [](const std::string& text) {
        try {
            app::ParseInteger(text, "--n", 0, 100);
        } catch (const app::UsageError& error) {
            return std::string(error.what());
        }
        return std::string("accepted");
    };
    EXPECT_THAT(refusal("101"), HasSubstr("'101' is out of range (0 to 100)"));
    EXPECT_THAT(refusal("18446744073709551615"), HasSubstr("'18446744073709551615' is out of range"));
    EXPECT_THAT(refusal("1e3"), HasSubstr("not a whole number"));
    EXPECT_THAT(refusal("-"), HasSubstr("not a whole number"));
}

TEST(ParseNumberList, SplitsAndRefusesEmptyItems) {
    EXPECT_EQ(app::ParseNumberList("1,2,pi", "x"), (std::vector<double>{1, 2, std::numbers::pi}));
    EXPECT_THROW(app::ParseNumberList("1,,2", "x"), app::UsageError);
    EXPECT_THROW(app::ParseNumberList("1,2,", "x"), app::UsageError);
    EXPECT_THROW(app::ParseNumberList("", "x"), app::UsageError);
}
