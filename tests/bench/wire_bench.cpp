// Cost of sending one evaluation over the wire (to a server, or through a Python map): encoding a
// response (result plus the initial and final 30x30 meshes at full precision) into bytes, and
// decoding it back; and the C++ cost of an evaluation with no relaxation, the baseline of
// tests/bench/python_bench.py's per-call overhead.
//   build/tests/wire_bench
#include <benchmark/benchmark.h>
#include <malloc.h>

#include "formats/schema_convert.h"
#include "sim/batch.h"

namespace {

const sim::SimResult& Sample() {
    static const sim::SimResult result = [] {
        sim::SimParams params = sim::DefaultSimParams();
        params.iterations = 100;
        return sim::Evaluate(sim::SineShape{4.1, 0.5, 2.64}, sim::DefaultMeshDef(), params);
    }();
    return result;
}

void BM_EncodeResponse(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(app::ResultBytes(Sample(), sim::ModelKind::Thesis).size());
    state.counters["bytes"] = static_cast<double>(app::ResultBytes(Sample(), sim::ModelKind::Thesis).size());
}

void BM_DecodeResponse(benchmark::State& state) {
    const std::string bytes = app::ResultBytes(Sample(), sim::ModelKind::Thesis);
    for (auto _ : state) benchmark::DoNotOptimize(app::ResultFromBytes(bytes).final.x.data());
}

// The C++ side of one Python evaluate() call with no relaxation: building the helix, shaping it and
// the result's meshes. tests/bench/python_bench.py times the same call from Python.
void BM_EvaluateZeroIterations(benchmark::State& state) {
    sim::EvalJob job;
    job.shape = sim::SineShape{4.1, 0.5, 2.64};
    job.Thesis().params = sim::DefaultSimParams();
    job.Thesis().params.iterations = 0;
    job.Thesis().mesh = sim::DefaultMeshDef();
    // glibc gives the top of the heap back after each call unless the trim threshold was raised, as
    // it is in a process that has freed a large block (the Python interpreter has; so has this
    // program after BM_EncodeResponse). Raised here, so the figure does not depend on which
    // benchmarks ran first: 26 us against 50 us with a page fault per page each call.
    mallopt(M_TRIM_THRESHOLD, 64 << 20);
    for (auto _ : state) benchmark::DoNotOptimize(sim::Evaluate(job).final.x.data());
}

}  // namespace

BENCHMARK(BM_EncodeResponse)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DecodeResponse)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_EvaluateZeroIterations)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
