// Speed of one evaluation: the thesis's 30x30 mesh, 10,000 iterations, one thread.
//   build/tests/actuator_bench --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
// The VM this runs on is noisy: read the min (and median), not the mean.
#include <benchmark/benchmark.h>

#include <numbers>

#include "reference_solver.h"
#include "sim/solver.h"

namespace {

const sim::SineShape kShape{4.1, 0.5, std::numbers::pi - 0.5};

void BM_Evaluate(benchmark::State& state, sim::Precision precision, sim::Load load) {
    sim::SimParams params = sim::DefaultSimParams();
    params.precision = precision;
    params.load = load;
    for (auto _ : state) benchmark::DoNotOptimize(sim::Evaluate(kShape, sim::DefaultMeshDef(), params).fitness);
    state.counters["springs/s"] = benchmark::Counter(3508.0 * params.iterations, benchmark::Counter::kIsIterationInvariantRate);
}

// The straightforward edge-list implementation in doubles (tests/support): the baseline.
void BM_NaiveEdgeListDouble(benchmark::State& state) {
    const sim::MeshDef def = sim::DefaultMeshDef();
    const sim::Positions initial = sim::BuildInitialPositions(kShape, def);
    for (auto _ : state) benchmark::DoNotOptimize(reference::Relax(initial, def, sim::DefaultSimParams()).z[0]);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Evaluate, float_inflate, sim::Precision::Float, sim::Load::Inflate)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Evaluate, float_stretch, sim::Precision::Float, sim::Load::Stretch)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Evaluate, double_inflate, sim::Precision::Double, sim::Load::Inflate)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NaiveEdgeListDouble)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
