// Speed of the membrane and shell models (issues 10 and 11): one evaluation of a thesis-sized design (the
// 4.1 sine at A = 1.3, R = 5 mm, L = 150 mm, 3 kPa in 4 load steps, Ecoflex 00-30) at 30 x 30,
// 60 x 60 and 120 x 120, beside the thesis model's evaluation measured in the same run, on one core.
// The counters give the Newton iterations and factorisations per evaluation.
//   build/tests/shell_bench --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <numbers>

#include "sim/batch.h"

namespace {

sim::EvalJob Job(sim::ModelKind model, int ringVertices, int rings) {
    sim::EvalJob job;
    job.model = model;
    job.shape = sim::SineShape{1.3, 0.5, std::numbers::pi - 0.5};
    job.shell.geometry.ringVertices = ringVertices;
    job.shell.geometry.rings = rings;
    return job;
}

void BM_Thesis30x30(benchmark::State& state) {
    const sim::EvalJob job{sim::SineShape{4.1, 0.5, std::numbers::pi - 0.5}, sim::DefaultMeshDef(), sim::DefaultSimParams()};
    for (auto _ : state) benchmark::DoNotOptimize(sim::Evaluate(job).fitness);
}

void BM_Shell(benchmark::State& state, sim::ModelKind model, sim::FibreLayout fibres) {
    const int n = static_cast<int>(state.range(0));
    sim::EvalJob job = Job(model, n, n);
    job.shell.fibres.layout = fibres;  // braid at the default 30 degrees, 50 N/mm
    sim::SimResult last;
    for (auto _ : state) {
        last = sim::Evaluate(job);
        benchmark::DoNotOptimize(last.fitness);
    }
    if (last.status != sim::Status::Ok) state.SkipWithError(sim::Name(last.status));
    state.counters["newton_iterations"] = last.shell.newtonIterations;
    state.counters["factorizations"] = last.shell.factorizations;
    state.counters["contraction_percent"] = last.contractionPercent;
}

}  // namespace

BENCHMARK(BM_Thesis30x30)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Shell, membrane, sim::ModelKind::Membrane, sim::FibreLayout::None)->Arg(30)->Arg(60)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Shell, shell, sim::ModelKind::Shell, sim::FibreLayout::None)->Arg(30)->Arg(60)->Unit(benchmark::kMillisecond)->MinTime(2);
// What fibres cost (issue 11: at most 30 % more).
BENCHMARK_CAPTURE(BM_Shell, shell_braid, sim::ModelKind::Shell, sim::FibreLayout::Braid)->Arg(30)->Arg(60)->Unit(benchmark::kMillisecond)->MinTime(2);
// 120 x 120 once each (seconds: the first evaluation, pattern and analysis included).
BENCHMARK_CAPTURE(BM_Shell, membrane, sim::ModelKind::Membrane, sim::FibreLayout::None)->Arg(120)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Shell, shell, sim::ModelKind::Shell, sim::FibreLayout::None)->Arg(120)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
