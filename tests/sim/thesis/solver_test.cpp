// Physics first: known answers from the thesis's tables, invariants of the model, agreement with an
// independent edge-list implementation, numerical failure as a status.
#include "sim/solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "reference_solver.h"

namespace {

constexpr double kPi = std::numbers::pi;

sim::SimParams Params(sim::Load load, sim::Precision precision = sim::Precision::Float, int iterations = 10000) {
    sim::SimParams p = sim::DefaultSimParams();
    p.load = load;
    p.precision = precision;
    p.iterations = iterations;
    return p;
}

// One shape of every family, as a user would give them.
std::vector<std::pair<std::string, sim::Shape>> EveryShape() {
    const sim::MeshDef def = sim::DefaultMeshDef();
    std::vector<double> dx(900), dy(900);
    for (int i = 0; i < 900; ++i) {
        dx[i] = 0.3 * std::sin(0.37 * i);
        dy[i] = 0.3 * std::cos(0.23 * i);
    }
    sim::Positions helixWithBulge = sim::BuildInitialPositions(sim::SineShape{2.0, 0.5, kPi - 0.5}, def);
    return {
        {"cylinder", sim::CylinderShape{}},
        {"sine A=4.1", sim::SineShape{4.1, 0.5, kPi - 0.5}},
        {"abs-sine A=4 [0,4pi]", sim::AbsSineShape{4.0, 0.0, 4 * kPi}},
        {"bspline middle 1 spline", sim::BSplineShape{sim::SplineRegion::Middle, {{8, 8, 0, 4, 0, 0, 2}}}},
        {"bspline entire 1 spline", sim::BSplineShape{sim::SplineRegion::Entire, {{2, 3, 1, 2, 2}}}},
        {"bspline middle 4 splines",
         sim::BSplineShape{sim::SplineRegion::Middle, {{4, 6, 2, 5}, {2, 3, 7, 4, 6}, {5, 5, 1, 2}, {3, 3, 3, 3}}}},
        {"free-xy", sim::FreeXYShape{dx, dy}},
        {"mesh", sim::MeshShape{helixWithBulge}},
    };
}

}  // namespace

// ---- Known answers (docs/models/thesis.md, "Known values") ------------------------------------------

TEST(ThesisValues, AbsSineAmplitude4OverFourPiContracts0964) {
    // Thesis Table 4.4, mesh 1: 0.97. This model: 0.964.
    for (auto precision : {sim::Precision::Float, sim::Precision::Double}) {
        const auto r = sim::Evaluate(sim::AbsSineShape{4.0, 0.0, 4 * kPi}, sim::DefaultMeshDef(), Params(sim::Load::Inflate, precision));
        ASSERT_EQ(r.status, sim::Status::Ok);
        EXPECT_NEAR(r.fitness, 0.964, 0.005) << sim::Name(precision)
                                             << "; reproduce: actuator simulate --shape abs-sine --amplitude 4 --phase 0,4pi";
        EXPECT_NEAR(r.contractionPercent, 100 * r.fitness / 30, 1e-12);
    }
}

TEST(ThesisValues, SineAmplitude41StretchedGivesMinus1718) {
    // Thesis Table 6.1: -1.74. This model: -1.718.
    for (auto precision : {sim::Precision::Float, sim::Precision::Double}) {
        const auto r = sim::Evaluate(sim::SineShape{4.1, 0.5, kPi - 0.5}, sim::DefaultMeshDef(), Params(sim::Load::Stretch, precision));
        ASSERT_EQ(r.status, sim::Status::Ok);
        EXPECT_NEAR(r.fitness, -1.718, 0.005) << sim::Name(precision)
                                              << "; reproduce: actuator simulate --shape sine --amplitude 4.1 --load stretch";
    }
}

TEST(ThesisValues, SineAmplitude41InflatedGives058) {
    // docs/models/thesis.md, weaknesses: 0.58 at 10,000 iterations and 0.25 at 5,000 (a transient, not equilibrium).
    const sim::SineShape shape{4.1, 0.5, kPi - 0.5};
    EXPECT_NEAR(sim::Evaluate(shape, sim::DefaultMeshDef(), Params(sim::Load::Inflate)).fitness, 0.58, 0.005);
    EXPECT_NEAR(sim::Evaluate(shape, sim::DefaultMeshDef(), Params(sim::Load::Inflate, sim::Precision::Float, 5000)).fitness, 0.25, 0.005);
}

// ---- Invariants ---------------------------------------------------------------------------------

