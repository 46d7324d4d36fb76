// Speed of the membrane and shell models (issues 10 and 11): one evaluation of a thesis-sized design (the
// 4.1 sine at A = 1.3, R = 5 mm, L = 150 mm, 3 kPa in 4 load steps, Ecoflex 00-30) at 30 x 30,
// 60 x 60 and 120 x 120, beside the thesis model's evaluation measured in the same run, on one core.
// Fibres' cost (issue 11) on the same sine and on two of the GA's fibre designs, each beside the same
// design without fibres; one assembly with and without the fibre terms. The counters give the
// Newton iterations and factorisations per evaluation. Self-contact's cost with no wall near another
// and on a collapsed tube; a compressed held state's sideways push.
//   build/tests/shell_bench --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <numbers>

#include "sim/batch.h"
#include "shell/block_ldlt.h"
#include "shell/shell_problem.h"

namespace {

// The benchmarks' silicone: the data-sheet Ecoflex 00-30 their problems (and docs/performance.md's
// figures) were set up in; the softer fitted preset would take the same pressures past the designs'
// pressure maxima.
const sim::MaterialDef kBenchMaterial = sim::MaterialPresetDef(sim::MaterialPreset::Ecoflex0030Datasheet);

sim::EvalJob Job(sim::ModelKind model, int ringVertices, int rings) {
    sim::EvalJob job;
    job.SetModel(model);
    job.Shell().material = kBenchMaterial;
    job.shape = sim::SineShape{1.3, 0.5, std::numbers::pi - 0.5};
    job.Shell().geometry.ringVertices = ringVertices;
    job.Shell().geometry.rings = rings;
    return job;
}

void BM_Thesis30x30(benchmark::State& state) {
    const sim::EvalJob job{sim::SineShape{4.1, 0.5, std::numbers::pi - 0.5}, sim::ModelKind::Thesis, sim::ThesisDef{}};
    for (auto _ : state) benchmark::DoNotOptimize(sim::Evaluate(job).fitness);
}

// Evaluates `job` as often as the state asks; the last result's counters.
void Measure(benchmark::State& state, const sim::EvalJob& job) {
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

// range(0): n vertices x n rings; range(1): 1 graded toward the clamps as by default, 0 evenly spaced
// (the default mesh before the grading, for the cost comparison of docs/performance.md).
void BM_Shell(benchmark::State& state, sim::ModelKind model, sim::FibreLayout fibres) {
    const int n = static_cast<int>(state.range(0));
    sim::EvalJob job = Job(model, n, n);
    if (state.range(1) == 0) job.Shell().geometry.edgeSpacingMm = 0;
    state.counters["rings"] = sim::RingCount(job.Shell().geometry);
    job.Shell().fibres.layout = fibres;  // braid at the default 30 degrees, 50 N/mm
    Measure(state, job);
}

// Two designs the thesis's GA found with fibre genes in reproduce part 2 (1 kPa), with their fibres
// and without: the benchmark's sine is an easy design, and these show what fibres cost on the shapes
// the optimizers actually visit. S5.2F's best (one B-spline over the middle, a single +43.6 degree
// family) and an S5.4F individual (four sector B-splines, a single family at 11-31 degrees in four bands).
sim::EvalJob GaDesign(int which, bool fibres) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    job.Shell().material = kBenchMaterial;
    job.Shell().load.pressureKpa = 1;
    sim::BSplineShape shape;
    if (which == 0) {
        shape.splines = {{7, 8, 1, 5, 7, 5, 5}};
        job.Shell().fibres.angleDeg = 43.6062675338317;
    } else {
        shape.splines = {{5, 7, 0, 2, 7, 3, 7}, {5, 2, 1, 4, 6}, {4, 2, 1, 1, 1}, {0, 5, 0, 8, 4, 3, 2, 5, 4, 6, 2, 7, 4}};
        job.Shell().fibres.bands = {{0, 0.25, 12.308510908575812}, {0.25, 0.5, 31.12818092256292}, {0.5, 0.75, 29.65807805103285}, {0.75, 1, 10.786319724686154}};
    }
    job.shape = shape;
    job.Shell().fibres.layout = fibres ? sim::FibreLayout::Braid : sim::FibreLayout::None;
    job.Shell().fibres.minus = false;
    return job;
}

// With contact off as well: the S5.4F shape's wall bulges sector by sector, which no affine motion
// of a ring fits, so it is where self-contact's bookkeeping costs most with no wall near another.
void BM_GaDesign(benchmark::State& state, int which, bool fibres, bool contact) {
    sim::EvalJob job = GaDesign(which, fibres);
    job.Shell().contact.mode = contact ? sim::ContactMode::On : sim::ContactMode::Off;
    Measure(state, job);
}

// A design solved, and the problem, unknowns and load of its equilibrium: what the benchmarks of one
// assembly or factorisation there start from. False (the benchmark skipped with `failure`) when it
// does not solve.
struct Equilibrium {
    sim::ShellProblem problem;
    Eigen::VectorXd q;
    sim::LoadTerms load;
};
bool Solve(benchmark::State& state, const sim::EvalJob& job, const char* failure, Equilibrium& e) {
    const sim::SimResult solved = sim::Evaluate(job);
    std::string error;
    e.problem = sim::BuildTubeProblem(job.Shell(), job.shape, true, &error);
    if (solved.status != sim::Status::Ok || !error.empty()) {
        state.SkipWithError(failure);
        return false;
    }
    e.q = sim::UnknownsOf(e.problem, solved.final);
    e.load.pressure = job.Shell().load.pressureKpa * 1e-3;  // MPa
    return true;
}

// What the fibre terms cost in one assembly, apart from the iterations they make Newton take: the
// braided sine's equilibrium (30 x 30, 3 kPa), assembled as a Newton iteration does (gradient and
// projected Hessian) or as a line-search trial does (gradient only), with the fibres' terms and
// without them, at the same state.
void BM_Assembly(benchmark::State& state, bool hessian, bool fibres) {
    sim::EvalJob job = Job(sim::ModelKind::Shell, 30, 30);
    job.Shell().fibres.layout = sim::FibreLayout::Braid;
    Equilibrium e;
    if (!Solve(state, job, "the braided sine did not solve", e)) return;
    sim::EnergyTerms terms;
    terms.fibres = fibres;
    // Without contact: with no list given, every assembly would search the whole wall for its pairs
    // (3-4 ms of the 5 ms such an assembly takes), which a Newton iteration, holding its list, does not.
    terms.contact = false;
    sim::HessianPattern pattern(e.problem);
    for (auto _ : state) {
        const sim::EnergyResult r = sim::AssembleEnergy(e.problem, e.q, e.load, terms, true, hessian ? &pattern : nullptr, sim::HessianKind::Projected);
        benchmark::DoNotOptimize(r.energy);
    }
}

// One factorisation of Newton's matrix, what a search's fibre designs spend most of their time in (an
// S5.4F GA factorises on 85 % of its Newton iterations), and one solve with it (conjugate gradients
// make several a step): the exact Hessian of the S5.4F individual with its fibres at its equilibrium
// (30 x 30 graded), its pattern analysed once. The counter gives the factor's 3 x 3 blocks below the
// diagonal.
void BM_Factor(benchmark::State& state, bool solve) {
    Equilibrium e;
    if (!Solve(state, GaDesign(1, true), "the S5.4F individual did not solve", e)) return;
    const sim::ShellProblem& problem = e.problem;
    sim::HessianPattern pattern(problem);
    sim::AssembleEnergy(problem, e.q, e.load, sim::EnergyTerms{}, false, &pattern, sim::HessianKind::Exact);
    sim::BlockLdlt ldlt;
    ldlt.Analyse(pattern.matrix, sim::VertexBlockPlaces(problem));
    if (solve) {
        ldlt.Factorise(pattern.matrix, 0);
        const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(problem.unknowns, -1, 1);
        for (auto _ : state) benchmark::DoNotOptimize(ldlt.Solve(b)[0]);
    } else {
        for (auto _ : state) benchmark::DoNotOptimize(ldlt.Factorise(pattern.matrix, 0));
    }
    state.counters["factor_blocks"] = static_cast<double>(ldlt.FactorBlocks());
    state.counters["negative_pivots"] = ldlt.NegativePivots();
}

// A held state that pushes on its clamps, pushed a tube's diameter sideways (docs/models/shell.md
// section 12): the +/-70 deg braid on the plain tube (the fitted Ecoflex 00-30, 3 kPa) inflated, its
// blocking force with the push (it bows) and without (straight), and a contracting design whose
// held state pulls (the +/-30 deg braid: no push).
void BM_HeldPush(benchmark::State& state, double angleDeg, double pushDiameters) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    job.shape = sim::CylinderShape{};
    job.Shell().fibres.layout = sim::FibreLayout::Braid;
    job.Shell().fibres.angleDeg = angleDeg;
    job.Shell().solver.heldPushDiameters = pushDiameters;
    Measure(state, job);
    state.counters["blocking_force_n"] = sim::Evaluate(job).shell.blockingForceN;
}

}  // namespace

