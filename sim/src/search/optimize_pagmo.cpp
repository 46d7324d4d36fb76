// RunOptimizer's work (optimize.h), in the optimizer module: pagmo's algorithms stepped one
// generation at a time, each generation foreseen on copies so that its designs are evaluated as one
// batch. Built without
// -march=native: pagmo's headers carry Eigen, and Debian's libpagmo was built for the baseline
// x86-64, so both sides must agree on Eigen's alignment (a mismatch crashes in ~cmaes()).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <pagmo/algorithm.hpp>
#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/algorithms/de.hpp>
#include <pagmo/algorithms/moead.hpp>
#include <pagmo/algorithms/nsga2.hpp>
#include <pagmo/algorithms/pso_gen.hpp>
#include <pagmo/algorithms/sade.hpp>
#include <pagmo/algorithms/sga.hpp>
#include <pagmo/algorithms/xnes.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/utils/hypervolume.hpp>

#include "sim/optimize.h"
#include "sim/optimizer_module.h"

#include "algorithms.h"

namespace sim {
namespace {

// What the problem's fitness calls go to, shared by every copy of the problem. Answering: from the
// results so far, else evaluated on the spot (one design: the foresight missed it). Recording
// (while a copy of the generation is run ahead): every new design asked for is noted and answered
// with zeros; that copy is then thrown away.
struct Oracle {
    const OptimizerDef* def = nullptr;
    const VectorEvaluator* evaluate = nullptr;
    bool recording = false;
    std::map<std::vector<double>, size_t> known;  // vector -> index into run->evaluated
    std::vector<std::vector<double>> asked;       // recording: new vectors, in the order asked
    OptimizerRun* run = nullptr;
    int generation = 0;

    // Evaluates new vectors as one batch and records them.
    void EvaluateBatch(const std::vector<std::vector<double>>& xs) {
        std::vector<std::vector<double>> fresh;
        for (const auto& x : xs)
            if (!known.count(x) && std::find(fresh.begin(), fresh.end(), x) == fresh.end()) fresh.push_back(x);
        if (fresh.empty()) return;
        std::vector<DesignScore> scores = (*evaluate)(fresh);
        for (size_t k = 0; k < fresh.size(); ++k) {
            known.emplace(fresh[k], run->evaluated.size());
            run->evaluated.push_back({fresh[k], k < scores.size() ? scores[k] : DesignScore{{}, Status::NaN}, generation});
        }
    }

    pagmo::vector_double Fitness(const pagmo::vector_double& x) {
        if (recording) {
            if (!known.count(x) && std::find(asked.begin(), asked.end(), x) == asked.end()) asked.push_back(x);
            return pagmo::vector_double(def->objectives.size(), 0.0);
        }
        if (!known.count(x)) {
            ++run->unforeseen;
            EvaluateBatch({x});
        }
        return MinimisedForm(*def, run->evaluated[known.at(x)].score);
    }
};

// The user-defined problem pagmo sees: the genome's bounds and the oracle.
struct DesignProblem {
    std::shared_ptr<Oracle> oracle;
    std::vector<double> lo, hi;
    size_t objectives = 1;

