// The pagmo optimizers around a callback: they find known optima of cheap functions, give the
// same run whatever order the batch is evaluated in, foresee their generations (so batches keep
// every core busy), and report fronts that are non-dominated. Genome decoding and the checks of a
// definition are tested here too.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/optimize.h"

namespace sim {
namespace {

using ::testing::HasSubstr;

const MeshDef kMesh{30, 30};

// A sine genome with only the amplitude free, in [0, 10].
OptimizerDef OneGene(Algorithm algorithm, int population, int generations) {
    OptimizerDef def;
    def.algorithm = algorithm;
    def.population = population;
    def.genome.family = VectorFamily::Sine;
    def.genome.amplitude = {0, 10};
    def.generations = generations;
    return def;
}

// Three free genes (amplitude, phase start, phase end).
OptimizerDef ThreeGenes(Algorithm algorithm, int population, int generations) {
    OptimizerDef def = OneGene(algorithm, population, generations);
    def.genome.phaseStart = {0, 10};
    def.genome.phaseEnd = {0, 10};
    return def;
}

// Peak 5 at (3, 4, 6): maximised "contraction".
VectorEvaluator Bowl(long long* calls = nullptr, bool reversed = false) {
    return [=](const std::vector<std::vector<double>>& xs) {
        if (calls) *calls += static_cast<long long>(xs.size());
        std::vector<DesignScore> out(xs.size());
        std::vector<size_t> order(xs.size());
        for (size_t k = 0; k < xs.size(); ++k) order[k] = reversed ? xs.size() - 1 - k : k;
        for (size_t k : order) {
            const auto& x = xs[k];
            double d = 0;
            const double centre[] = {3, 4, 6};
            for (size_t i = 0; i < x.size(); ++i) d += (x[i] - centre[i]) * (x[i] - centre[i]);
            out[k] = {{5 - d}, Status::Ok};
        }
        return out;
    };
}

class EachSingleObjective : public ::testing::TestWithParam<Algorithm> {};

TEST_P(EachSingleObjective, FindsThePeakOfABowlAndForeseesEveryGeneration) {
    OptimizerDef def = ThreeGenes(GetParam(), 16, 60);
    long long calls = 0;
    const OptimizerRun run = RunOptimizer(def, kMesh, 7, Bowl(&calls), {});
    ASSERT_FALSE(run.hallOfFame.empty());
    const EvaluatedDesign& best = run.evaluated[run.hallOfFame[0]];
    EXPECT_GT(best.score.values[0], 4.9) << Name(GetParam());
    EXPECT_EQ(run.stopReason, "generations");
    EXPECT_EQ(run.logbook.size(), 61u);
    // Every evaluation was asked for once, and by batches foreseen in advance, except a few.
    EXPECT_EQ(calls, static_cast<long long>(run.evaluated.size()));
    EXPECT_EQ(run.unforeseen, 0) << Name(GetParam()) << ": " << run.unforeseen << " of " << run.evaluated.size();
    // The best so far never gets worse.
    for (size_t g = 1; g < run.logbook.size(); ++g) EXPECT_GE(run.logbook[g].bestSoFar, run.logbook[g - 1].bestSoFar);
}

INSTANTIATE_TEST_SUITE_P(Optimize, EachSingleObjective,
                         ::testing::Values(Algorithm::Cmaes, Algorithm::Xnes, Algorithm::De, Algorithm::Sade, Algorithm::Pso, Algorithm::Sga),
                         [](const auto& info) { return std::string(Name(info.param)); });

TEST(Optimize, TheSameSeedGivesTheSameRunWhateverTheOrderOfEvaluation) {
    for (Algorithm a : {Algorithm::Cmaes, Algorithm::De, Algorithm::Pso}) {
        const OptimizerDef def = ThreeGenes(a, 12, 10);
        const OptimizerRun one = RunOptimizer(def, kMesh, 3, Bowl(nullptr, false), {});
        const OptimizerRun two = RunOptimizer(def, kMesh, 3, Bowl(nullptr, true), {});
        ASSERT_EQ(one.evaluated.size(), two.evaluated.size()) << Name(a);
        for (size_t k = 0; k < one.evaluated.size(); ++k) EXPECT_EQ(one.evaluated[k].x, two.evaluated[k].x) << Name(a);
        const OptimizerRun other = RunOptimizer(def, kMesh, 4, Bowl(), {});
        EXPECT_NE(one.evaluated.back().x, other.evaluated.back().x) << Name(a) << ": another seed, another run";
    }
}

TEST(Optimize, FailedDesignsAreNeverTheBestAndStopCriteriaAreHonoured) {
    OptimizerDef def = OneGene(Algorithm::Cmaes, 8, 50);
    // Amplitudes above 3.5 fail: the best valid design is at the edge, 3.5.
    auto evaluate = [](const std::vector<std::vector<double>>& xs) {
        std::vector<DesignScore> out;
        for (const auto& x : xs) out.push_back(x[0] > 3.5 ? DesignScore{{NAN}, Status::LimitPoint} : DesignScore{{x[0]}, Status::Ok});
        return out;
    };
    OptimizerRun run = RunOptimizer(def, kMesh, 1, evaluate, {});
    ASSERT_FALSE(run.hallOfFame.empty());
    EXPECT_LE(run.evaluated[run.hallOfFame[0]].x[0], 3.5);
    EXPECT_GT(run.evaluated[run.hallOfFame[0]].x[0], 3.3);

    def.stop.target = 3.0;
    run = RunOptimizer(def, kMesh, 1, evaluate, {});
    EXPECT_EQ(run.stopReason, "target");
    EXPECT_GE(run.logbook.back().bestSoFar, 3.0);
    EXPECT_LT(run.logbook.size(), 51u);

    def.stop.target = NAN;
    def.stop.evaluations = 30;
    run = RunOptimizer(def, kMesh, 1, evaluate, {});
    EXPECT_EQ(run.stopReason, "evaluations");
    EXPECT_GE(run.logbook.back().evaluationsSoFar, 30);
    EXPECT_LT(run.logbook[run.logbook.size() - 2].evaluationsSoFar, 30);

    def.stop.evaluations = 0;
    def.stop.stagnation = 3;
    auto flat = [](const std::vector<std::vector<double>>& xs) { return std::vector<DesignScore>(xs.size(), DesignScore{{1.0}, Status::Ok}); };
    run = RunOptimizer(def, kMesh, 1, flat, {});
    EXPECT_EQ(run.stopReason, "stagnation");
    EXPECT_EQ(run.logbook.size(), 4u);

    def.stop.stagnation = 0;
    int calls = 0;
    run = RunOptimizer(def, kMesh, 1, flat, [&](const OptimizerRun&) { return ++calls < 5; });
    EXPECT_EQ(run.stopReason, "stopped");
    EXPECT_EQ(run.logbook.size(), 5u);
}

TEST(Optimize, AReplayAnsweredFromStoredResultsEndsAsTheOriginalRun) {
    // What resume does: the run again from the start, the designs evaluated before answered from
    // their stored results; the callback is asked only for the rest.
    const OptimizerDef def = ThreeGenes(Algorithm::Cmaes, 10, 12);
    const OptimizerRun whole = RunOptimizer(def, kMesh, 9, Bowl(), {});
    std::map<std::vector<double>, DesignScore> stored;
    for (size_t k = 0; k < whole.evaluated.size() / 2; ++k) stored[whole.evaluated[k].x] = whole.evaluated[k].score;
    long long simulated = 0;
    auto bowl = Bowl(&simulated);
    auto replay = [&](const std::vector<std::vector<double>>& xs) {
        std::vector<DesignScore> out(xs.size());
        std::vector<std::vector<double>> missing;
        for (const auto& x : xs)
            if (!stored.count(x)) missing.push_back(x);
        const auto fresh = bowl(missing);
        for (size_t k = 0, m = 0; k < xs.size(); ++k) out[k] = stored.count(xs[k]) ? stored[xs[k]] : fresh[m++];
        return out;
    };
    const OptimizerRun resumed = RunOptimizer(def, kMesh, 9, replay, {});
    ASSERT_EQ(resumed.evaluated.size(), whole.evaluated.size());
    for (size_t k = 0; k < whole.evaluated.size(); ++k) EXPECT_EQ(resumed.evaluated[k].x, whole.evaluated[k].x);
    EXPECT_EQ(simulated, static_cast<long long>(whole.evaluated.size() - whole.evaluated.size() / 2));
}

TEST(Optimize, TwoObjectiveFrontsAreNonDominatedAndTheHypervolumeGrows) {
    for (Algorithm a : {Algorithm::Nsga2, Algorithm::Moead}) {
        OptimizerDef def = ThreeGenes(a, 16, 25);
        def.objectives = {{ObjectiveKind::Contraction, true}, {ObjectiveKind::MaxStretch, false}};
        // Contraction wants a large amplitude, the stretch a small one: a trade-off.
        auto evaluate = [](const std::vector<std::vector<double>>& xs) {
            std::vector<DesignScore> out;
            for (const auto& x : xs) out.push_back({{x[0] - 0.1 * std::fabs(x[1] - 5), 1 + x[0] * x[0] / 10 + 0.1 * std::fabs(x[2] - 5)}, Status::Ok});
            return out;
        };
        const OptimizerRun run = RunOptimizer(def, kMesh, 5, evaluate, {});
        ASSERT_GE(run.front.size(), 5u) << Name(a);
        std::vector<std::vector<double>> all;
        for (const auto& d : run.evaluated) all.push_back(MinimisedForm(def, d.score));
        // Brute force: nothing evaluated dominates a front member.
        for (size_t f : run.front) {
            const auto p = MinimisedForm(def, run.evaluated[f].score);
            for (const auto& q : all) EXPECT_FALSE(q[0] <= p[0] && q[1] <= p[1] && (q[0] < p[0] || q[1] < p[1])) << Name(a);
        }
        for (size_t g = 1; g < run.logbook.size(); ++g) EXPECT_GE(run.logbook[g].hypervolume, run.logbook[g - 1].hypervolume) << Name(a);
        EXPECT_GT(run.logbook.back().hypervolume, run.logbook.front().hypervolume) << Name(a);
    }
}

TEST(Optimize, NonDominatedKeepsOneOfEqualPoints) {
    const std::vector<std::vector<double>> points{{1, 3}, {2, 2}, {1, 3}, {3, 3}, {3, 1}};
    EXPECT_EQ(NonDominated(points), (std::vector<size_t>{0, 1, 4}));
}

TEST(Optimize, BSplineGenesRoundToTheThesissIntegersInOnePlace) {
    VectorGenomeDef def;
    def.family = VectorFamily::BSpline;
    def.controlPoints = 5;
    def.genes.splines = 2;
    def.genes.fibreAngles = 1;
    def.genes.fibreSwitches = true;
    const auto [lo, hi] = VectorBounds(def, kMesh);
    ASSERT_EQ(lo.size(), 2u * 5 + 1 + 2);
    EXPECT_EQ(lo[0], -0.5);
    EXPECT_EQ(hi[0], 8.5);
    EXPECT_EQ(VectorGeneNames(def, kMesh).size(), lo.size());
    std::vector<double> x{-0.5, 0.49, 0.5, 7.6, 8.5, 1, 2, 3, 4, 5, 33.3, 0.7, 0.2};
    const VectorDesign d = DesignOfVector(def, x, kMesh);
    const auto& b = std::get<BSplineShape>(d.shape);
    EXPECT_EQ(b.splines[0], (std::vector<double>{0, 0, 1, 8, 8}));
    EXPECT_EQ(d.genome.back(), (std::vector<double>{33.3, 1, 0}));
    // A finer grid: genes are radii, rounded to the nearest grid point, each point an equal share.
    def.genes.controlMin = 0.5;
    def.genes.controlMax = 2.5;
    def.genes.controlStep = 0.25;
    const auto [fineLo, fineHi] = VectorBounds(def, kMesh);
    EXPECT_EQ(fineLo[0], 0.375);
    EXPECT_EQ(fineHi[0], 2.625);
    x = {0.375, 0.62, 0.63, 2.3, 2.625, 1, 2, 3, 4, 5, 33.3, 0.7, 0.2};
    EXPECT_EQ(std::get<BSplineShape>(DesignOfVector(def, x, kMesh).shape).splines[0], (std::vector<double>{0.5, 0.5, 0.75, 2.25, 2.5}));
}

TEST(Optimize, DefinitionsThatCannotRunAreRefusedWithTheReason) {
    OptimizerDef def = OneGene(Algorithm::Nsga2, 10, 5);
    def.objectives = {{ObjectiveKind::Contraction, true}, {ObjectiveKind::MaxStretch, false}};
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("multiple of 4"));
    def.population = 4;
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("at least 8"));
    def.population = 12;
    EXPECT_EQ(OptimizerDefError(def, ModelKind::Shell, kMesh), "");
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Thesis, kMesh), HasSubstr("thesis model gives only"));
    def.objectives.pop_back();
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("two or more"));
    def = OneGene(Algorithm::De, 10, 5);
    def.parameters["G"] = 1;
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("no parameter 'G' (valid: F, CR, variant)"));
    def.parameters = {{"variant", 2.5}};
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("an integer"));
    def.parameters.clear();
    def.genome.amplitude = {5, 1};
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("reversed"));
    def.genome.amplitude = {5, 5};
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("no gene"));
    def = OneGene(Algorithm::Moead, 8, 5);
    def.objectives = {{ObjectiveKind::Contraction, true}, {ObjectiveKind::MaxStretch, false}};
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("neighbours (10) must be smaller than the population (8)"));
    def = OneGene(Algorithm::Sga, 4, 5);
    def.parameters["param_s"] = 6;
    EXPECT_THAT(OptimizerDefError(def, ModelKind::Shell, kMesh), HasSubstr("tournament (param_s 6) is larger than the population (4)"));
    def.parameters["param_s"] = 4;
    EXPECT_EQ(OptimizerDefError(def, ModelKind::Shell, kMesh), "");
}

}  // namespace
}  // namespace sim
