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

// Called after each job finishes, from a worker thread, serialised: for progress lines.
using BatchProgress = std::function<void(int done, int total, const SimResult& finished)>;

// 0 threads means one per hardware core.
std::vector<SimResult> EvaluateBatch(const std::vector<EvalJob>& jobs, int threads, const BatchProgress& onDone = {});

int HardwareThreads();

}  // namespace sim
