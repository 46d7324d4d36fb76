// The pagmo optimizers as a run-time module, libactuator_optimizer.so. pagmo and what it brings
// (Boost.Serialization, TBB) take some 65 ms of CPU to load and initialise: linked into `actuator`,
// every process paid it before any work, `--help` and a thesis `simulate` included. As a module it is
// mapped the first time an optimizer runs (app: LoadOptimizerModule), like the GL backends.
#pragma once

#include <cstdint>

#include "sim/optimize.h"

namespace sim {

constexpr int kOptimizerModuleAbiVersion = 1;

// RunOptimizer (optimize.h) as the module runs it.
OptimizerRun RunPagmoOptimizer(const OptimizerDef& def, const MeshDef& mesh, std::uint64_t seed, const VectorEvaluator& evaluate,
                               const GenerationHook& onGeneration);

// What the module gives.
struct OptimizerModuleApi {
    int abiVersion;  // kOptimizerModuleAbiVersion of the module's build
    OptimizerRun (*runOptimizer)(const OptimizerDef& def, const MeshDef& mesh, std::uint64_t seed, const VectorEvaluator& evaluate,
                                 const GenerationHook& onGeneration);
};

}  // namespace sim

// The module's one exported symbol.
extern "C" const sim::OptimizerModuleApi* actuator_optimizer_module();
