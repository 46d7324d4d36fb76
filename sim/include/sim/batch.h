// Many evaluations on a pool of threads. Each job's result depends only on the job, never on the
// thread count or the order of completion.
#pragma once

#include <functional>
#include <vector>

#include "sim/solver.h"

namespace sim {

struct EvalJob {
    Shape shape;
    MeshDef mesh;
    SimParams params;
};

// 0 threads means one per hardware core. onDone (optional) is called after each job finishes,
// from a worker thread, serialised; use it for progress lines.
std::vector<SimResult> EvaluateBatch(const std::vector<EvalJob>& jobs, int threads,
                                     const std::function<void(int done, int total)>& onDone = {});

int HardwareThreads();

}  // namespace sim
