// actuator: the Actuator Workbench command line. Dispatches to subcommands; turns bad input into one
// line on stderr and exit code 2, and output that could not be written into an error.
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>

#include "options/cli.h"
#include "commands/registry.h"
#include "support/errors.h"
#include "formats/files.h"

namespace {

std::string MainHelp() {
    std::string text = std::string("actuator ") + app::Version() +
                       "\n\nusage: actuator COMMAND [options]\n\n"
                       "Actuator Workbench: generative design of thin-walled soft pneumatic actuators (see README.md).\n\nCommands:\n";
    size_t width = 0;  // the names' column: the longest and two spaces
    for (const app::Command& c : app::Commands()) width = std::max(width, std::strlen(c.name) + 2);
    for (const app::Command& c : app::Commands()) text += "  " + std::string(c.name) + std::string(width - std::strlen(c.name), ' ') + c.summary + "\n";
    text += "\nRun 'actuator COMMAND --help' for a command's options and their defaults.\n"
            "Exit codes: 0 success, 2 bad input (one line on stderr says what and where), 3 every evaluation\n"
            "server (--workers) is gone, 70 an internal error (a bug: please report it), 74 the output could not\n"
            "be written (a full disk).\n";
    return text;
}

int Finish(int code, const std::string& name) {
    // Output that could not be written (a full disk, /dev/full, a closed pipe) is not a success.
    if (!app::CloseStdout()) {
        std::cerr << "actuator" << (name.empty() ? "" : " " + name) << ": error: could not write the output (" << std::strerror(errno) << ")\n";
        return code == 0 ? 74 : code;
    }
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    app::InstallInterruptCleanup();
    // A file-size limit (ulimit -f) makes a write fail with EFBIG, reported as output that could not
    // be written, instead of killing the process.
    signal(SIGXFSZ, SIG_IGN);
    if (argc < 2) {
        std::cerr << MainHelp();
        return 2;
    }
    const std::string name = argv[1];
    if (name == "--help" || name == "-h" || name == "help") {
        std::cout << MainHelp();
        return Finish(0, "");
    }
    if (name == "--version") {
        std::cout << "actuator " << app::Version() << "\n";
        return Finish(0, "");
    }
    if (const app::Command* command = app::FindCommand(name)) {
        try {
            return Finish(command->run(argc, argv, 2), name);
        } catch (const app::WorkersGone& error) {
            std::cerr << "actuator " << name << ": stopped: " << error.what() << "; continue later with --resume\n";
            return Finish(3, name);
        } catch (const app::OutputError& error) {
            std::cerr << "actuator " << name << ": error: could not write the output: " << error.what() << "\n";
            return Finish(74, name);
        } catch (const app::UsageError& error) {
            std::cerr << "actuator " << name << ": error: " << error.what() << "\n";
            return Finish(2, name);
        } catch (const std::bad_alloc&) {
            std::cerr << "actuator " << name << ": error: out of memory\n";
            return Finish(2, name);
        } catch (const std::exception& error) {
            std::cerr << "actuator " << name << ": internal error: " << error.what() << "\n";
            return Finish(70, name);
        }
    }
    std::cerr << "actuator: error: unknown command " << app::Quote(name) << " (run 'actuator --help' for the list)\n";
    return 2;
}
