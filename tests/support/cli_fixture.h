// Runs the `actuator` binary as a user would, in a fresh temporary folder per test, and checks the
// contract for bad input: exit code 2, one line on stderr naming the problem, nothing on stdout.
// Failures point at the calling line (std::source_location).
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <source_location>
#include <string>

#include "png.h"
#include "process.h"
#include "temp_folder.h"

class CliTest : public ::testing::Test {
protected:
    using Result = testing_support::RunResult;

    CliTest() : folder_(::testing::UnitTest::GetInstance()->current_test_info()->name()), dir_(folder_.Path()) {}

    std::string Path(const std::string& name) const { return (dir_ / name).string(); }
    static std::string Slurp(const std::filesystem::path& path) { return testing_support::Slurp(path); }
    void Write(const std::string& name, const std::string& contents) const { std::ofstream(Path(name), std::ios::binary) << contents; }

    // `environment` is put before the command, e.g. "PATH=/nowhere".
    Result Run(const std::string& args, const std::string& environment = "") const {
        return testing_support::RunShell(environment + " " + ACTUATOR_BIN + " " + args, dir_);
    }

    void ExpectRefused(const std::string& args, const std::string& mentions, std::source_location where = std::source_location::current()) const {
        const Result r = Run(args);
        const ::testing::ScopedTrace trace(where.file_name(), static_cast<int>(where.line()), "actuator " + args);
        EXPECT_EQ(r.exitCode, 2) << "stderr: " << r.err;
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "want one line, got: " << r.err;
        EXPECT_THAT(r.err, ::testing::HasSubstr(mentions));
    }

    testing_support::TempFolder folder_;
    std::filesystem::path dir_;
};
