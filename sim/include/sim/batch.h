// Many evaluations on a pool of threads. Each job's result depends only on the job, never on the
// thread count or the order of completion.
#pragma once

#include <functional>
#include <vector>

#include "sim/search.h"
#include "sim/shell.h"
#include "sim/solver.h"

namespace sim {

// One evaluation: a design under a model. The thesis model reads `mesh` and `params`; the membrane
// and shell models read `shell`.
struct EvalJob {
    Shape shape;
    MeshDef mesh;
    SimParams params;
    ModelKind model = ModelKind::Thesis;
    ShellDef shell;
};

// The job's evaluation under its model.
SimResult Evaluate(const EvalJob& job);
// Empty when the job can be evaluated; otherwise what is wrong (shape, parameters, mesh).
std::string JobError(const EvalJob& job);
// The triangles and edges a job's meshes are drawn with.
Surface SurfaceOf(const EvalJob& job);

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

}  // namespace sim
