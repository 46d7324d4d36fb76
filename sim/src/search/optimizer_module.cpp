// The entry point of libactuator_optimizer.so (sim/optimizer_module.h): everything else in the
// module is hidden, so its copies of sim's functions never stand in for the loading program's.
#include "sim/optimizer_module.h"

extern "C" __attribute__((visibility("default"))) const sim::OptimizerModuleApi* actuator_optimizer_module() {
    static const sim::OptimizerModuleApi api{sim::kOptimizerModuleAbiVersion, &sim::RunPagmoOptimizer};
    return &api;
}
