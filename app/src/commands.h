// Subcommands of `actuator`. Each takes the arguments after its name and returns the exit code;
// bad input is thrown as UsageError and reported by main().
#pragma once

#include <string>

namespace app {

struct Command {
    const char* name;
    const char* summary;
    int (*run)(int argc, char** argv, int first);  // argv[first] is the first argument after the name
    std::string (*help)();
};

int RunSimulate(int argc, char** argv, int first);
std::string SimulateHelp();
int RunRender(int argc, char** argv, int first);
std::string RenderHelp();
int RunImgDiff(int argc, char** argv, int first);
int RunSweep(int argc, char** argv, int first);
std::string SweepHelp();
int RunEvolve(int argc, char** argv, int first);
std::string EvolveHelp();
int RunReproduce(int argc, char** argv, int first);
int RunInspect(int argc, char** argv, int first);
int RunServe(int argc, char** argv, int first);
std::string ServeHelp();
std::string InspectHelp();
std::string ReproduceHelp();
std::string ImgDiffHelp();

}  // namespace app
