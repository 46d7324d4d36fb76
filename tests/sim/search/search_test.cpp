// The search algorithms on their own, with cheap synthetic fitness functions where the physics
// would only slow the test down.
#include "sim/search.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

namespace {

// Fitness: how close every control point is to 5 (best 0). Genomes whose first gene is 0 "fail".
std::vector<std::pair<double, sim::Status>> Synthetic(const std::vector<const sim::Genome*>& genomes) {
    std::vector<std::pair<double, sim::Status>> out;
    for (const auto* g : genomes) {
        if ((*g)[0][0] == 0) {
            out.push_back({std::nan(""), sim::Status::NaN});
            continue;
        }
        double f = 0;
        for (const auto& spline : *g)
            for (double c : spline) f -= (c - 5) * (c - 5);
        out.push_back({f, sim::Status::Ok});
    }
    return out;
}

sim::GaDef SmallGa() {
    sim::GaDef d;
    d.population = 20;
    d.generations = 25;
    d.tournament = 3;
    d.elite = 1;
    d.mutpb = 0.4;
    d.indpb = 0.2;
    d.genome.splines = 2;
    return d;
}

}  // namespace

TEST(Sweep, LinspaceAndGridOrder) {
    EXPECT_EQ(sim::Linspace(1, 10, 4), (std::vector<double>{1, 4, 7, 10}));
    sim::SweepDef def{sim::SineShape{1, 0, 1}, {{sim::SweepParameter::Amplitude, {0.5, 1.0}}, {sim::SweepParameter::Cycles, {2, 3, 4}}}};
    const auto shapes = sim::SweepShapes(def);
    ASSERT_EQ(shapes.size(), 6u);
    // Last axis fastest: (0.5, 2), (0.5, 3), (0.5, 4), (1.0, 2), ...
    const auto& s4 = std::get<sim::SineShape>(shapes[4]);
    EXPECT_DOUBLE_EQ(s4.amplitude, 1.0);
    EXPECT_DOUBLE_EQ(s4.phaseEnd, 3 * std::numbers::pi);
    EXPECT_DOUBLE_EQ(s4.phaseStart, 0);
}

TEST(Ga, SameSeedSameEvolution) {
    const auto def = SmallGa();
    const sim::MeshDef mesh;
    auto a = sim::StartEvolution(def, mesh, 42, Synthetic), b = sim::StartEvolution(def, mesh, 42, Synthetic);
    for (int g = 0; g < def.generations; ++g) {
        ASSERT_TRUE(sim::EvolveOneGeneration(def, mesh, a, Synthetic));
        ASSERT_TRUE(sim::EvolveOneGeneration(def, mesh, b, Synthetic));
    }
    ASSERT_EQ(a.logbook.size(), b.logbook.size());
    for (size_t k = 0; k < a.logbook.size(); ++k) EXPECT_EQ(a.logbook[k].best, b.logbook[k].best);
    EXPECT_EQ(sim::GenomeText(a.hallOfFame.front().genome), sim::GenomeText(b.hallOfFame.front().genome));
    auto c = sim::StartEvolution(def, mesh, 43, Synthetic);
    EXPECT_NE(sim::GenomeText(c.population[0].genome), sim::GenomeText(sim::StartEvolution(def, mesh, 42, Synthetic).population[0].genome));
}

TEST(Ga, ElitismMakesTheBestNeverWorseAndEvolutionImproves) {
    const auto def = SmallGa();
    const sim::MeshDef mesh;
    auto state = sim::StartEvolution(def, mesh, 7, Synthetic);
    for (int g = 0; g < def.generations; ++g) ASSERT_TRUE(sim::EvolveOneGeneration(def, mesh, state, Synthetic));
    for (size_t k = 1; k < state.logbook.size(); ++k) EXPECT_GE(state.logbook[k].best, state.logbook[k - 1].best) << "generation " << k;
    EXPECT_GT(state.logbook.back().best, state.logbook.front().best);
    EXPECT_GT(state.logbook.back().mean, state.logbook.front().mean);
    EXPECT_EQ(state.logbook.back().generation, def.generations);
}

TEST(Ga, FailedIndividualsAreCountedButNeverSelected) {
    auto def = SmallGa();
    def.genome.controlMin = 0;
    def.genome.controlMax = 2;  // a third of first genes are 0, which the synthetic fitness fails
    const sim::MeshDef mesh;
    std::multiset<std::string> evaluatedThisGeneration;
    auto recording = [&](const std::vector<const sim::Genome*>& genomes) {
        for (const auto* g : genomes) evaluatedThisGeneration.insert(sim::GenomeText(*g));
        return Synthetic(genomes);
    };
    auto state = sim::StartEvolution(def, mesh, 3, recording);
    int invalidSeen = 0;
    for (int g = 0; g < 10; ++g) {
        evaluatedThisGeneration.clear();
        ASSERT_TRUE(sim::EvolveOneGeneration(def, mesh, state, recording));
        invalidSeen += state.logbook.back().invalid;
        for (const auto& individual : state.population) {
            if (individual.Valid()) continue;
            // A failed individual in the new generation must be a fresh offspring evaluated just now:
            // one carried over by selection or elitism would mean a failure was selected.
            EXPECT_TRUE(evaluatedThisGeneration.count(sim::GenomeText(individual.genome))) << "generation " << g + 1;
            EXPECT_TRUE(std::isnan(individual.fitness)) << "a failure must not read as a number";
        }
        EXPECT_TRUE(std::isfinite(state.logbook.back().best));
    }
    EXPECT_GT(invalidSeen + state.logbook.front().invalid, 0) << "the test should exercise failures";
}

