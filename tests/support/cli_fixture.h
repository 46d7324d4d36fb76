// Runs the `actuator` binary as a user would, in a fresh temporary folder per test, and checks the
// contract for bad input: exit code 2, one line on stderr naming the problem, nothing on stdout.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

class CliTest : public ::testing::Test {
protected:
    struct Result {
        int exitCode = -1;
        std::string out, err;
    };

    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("actuator_test_" + std::to_string(getpid()) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string Path(const std::string& name) const { return (dir_ / name).string(); }

    static std::string Slurp(const std::filesystem::path& path) {
        std::ifstream in(path, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }

    void Write(const std::string& name, const std::string& contents) const { std::ofstream(Path(name), std::ios::binary) << contents; }

    // `environment` is put before the command, e.g. "PATH=/nowhere".
    Result Run(const std::string& args, const std::string& environment = "") const {
        const std::string command = environment + " " + ACTUATOR_BIN + " " + args + " > " + Path("stdout") + " 2> " + Path("stderr");
        const int status = std::system(command.c_str());
        return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, Slurp(dir_ / "stdout"), Slurp(dir_ / "stderr")};
    }

    void ExpectRefused(const std::string& args, const std::string& mentions) const {
        const Result r = Run(args);
        EXPECT_EQ(r.exitCode, 2) << "actuator " << args << "\nstderr: " << r.err;
        EXPECT_EQ(r.out, "") << "actuator " << args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "want one line, got: " << r.err;
        EXPECT_NE(r.err.find(mentions), std::string::npos) << "message should mention '" << mentions << "': " << r.err;
    }

    std::filesystem::path dir_;
};