// Self-contact: the sine above with contact on, where no wall comes near another (what a search
// pays for the barrier's bookkeeping), and the vacuum tube of the contact tests (R 5, L 60, 20 x 16,
// 0.5 kPa of vacuum: collapsed, 531 pairs in contact), each with contact on; the sine also off, and
// both without the held state's sideways push (whose 14 mm excursion and way back are most of the
// contact searches an evaluation makes).
void BM_Contact(benchmark::State& state, bool vacuum, bool contact, bool push) {
    sim::EvalJob job = Job(sim::ModelKind::Shell, 30, 30);
    if (vacuum) {
        job.Shell().material = sim::MaterialPresetDef(sim::MaterialPreset::Ecoflex0030);
        job.shape = sim::CylinderShape{};
        job.Shell().geometry.lengthMm = 60;
        job.Shell().geometry.ringVertices = 20;
        job.Shell().geometry.rings = 16;
        job.Shell().load.pressureKpa = -0.5;
    }
    job.Shell().contact.mode = contact ? sim::ContactMode::On : sim::ContactMode::Off;
    if (!push) job.Shell().solver.heldPushDiameters = 0;
    Measure(state, job);
    state.counters["contact_pairs"] = sim::Evaluate(job).shell.contactPairs;
}

BENCHMARK(BM_Thesis30x30)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Contact, sine_contact_off, false, false, true)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Contact, sine_contact_on, false, true, true)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Contact, sine_not_pushed_contact_off, false, false, false)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Contact, sine_not_pushed_contact_on, false, true, false)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Contact, vacuum_collapse, true, true, true)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Shell, membrane, sim::ModelKind::Membrane, sim::FibreLayout::None)->Args({30, 1})->Args({30, 0})->Args({60, 1})->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Shell, shell, sim::ModelKind::Shell, sim::FibreLayout::None)->Args({30, 1})->Args({30, 0})->Args({60, 1})->Unit(benchmark::kMillisecond)->MinTime(2);
// What fibres cost (issue 11: at most 30 % more).
BENCHMARK_CAPTURE(BM_Shell, shell_braid, sim::ModelKind::Shell, sim::FibreLayout::Braid)->Args({30, 1})->Args({30, 0})->Args({60, 1})->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_GaDesign, S5_2F_best, 0, true, true)->Unit(benchmark::kMillisecond)->MinTime(3);
BENCHMARK_CAPTURE(BM_GaDesign, S5_2F_best_without_fibres, 0, false, true)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_GaDesign, S5_4F_individual, 1, true, true)->Unit(benchmark::kMillisecond)->MinTime(3);
BENCHMARK_CAPTURE(BM_GaDesign, S5_4F_individual_without_fibres, 1, false, true)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_GaDesign, S5_4F_individual_without_fibres_contact_off, 1, false, false)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_HeldPush, braid70_pushed, 70.0, 1.0)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_HeldPush, braid70_not_pushed, 70.0, 0.0)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_HeldPush, braid30_pulls, 30.0, 1.0)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(BM_Factor, factorise, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Factor, solve, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Assembly, newton_braid, true, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Assembly, newton_without_fibres, true, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Assembly, gradient_braid, false, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Assembly, gradient_without_fibres, false, false)->Unit(benchmark::kMicrosecond);
// 120 x 120 once each (seconds: the first evaluation, pattern and analysis included).
BENCHMARK_CAPTURE(BM_Shell, membrane, sim::ModelKind::Membrane, sim::FibreLayout::None)->Args({120, 1})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Shell, shell, sim::ModelKind::Shell, sim::FibreLayout::None)->Args({120, 1})->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
