#include "commands/registry.h"

#include <algorithm>
#include <stdexcept>

namespace app {
namespace {

// Built on first use, so that registrations from any file's static initialisers find it constructed.
std::vector<Command>& Registry() {
    static std::vector<Command> commands;
    return commands;
}

}  // namespace

RegisterCommand::RegisterCommand(const Command& command) {
    std::vector<Command>& commands = Registry();
    for (const Command& c : commands)
        if (std::string(c.name) == command.name) throw std::logic_error(std::string("two commands named ") + command.name);
    commands.push_back(command);
    std::stable_sort(commands.begin(), commands.end(), [](const Command& a, const Command& b) { return a.place < b.place; });
}

const std::vector<Command>& Commands() { return Registry(); }

const Command* FindCommand(const std::string& name) {
    for (const Command& c : Registry())
        if (name == c.name) return &c;
    return nullptr;
}

}  // namespace app
