// Many evaluations on a pool of threads. Each job's result depends only on the job, never on the
// thread count or the order of completion.
#pragma once

#include <functional>
#include <vector>

#include "sim/model.h"
#include "sim/search.h"

namespace sim {

// Sweeps over jobs: a shape parameter lives in the job's shape, the pressure in its shell load.
double SweepValue(const EvalJob& job, SweepParameter parameter);
EvalJob WithSweepValue(EvalJob job, SweepParameter parameter, double value);
// The grid's jobs, row-major (the last axis varies fastest): `base` with def.base as its shape and
// each point's values set.
std::vector<EvalJob> SweepJobs(const SweepDef& def, const EvalJob& base);

// Called after each job finishes, from a worker thread, serialised: for progress lines.
using BatchProgress = std::function<void(int done, int total, const SimResult& finished)>;

// 0 threads means one per hardware core.
std::vector<SimResult> EvaluateBatch(const std::vector<EvalJob>& jobs, int threads, const BatchProgress& onDone = {});

int HardwareThreads();

// Runs task(i) for every i in [0, count) on `threads` workers (0: one per core; the calling thread is
// one), each index once, in no fixed order: a task writes only its own index's result.
void ParallelFor(int count, int threads, const std::function<void(int)>& task);

}  // namespace sim