TEST(Invariants, AMeshWithNoLoadDoesNotMove) {
    // Rest lengths are the initial lengths, so with no load every spring force is exactly zero.
    for (const auto& [name, shape] : EveryShape()) {
        for (auto precision : {sim::Precision::Float, sim::Precision::Double}) {
            const auto r = sim::Evaluate(shape, sim::DefaultMeshDef(), Params(sim::Load::None, precision, 2000));
            ASSERT_EQ(r.status, sim::Status::Ok) << name;
            EXPECT_EQ(sim::PositionsHash(r.final), sim::PositionsHash(r.initial)) << name << " moved without a load";
            EXPECT_EQ(r.fitness, 0.0) << name;
        }
    }
}

TEST(Invariants, StretchingLengthensEveryShape) {
    for (const auto& [name, shape] : EveryShape()) {
        const auto r = sim::Evaluate(shape, sim::DefaultMeshDef(), Params(sim::Load::Stretch));
        ASSERT_EQ(r.status, sim::Status::Ok) << name;
        EXPECT_LT(r.fitness, -0.01) << name << " did not get longer under the stretch load";
        // The bottom turn went down and the top turn went up.
        EXPECT_LT(r.final.z[0], r.initial.z[0]) << name;
        EXPECT_GT(r.final.z[899], r.initial.z[899]) << name;
    }
}

TEST(Invariants, ClampedTurnsOnlySlideAlongZ) {
    const auto r = sim::Evaluate(sim::SineShape{4.1, 0.5, kPi - 0.5}, sim::DefaultMeshDef(), Params(sim::Load::Inflate));
    for (int i : {0, 29, 59, 840, 899}) {
        EXPECT_EQ(r.final.x[i], r.initial.x[i]) << "vertex " << i;
        EXPECT_EQ(r.final.y[i], r.initial.y[i]) << "vertex " << i;
    }
    EXPECT_NE(r.final.z[0], r.initial.z[0]);
    EXPECT_NE(r.final.x[450], r.initial.x[450]);  // a free vertex does move sideways
}

TEST(Invariants, InflationPushesTheCylinderOutward) {
    const auto r = sim::Evaluate(sim::CylinderShape{}, sim::DefaultMeshDef(), Params(sim::Load::Inflate, sim::Precision::Float, 200));
    const int middle = 450;
    EXPECT_GT(std::hypot(r.final.x[middle], r.final.y[middle]), 1.0 + 1e-3);
}

TEST(Invariants, FloatStaysWithin0005OfDouble) {
    for (const auto& [name, shape] : EveryShape()) {
        for (auto load : {sim::Load::Inflate, sim::Load::Stretch}) {
            const auto f = sim::Evaluate(shape, sim::DefaultMeshDef(), Params(load, sim::Precision::Float));
            const auto d = sim::Evaluate(shape, sim::DefaultMeshDef(), Params(load, sim::Precision::Double));
            ASSERT_EQ(f.status, d.status) << name;
            if (d.status != sim::Status::Ok) continue;
            EXPECT_NEAR(f.fitness, d.fitness, 0.005) << name << " load " << sim::Name(load);
        }
    }
}

TEST(Invariants, AgreesWithAPlainEdgeListImplementation) {
    // Same model, written the obvious way in tests/support/reference_solver.cpp. Differences come only
    // from the order of floating-point sums.
    const sim::MeshDef def = sim::DefaultMeshDef();
    for (const auto& [name, shape] : EveryShape()) {
        for (auto load : {sim::Load::Inflate, sim::Load::Stretch}) {
            const auto params = Params(load, sim::Precision::Double, 3000);
            const auto r = sim::Evaluate(shape, def, params);
            const auto expected = reference::Relax(sim::BuildInitialPositions(shape, def), def, params);
            double worst = 0;
            for (int i = 0; i < 900; ++i)
                worst = std::max({worst, std::fabs(r.final.x[i] - expected.x[i]), std::fabs(r.final.y[i] - expected.y[i]),
                                  std::fabs(r.final.z[i] - expected.z[i])});
            EXPECT_LT(worst, 1e-9) << name << " load " << sim::Name(load);
        }
    }
}

TEST(Invariants, OtherMeshSizesWork) {
    // A shorter, coarser helix still contracts under inflation and is measured over its own turns.
    const sim::MeshDef def{12, 10};
    const auto r = sim::Evaluate(sim::SineShape{2.0, 0.5, kPi - 0.5}, def, Params(sim::Load::Inflate));
    ASSERT_EQ(r.status, sim::Status::Ok);
    EXPECT_EQ(r.final.Size(), 120);
    EXPECT_NEAR(r.contractionPercent, 100 * r.fitness / 10, 1e-12);
}

