// Subcommands of `actuator`. Each takes the arguments after its name and returns the exit code;
// bad input is thrown as UsageError and reported by main().
#pragma once

namespace app {

int RunSimulate(int argc, char** argv, int first);
int RunRender(int argc, char** argv, int first);
int RunSweepCommand(int argc, char** argv, int first);
int RunEvolveCommand(int argc, char** argv, int first);
int RunReproduce(int argc, char** argv, int first);
int RunCompare(int argc, char** argv, int first);
int RunInspect(int argc, char** argv, int first);
int RunServe(int argc, char** argv, int first);
int RunImgDiff(int argc, char** argv, int first);
int RunExport(int argc, char** argv, int first);

}  // namespace app