TEST(Ga, GenomesStayWithinTheirBounds) {
    auto def = SmallGa();
    def.genome.splines = 4;
    def.genome.lengthMin = 5;
    def.genome.lengthMax = 7;
    def.indpb = 0.5;
    def.mutpb = 1.0;
    const sim::MeshDef mesh;
    auto state = sim::StartEvolution(def, mesh, 11, Synthetic);
    std::set<size_t> lengths;
    for (int g = 0; g < 15; ++g) {
        ASSERT_TRUE(sim::EvolveOneGeneration(def, mesh, state, Synthetic));
        for (const auto& individual : state.population) {
            ASSERT_EQ(individual.genome.size(), 4u);
            for (const auto& spline : individual.genome) {
                EXPECT_GE(spline.size(), 5u);
                EXPECT_LE(spline.size(), 7u);
                lengths.insert(spline.size());
                for (double c : spline) {
                    EXPECT_GE(c, 0);
                    EXPECT_LE(c, 8);
                    EXPECT_EQ(c, std::round(c));
                }
            }
        }
    }
    EXPECT_EQ(lengths.size(), 3u) << "mutation should grow and shrink splines across the whole range";
}

// A control grid finer than the thesis's integers: every control point the GA draws or mutates lies
// on it, and the grid's every point is reached.
TEST(Ga, ControlPointsStayOnAFinerGrid) {
    auto def = SmallGa();
    def.genome.controlMin = 0.5;
    def.genome.controlMax = 2.5;
    def.genome.controlStep = 0.25;
    def.indpb = 0.5;
    def.mutpb = 1.0;
    ASSERT_EQ(sim::GaDefError(def, sim::MeshDef{}), "");
    const sim::MeshDef mesh;
    auto state = sim::StartEvolution(def, mesh, 5, Synthetic);
    std::set<double> seen;
    for (int g = 0; g < 10; ++g) {
        ASSERT_TRUE(sim::EvolveOneGeneration(def, mesh, state, Synthetic));
        for (const auto& individual : state.population)
            for (const auto& spline : individual.genome)
                for (double c : spline) {
                    EXPECT_TRUE(def.genome.OnControlGrid(c)) << c;
                    seen.insert(c);
                }
    }
    EXPECT_EQ(seen.size(), 9u) << "0.5, 0.75, ..., 2.5";
    EXPECT_FALSE(def.genome.OnControlGrid(0.6));
    EXPECT_FALSE(def.genome.OnControlGrid(2.75));
    def.genome.controlStep = 0.3;  // 2 / 0.3 is no whole number of steps
    EXPECT_THAT(sim::GaDefError(def, mesh), testing::HasSubstr("must divide the control range"));
    def.genome.controlStep = 0;
    EXPECT_THAT(sim::GaDefError(def, mesh), testing::HasSubstr("control step must be positive"));
}

TEST(Ga, FreeXYMutationAndCrossoverRespectTheBound) {
    sim::GaDef def;
    def.population = 8;
    def.elite = 1;
    def.mutpb = 1;
    def.indpb = 0.3;
    def.cxpb = 1;
    def.genome.kind = sim::GenomeKind::FreeXY;
    def.genome.sigma = 0.8;
    def.genome.bound = 1.0;
    const sim::MeshDef mesh{12, 6};
    auto sumOfSquares = [](const std::vector<const sim::Genome*>& genomes) {
        std::vector<std::pair<double, sim::Status>> out;
        for (const auto* g : genomes) {
            double f = 0;
            for (double v : (*g)[0]) f -= v * v;
            out.push_back({f, sim::Status::Ok});
        }
        return out;
    };
    auto state = sim::StartEvolution(def, mesh, 5, sumOfSquares);
    ASSERT_EQ(state.population[0].genome[0].size(), 2u * 72);
    for (int g = 0; g < 10; ++g) {
        ASSERT_TRUE(sim::EvolveOneGeneration(def, mesh, state, sumOfSquares));
        for (const auto& individual : state.population)
            for (double v : individual.genome[0]) {
                EXPECT_GE(v, -1.0);
                EXPECT_LE(v, 1.0);
            }
    }
    const auto shape = sim::ShapeOfGenome(state.population[0].genome, def.genome, mesh);
    EXPECT_EQ(sim::ShapeError(shape, mesh), "");
}

TEST(Ga, GenomeShapesAreValidBSplines) {
    const sim::GenomeDef g;
    const sim::Genome genome{{8, 8, 0, 4, 0, 0, 2}};
    const auto shape = sim::ShapeOfGenome(genome, g, sim::MeshDef{});
    EXPECT_EQ(sim::ShapeError(shape, sim::MeshDef{}), "");
    EXPECT_EQ(sim::GenomeText({{8, 8, 0}, {1.5, 2}}), "8,8,0;1.5,2");
}
