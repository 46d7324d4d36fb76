// Running programs from tests: a command line through the shell with its exit code and output, and
// a child process that can be killed at a chosen moment (SIGKILL-and-resume tests, servers).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace testing_support {

inline std::string Slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

struct RunResult {
    int exitCode = -1;  // -1: killed by a signal
    std::string out, err;
};

// `command` runs through /bin/sh (so quotes and redirections work); stdout and stderr are captured
// through files in `scratch`.
inline RunResult RunShell(const std::string& command, const std::filesystem::path& scratch) {
    const auto out = scratch / ".stdout", err = scratch / ".stderr";
    const std::string line = "(" + command + ") > '" + out.string() + "' 2> '" + err.string() + "'";
    const int status = std::system(line.c_str());
    RunResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, Slurp(out), Slurp(err)};
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

// Polls `done` every 5 ms for at most `seconds`.
inline bool WaitUntil(const std::function<bool()>& done, double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until) {
        if (done()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return done();
}

// A child process with stdout and stderr sent to files (or /dev/null); killed when destroyed.
class Child {
public:
    Child(const std::vector<std::string>& args, const std::string& stdoutPath = "/dev/null", const std::string& stderrPath = "/dev/null") {
        std::vector<std::string> copy = args;
        std::vector<char*> argv;
        for (auto& a : copy) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 1, stdoutPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_addopen(&actions, 2, stderrPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (posix_spawn(&pid_, copy[0].c_str(), &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
        posix_spawn_file_actions_destroy(&actions);
    }
    ~Child() { Kill(SIGKILL); }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;

    pid_t Pid() const { return pid_; }
    bool Running() const { return pid_ > 0 && waitpid(pid_, nullptr, WNOHANG) == 0; }
    // Sends `signal` and waits; returns the wait status (or -1 when already reaped).
    int Kill(int signal) {
        if (pid_ <= 0) return -1;
        ::kill(pid_, signal);
        return Wait();
    }
    int Wait() {
        if (pid_ <= 0) return -1;
        int status = 0;
        waitpid(pid_, &status, 0);
        pid_ = -1;
        return status;
    }

private:
    pid_t pid_ = -1;
};

}  // namespace testing_support
