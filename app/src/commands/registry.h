// The commands of `actuator`: each cmd_*.cpp registers its own at start-up, and main() (and the
// tests that run a command in process) find them here by name. Adding a command is one file:
// docs/architecture.md shows it.
#pragma once

#include <string>
#include <vector>

namespace app {

struct Command {
    const char* name;     // as typed: `actuator NAME`
    const char* summary;  // one line in `actuator --help`
    int place;            // where `actuator --help` lists it: lower first
    // Takes the arguments after the name (argv[first] is the first of them) and returns the exit
    // code; bad input is thrown as UsageError, which main() reports with exit code 2.
    int (*run)(int argc, char** argv, int first);
};

// `static const RegisterCommand registered{{"simulate", "...", 10, RunSimulate}};` in a command's file.
struct RegisterCommand {
    explicit RegisterCommand(const Command& command);
};

// Every registered command, in `place` order.
const std::vector<Command>& Commands();
// The command of that name, or null.
const Command* FindCommand(const std::string& name);

}  // namespace app