// ---- Determinism ----------------------------------------------------------------------------------

TEST(Determinism, FinalPositionsHashIsFixed) {
    // Bit-exact across runs and across SSE/AVX2/AVX-512 builds: the hot code is compiled without FP
    // contraction and sums in a fixed order. A change here means the model's arithmetic changed.
    const sim::SineShape shape{4.1, 0.5, kPi - 0.5};
    const auto f = sim::Evaluate(shape, sim::DefaultMeshDef(), Params(sim::Load::Inflate, sim::Precision::Float));
    const auto d = sim::Evaluate(shape, sim::DefaultMeshDef(), Params(sim::Load::Inflate, sim::Precision::Double));
    EXPECT_EQ(sim::PositionsHash(f.final), 0xfe50c0fb8fd636a4ull) << "float; reproduce: actuator simulate --shape sine";
    EXPECT_EQ(sim::PositionsHash(d.final), 0xe80478efac2f502dull) << "double; reproduce: actuator simulate --shape sine --precision double";
    const auto again = sim::Evaluate(shape, sim::DefaultMeshDef(), Params(sim::Load::Inflate, sim::Precision::Float));
    EXPECT_EQ(sim::PositionsHash(again.final), sim::PositionsHash(f.final));
}

// ---- Numerical failure ----------------------------------------------------------------------------

TEST(NumericalFailure, LongRunsEndWithAStatusNotACrash) {
    // docs/models/thesis.md: the A=4.1 sine's positions are NaN by 40,000 iterations; the run stops at the first check.
    const sim::SineShape shape{4.1, 0.5, kPi - 0.5};
    const auto r = sim::Evaluate(shape, sim::DefaultMeshDef(), Params(sim::Load::Inflate, sim::Precision::Double, 40000));
    EXPECT_NE(r.status, sim::Status::Ok);
    EXPECT_TRUE(std::isnan(r.fitness)) << "a failed run must not report a number";
    EXPECT_LT(r.iterationsRun, 40000);
}

TEST(NumericalFailure, NonFiniteWithoutADivergenceBoundIsNaN) {
    sim::SimParams p = Params(sim::Load::Inflate, sim::Precision::Double, 60000);
    p.divergenceLimit = INFINITY;
    const auto r = sim::Evaluate(sim::SineShape{4.1, 0.5, kPi - 0.5}, sim::DefaultMeshDef(), p);
    EXPECT_EQ(r.status, sim::Status::NaN);
    EXPECT_TRUE(std::isnan(r.fitness));
}

TEST(NumericalFailure, RunawayMeshIsDiverged) {
    sim::SimParams p = Params(sim::Load::Inflate, sim::Precision::Float, 10000);
    p.pressureScale = 0.05;  // ten times the thesis's pressure: the mesh balloons without bound
    p.divergenceLimit = 1000;
    const auto r = sim::Evaluate(sim::CylinderShape{}, sim::DefaultMeshDef(), p);
    EXPECT_EQ(r.status, sim::Status::Diverged);
    EXPECT_TRUE(std::isnan(r.fitness));
}

TEST(NumericalFailure, ZeroLengthSpringExertsNoForce) {
    // Two vertices on top of each other (as B-spline genomes with zero control points can make).
    const sim::MeshDef def = sim::DefaultMeshDef();
    sim::Positions p = sim::BaseHelix(def);
    p.x[301] = p.x[300];
    p.y[301] = p.y[300];
    p.z[301] = p.z[300];
    for (auto precision : {sim::Precision::Float, sim::Precision::Double}) {
        const auto r = sim::Simulate(p, def, Params(sim::Load::Inflate, precision, 500));
        EXPECT_EQ(r.status, sim::Status::Ok) << sim::Name(precision);
        EXPECT_TRUE(std::isfinite(r.fitness));
    }
}

TEST(Observer, SeesSnapshotsAtItsIntervalAndCanStop) {
    std::vector<int> seen;
    sim::SimObserver observer;
    observer.interval = 250;
    observer.onSnapshot = [&](int iteration, const sim::Positions& positions) {
        EXPECT_EQ(positions.Size(), 900);
        seen.push_back(iteration);
        return iteration < 750;
    };
    const sim::MeshDef def = sim::DefaultMeshDef();
    const auto r = sim::Simulate(sim::BaseHelix(def), def, Params(sim::Load::Inflate, sim::Precision::Float, 2000), &observer);
    EXPECT_EQ(seen, (std::vector<int>{0, 250, 500, 750}));
    EXPECT_EQ(r.iterationsRun, 750);
}