    pagmo::vector_double fitness(const pagmo::vector_double& x) const { return oracle->Fitness(x); }
    std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const { return {lo, hi}; }
    pagmo::vector_double::size_type get_nobj() const { return objectives; }
    std::string get_name() const { return "actuator design"; }
    // Never evaluated on pagmo's threads: the oracle batches for the workbench's evaluator.
    pagmo::thread_safety get_thread_safety() const { return pagmo::thread_safety::none; }
};

unsigned Seed32(std::uint64_t seed, std::uint64_t stream) { return static_cast<unsigned>(DeriveSeed(seed, stream) >> 32); }

// Each algorithm with its parameters (AlgorithmRows: their defaults and ranges), stepping one
// generation per evolve() call with memory, so that stepping equals one long call; pagmo's own
// tolerances off: the run's stop criteria decide. pagmo 2.18's own defaults, except where noted there.
pagmo::algorithm MakeAlgorithm(const OptimizerDef& d, unsigned seed) {
    auto P = [&](const char* name) { return ParameterValue(d, name); };
    auto U = [&](const char* name) { return static_cast<unsigned>(ParameterValue(d, name)); };
    switch (d.algorithm) {
        case Algorithm::Cmaes: return pagmo::algorithm{pagmo::cmaes(1, P("cc"), P("cs"), P("c1"), P("cmu"), P("sigma0"), 0, 0, true, true, seed)};
        case Algorithm::Xnes: return pagmo::algorithm{pagmo::xnes(1, P("eta_mu"), P("eta_sigma"), P("eta_b"), P("sigma0"), 0, 0, true, true, seed)};
        case Algorithm::De: return pagmo::algorithm{pagmo::de(1, P("F"), P("CR"), U("variant"), 0, 0, seed)};
        case Algorithm::Sade: return pagmo::algorithm{pagmo::sade(1, U("variant"), U("variant_adptv"), 0, 0, true, seed)};
        case Algorithm::Pso:
            return pagmo::algorithm{
                pagmo::pso_gen(1, P("omega"), P("eta1"), P("eta2"), P("max_vel"), U("variant"), U("neighb_type"), U("neighb_param"), true, seed)};
        case Algorithm::Nsga2: return pagmo::algorithm{pagmo::nsga2(1, P("cr"), P("eta_c"), P("m"), P("eta_m"), seed)};
        case Algorithm::Moead:
            // "low discrepancy" weights work for any population size ("grid" does not).
            return pagmo::algorithm{pagmo::moead(1, "low discrepancy", "tchebycheff", static_cast<pagmo::population::size_type>(P("neighbours")), P("CR"),
                                                 P("F"), P("eta_m"), P("realb"), U("limit"), true, seed)};
        case Algorithm::Sga:
            // Tournament selection, exponential crossover, polynomial mutation, pure elitism (pagmo's
            // defaults for the three operators).
            return pagmo::algorithm{pagmo::sga(1, P("cr"), 1.0, P("m"), P("param_m"), U("param_s"), "exponential", "polynomial", "tournament", seed)};
    }
    throw std::logic_error("an algorithm without a maker");
}


// The statistics of a generation and of the run so far.
LogbookRow LogRow(const OptimizerDef& def, const OptimizerRun& run, const pagmo::population& pop, const std::map<std::vector<double>, size_t>& known,
                       int generation) {
    LogbookRow row;
    row.generation = generation;
    row.evaluationsSoFar = static_cast<long long>(run.evaluated.size());
    row.evaluations = row.evaluationsSoFar - (run.logbook.empty() ? 0 : run.logbook.back().evaluationsSoFar);
    const bool maximise = def.objectives[0].maximise;
    auto better = [&](double a, double b) { return maximise ? a > b : a < b; };
    std::vector<double> values;
    for (const auto& x : pop.get_x()) {
        const DesignScore& s = run.evaluated[known.at(x)].score;
        if (s.status != Status::Ok || s.values.empty() || !std::isfinite(s.values[0])) {
            ++row.invalid;
            continue;
        }
        values.push_back(s.values[0]);
    }
    if (!values.empty()) {
        double sum = 0, best = values[0], worst = values[0];
        for (double v : values) {
            sum += v;
            if (better(v, best)) best = v;
            if (better(worst, v)) worst = v;
        }
        row.mean = sum / static_cast<double>(values.size());
        double squares = 0;
        for (double v : values) squares += (v - row.mean) * (v - row.mean);
        row.stddev = std::sqrt(squares / static_cast<double>(values.size()));
        row.best = best;
        row.worst = worst;
        std::vector<double> ascending = values;
        std::sort(ascending.begin(), ascending.end());
        row.q1 = SortedQuantile(ascending, 0.25);
        row.median = SortedQuantile(ascending, 0.5);
        row.q3 = SortedQuantile(ascending, 0.75);
    }
    for (const EvaluatedDesign& d : run.evaluated)
        if (d.score.status == Status::Ok && !d.score.values.empty() && std::isfinite(d.score.values[0]) &&
            (std::isnan(row.bestSoFar) || better(d.score.values[0], row.bestSoFar)))
            row.bestSoFar = d.score.values[0];
    return row;
}

// A design that counts: status Ok and every objective known (no penalty in its minimised form).
bool Counts(const std::vector<double>& minimised) {
    return std::all_of(minimised.begin(), minimised.end(), [](double v) { return v < kFailedPenalty; });
}

// Front and hypervolume of every valid design so far (several objectives); the hall of fame (one).
void UpdateBests(const OptimizerDef& def, OptimizerRun& run, LogbookRow& row) {
    std::vector<size_t> valid;
    std::vector<std::vector<double>> points;
    for (size_t k = 0; k < run.evaluated.size(); ++k) {
        std::vector<double> minimised = MinimisedForm(def, run.evaluated[k].score);  // failed: all penalty
        if (!Counts(minimised)) continue;
        valid.push_back(k);
        points.push_back(std::move(minimised));
    }
    if (def.objectives.size() == 1) {
        std::vector<size_t> order(valid.size());
        for (size_t k = 0; k < order.size(); ++k) order[k] = k;
        // Best first; ties keep the order of evaluation.
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return points[a][0] < points[b][0]; });
        run.hallOfFame.clear();
        for (size_t k = 0; k < order.size() && run.hallOfFame.size() < 10; ++k) run.hallOfFame.push_back(valid[order[k]]);
        return;
    }
    // The front by its first objective (indices into `points`, then into `evaluated`).
    std::vector<size_t> front = NonDominated(points);
    std::stable_sort(front.begin(), front.end(), [&](size_t a, size_t b) { return points[a][0] < points[b][0]; });
    run.front.clear();
    for (size_t k : front) run.front.push_back(valid[k]);
    row.frontSize = static_cast<int>(run.front.size());
    // The reference point: fixed once there are valid designs, 10 % beyond the worst of them in
    // each objective (and a little beyond when all are equal), so that hypervolumes compare across
    // generations. Designs outside it do not count.
    if (run.referencePoint.empty() && !points.empty()) {
        run.referencePoint.assign(def.objectives.size(), 0.0);
        for (size_t m = 0; m < def.objectives.size(); ++m) {
            double lo = points[0][m], hi = points[0][m];
            for (const auto& p : points) {
                lo = std::min(lo, p[m]);
                hi = std::max(hi, p[m]);
            }
            run.referencePoint[m] = hi + std::max(0.1 * (hi - lo), 1e-9 * std::max(1.0, std::fabs(hi)));
        }
    }
    std::vector<pagmo::vector_double> inside;
    for (size_t k : front) {
        const auto& p = points[k];
        bool in = !run.referencePoint.empty();
        for (size_t m = 0; in && m < p.size(); ++m) in = p[m] < run.referencePoint[m];
        if (in) inside.push_back(p);
    }
    row.hypervolume = inside.empty() ? 0.0 : pagmo::hypervolume(inside, true).compute(run.referencePoint);
}

