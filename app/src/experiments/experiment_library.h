// Where experiment files are found: a path as given, else a name (with or without .json) among the
// shipped experiments, in the source tree this was built from or where `cmake --install` put them
// (share/actuator/experiments), subfolders included. `actuator sweep SF1_fibre_angle_sweep` works
// from any folder.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace app {

// The folders of shipped experiments that exist on this machine, source tree first.
std::vector<std::filesystem::path> ExperimentFolders();

// The file `given` names. Throws UsageError saying where it looked when there is none, and naming
// the candidates when a name matches more than one file.
std::filesystem::path FindExperimentFile(const std::string& given);

}  // namespace app
