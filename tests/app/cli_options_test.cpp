#include "cli_options.h"

#include <gtest/gtest.h>

#include <numbers>

TEST(ParseNumber, AcceptsPlainNumbersAndMultiplesOfPi) {
    EXPECT_DOUBLE_EQ(app::ParseNumber("4.1", "x"), 4.1);
    EXPECT_DOUBLE_EQ(app::ParseNumber("-2e-3", "x"), -2e-3);
    EXPECT_DOUBLE_EQ(app::ParseNumber("pi", "x"), std::numbers::pi);
    EXPECT_DOUBLE_EQ(app::ParseNumber("4pi", "x"), 4 * std::numbers::pi);
    EXPECT_DOUBLE_EQ(app::ParseNumber("0.5*pi", "x"), 0.5 * std::numbers::pi);
    EXPECT_DOUBLE_EQ(app::ParseNumber("-pi", "x"), -std::numbers::pi);
    EXPECT_DOUBLE_EQ(app::ParseNumber("pi-0.5", "x"), std::numbers::pi - 0.5);
    EXPECT_DOUBLE_EQ(app::ParseNumber("-pi/2 + 1", "x"), -std::numbers::pi / 2 + 1);
    EXPECT_DOUBLE_EQ(app::ParseNumber("(8/3)pi", "x"), 8.0 / 3 * std::numbers::pi);
    EXPECT_DOUBLE_EQ(app::ParseNumber("1e-2", "x"), 0.01);
    EXPECT_DOUBLE_EQ(app::ParseNumber(" 7 ", "x"), 7);
}

TEST(ParseNumber, RefusesJunkAndNonFiniteValues) {
    for (const char* bad : {"", "abc", "4.1x", "nan", "inf", "-inf", "1e999", "pipi", "1/0", "0x10", "(1", "2*", "1e", "."})
        EXPECT_THROW(app::ParseNumber(bad, "--amplitude"), app::UsageError) << bad;
}

TEST(ParseInt, ChecksRange) {
    EXPECT_EQ(app::ParseInt("50", "--iterations", 0, 100), 50);
    EXPECT_EQ(app::ParseInt("0", "--iterations", 0, 100), 0);
    EXPECT_THROW(app::ParseInt("5000", "--iterations", 0, 100), app::UsageError);
    EXPECT_THROW(app::ParseInt("-5", "--iterations", 0, 100), app::UsageError);
    EXPECT_THROW(app::ParseInt("3.5", "--iterations", 0, 100), app::UsageError);
    EXPECT_THROW(app::ParseInt("99999999999999999999", "--iterations", 0, 100), app::UsageError);
}

TEST(ParseArgs, ReadsBothFormsAndRefusesUnknownOrRepeatedOptions) {
    const std::vector<app::OptionSpec> specs{{"shape", "NAME", "", ""}, {"help", "", "", ""}};
    const char* argv[] = {"actuator", "simulate", "--shape", "sine", "--help"};
    const auto parsed = app::ParseArgs(5, const_cast<char**>(argv), 2, specs, 0);
    EXPECT_EQ(parsed.Get("shape"), "sine");
    EXPECT_TRUE(parsed.Has("help"));
    const char* inlineForm[] = {"actuator", "simulate", "--shape=bspline"};
    EXPECT_EQ(app::ParseArgs(3, const_cast<char**>(inlineForm), 2, specs, 0).Get("shape"), "bspline");
    const char* repeated[] = {"actuator", "simulate", "--shape", "a", "--shape", "b"};
    EXPECT_THROW(app::ParseArgs(6, const_cast<char**>(repeated), 2, specs, 0), app::UsageError);
    const char* unknown[] = {"actuator", "simulate", "--colour", "red"};
    EXPECT_THROW(app::ParseArgs(4, const_cast<char**>(unknown), 2, specs, 0), app::UsageError);
}