// Why the run stops after this generation, or "".
std::string StopReason(const OptimizerDef& def, const OptimizerRun& run) {
    const StopDef& s = def.stop;
    const LogbookRow& last = run.logbook.back();
    if (last.generation >= def.generations) return "generations";
    if (s.evaluations > 0 && last.evaluationsSoFar >= s.evaluations) return "evaluations";
    if (std::isfinite(s.target) && std::isfinite(last.bestSoFar) && (def.objectives[0].maximise ? last.bestSoFar >= s.target : last.bestSoFar <= s.target))
        return "target";
    if (s.stagnation > 0 && static_cast<int>(run.logbook.size()) > s.stagnation) {
        const LogbookRow& then = run.logbook[run.logbook.size() - 1 - static_cast<size_t>(s.stagnation)];
        const bool multi = def.objectives.size() > 1;
        const double now = multi ? last.hypervolume : last.bestSoFar, before = multi ? then.hypervolume : then.bestSoFar;
        const bool improved = multi ? now > before : (def.objectives[0].maximise ? now > before : now < before);
        if (!improved && !(std::isnan(before) && std::isfinite(now))) return "stagnation";
    }
    return "";
}

}  // namespace

OptimizerRun RunPagmoOptimizer(const OptimizerDef& def, const MeshDef& mesh, std::uint64_t seed, const VectorEvaluator& evaluate,
                               const GenerationHook& onGeneration) {
    OptimizerRun run;
    auto oracle = std::make_shared<Oracle>();
    oracle->def = &def;
    oracle->evaluate = &evaluate;
    oracle->run = &run;

    DesignProblem udp;
    std::tie(udp.lo, udp.hi) = VectorBounds(def.genome, mesh);
    udp.objectives = def.objectives.size();
    udp.oracle = oracle;
    const pagmo::problem problem{udp};
    // Runs `step` recording the designs it asks for, then evaluates them as one batch.
    auto foresee = [&](const auto& step) {
        oracle->recording = true;
        oracle->asked.clear();
        step();
        oracle->recording = false;
        oracle->EvaluateBatch(oracle->asked);
    };
    const unsigned populationSeed = Seed32(seed, 0), algorithmSeed = Seed32(seed, 1);
    const auto size = static_cast<pagmo::population::size_type>(def.population);

    // Generation 0: the random population, recorded, evaluated as one batch, then made for real
    // (the same seed draws the same vectors).
    foresee([&] { pagmo::population foreseen{problem, size, populationSeed}; });
    pagmo::population pop{problem, size, populationSeed};
    pagmo::algorithm algorithm = MakeAlgorithm(def, algorithmSeed);

    for (int generation = 0;; ++generation) {
        if (generation > 0) {
            oracle->generation = generation;
            // The same step on copies first (their random streams advance, not the originals').
            foresee([&] {
                pagmo::algorithm ahead = algorithm;
                ahead.evolve(pop);
            });
            pop = algorithm.evolve(pop);
        }
        run.population = pop.get_x();
        LogbookRow row = LogRow(def, run, pop, oracle->known, generation);
        UpdateBests(def, run, row);
        run.logbook.push_back(row);
        std::string reason = StopReason(def, run);
        const bool anyValid = row.invalid < def.population;
        if (reason.empty() && !anyValid && generation == 0) reason = "no valid design";
        if (onGeneration && !onGeneration(run) && reason.empty()) reason = "stopped";
        if (!reason.empty()) {
            run.stopReason = reason;
            return run;
        }
    }
}

}  // namespace sim
