// The workbench's run-time modules: the GL backends (render) and the optimizers (sim's pagmo part).
// Each is a shared object loaded with dlopen the first time a command needs it, so that a command
// that draws nothing or optimises nothing never maps OpenGL, LLVM or pagmo. Searched, in order:
// $ACTUATOR_MODULE_DIR, the install layout beside the running binary (bin/../lib/actuator), the
// Python module's folders (beside it, actuator.libs/), the build tree, the install prefix.
#pragma once

#include <string>

namespace sim {

// Loads the module `file` (for example "libactuator_optimizer.so") from the first folder that holds
// it and returns its entry point `symbol` (C linkage). Null with *error set (naming `what` and the
// folders looked in) when no folder has it or it does not load. Loaded modules stay mapped.
void* OpenModuleEntry(const std::string& file, const char* symbol, const std::string& what, std::string* error);

}  // namespace sim
