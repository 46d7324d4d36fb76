// actuator: the Actuator Workbench command line. Dispatches to subcommands; turns bad input into one
// line on stderr and exit code 2.
#include <cstring>
#include <exception>
#include <iostream>

#include "cli_options.h"
#include "commands.h"
#include "remote.h"

namespace {

const app::Command kCommands[] = {
    {"simulate", "evaluate one shape and print its fitness as JSON", app::RunSimulate, app::SimulateHelp},
    {"render", "pictures of one shape: before/after, stretch, turntable, time-lapse", app::RunRender, app::RenderHelp},
    {"sweep", "evaluate an experiment's grid of sine shapes; landscape figure", app::RunSweep, app::SweepHelp},
    {"evolve", "run an experiment's genetic algorithm; logbooks, checkpoints, figures", app::RunEvolve, app::EvolveHelp},
    {"reproduce", "run every thesis experiment and write report.md with figures", app::RunReproduce, app::ReproduceHelp},
    {"inspect", "list or filter the evaluations in an archive (evaluations.capnp)", app::RunInspect, app::InspectHelp},
    {"serve", "run an evaluation server for --workers (Cap'n Proto RPC)", app::RunServe, app::ServeHelp},
    {"imgdiff", "compare two PNG images with a tolerance (exit 0 match, 1 differ)", app::RunImgDiff, app::ImgDiffHelp},
};

std::string MainHelp() {
    std::string text =
        "usage: actuator COMMAND [options]\n\n"
        "Actuator Workbench: generative design of thin-walled soft pneumatic actuators (mass-spring\n"
        "model of the 2019 thesis; see README.md).\n\nCommands:\n";
    for (const auto& c : kCommands) text += "  " + std::string(c.name) + std::string(12 - std::strlen(c.name), ' ') + c.summary + "\n";
    text += "\nRun 'actuator COMMAND --help' for a command's options and their defaults.\n"
            "Exit codes: 0 success, 2 bad input (one line on stderr says what and where), 3 every evaluation\n"
            "server (--workers) is gone.\n";
    return text;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << MainHelp();
        return 2;
    }
    const std::string name = argv[1];
    if (name == "--help" || name == "-h" || name == "help") {
        std::cout << MainHelp();
        return 0;
    }
    for (const auto& command : kCommands) {
        if (name != command.name) continue;
        try {
            return command.run(argc, argv, 2);
        } catch (const app::WorkersGone& error) {
            std::cerr << "actuator " << name << ": stopped: " << error.what()
                      << "; a GA run keeps its checkpoint (continue with actuator evolve --resume DIR)\n";
            return 3;
        } catch (const app::UsageError& error) {
            std::cerr << "actuator " << name << ": error: " << error.what() << "\n";
            return 2;
        } catch (const std::bad_alloc&) {
            std::cerr << "actuator " << name << ": error: out of memory\n";
            return 2;
        } catch (const std::exception& error) {
            std::cerr << "actuator " << name << ": internal error: " << error.what() << "\n";
            return 70;
        }
    }
    std::cerr << "actuator: error: unknown command '" << name << "' (run 'actuator --help' for the list)\n";
    return 2;
}
