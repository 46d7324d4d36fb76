#include "sim/shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {
double Radius(const sim::Positions& p, int i) { return std::hypot(p.x[i], p.y[i]); }
}  // namespace

TEST(BSpline, ConstantControlPointsGiveAConstantCurve) {
    // The cubic B-spline basis sums to one everywhere.
    const std::vector<double> c(7, 2.5);
    for (double t = 0; t <= 1.0; t += 0.01) EXPECT_NEAR(sim::EvaluateBSpline(c, t), 2.5, 1e-12) << "t=" << t;
}

TEST(BSpline, MatchesTheModelFormulaAtKnots) {
    // At u = 0 the curve is (c_s + 4 c_{s+1} + c_{s+2}) / 6.
    const std::vector<double> c{8, 8, 0, 4, 0, 0, 2};
    EXPECT_NEAR(sim::EvaluateBSpline(c, 0.0), (8 + 4 * 8 + 0) / 6.0, 1e-12);
    EXPECT_NEAR(sim::EvaluateBSpline(c, 0.25), (8 + 4 * 0 + 4) / 6.0, 1e-12);  // x = 1
    // t = 1: x = m-3 = 4, s clamped to m-4 = 3, u = 1: (c_4 + 4 c_5 + c_6) / 6.
    EXPECT_NEAR(sim::EvaluateBSpline(c, 1.0), (0 + 4 * 0 + 2) / 6.0, 1e-12);
}

TEST(Shapes, MiddleRegionLeavesClampedTurnsAtRadiusOne) {
    const sim::MeshDef def{30, 30};
    sim::BSplineShape s{sim::SplineRegion::Middle, {{3, 3, 3, 3}}};
    const auto p = sim::BuildInitialPositions(s, def);
    for (int i = 0; i < 60; ++i) EXPECT_NEAR(Radius(p, i), 1.0, 1e-12);
    for (int i = 60; i < 840; ++i) EXPECT_NEAR(Radius(p, i), 3.0, 1e-12);
    for (int i = 840; i < 900; ++i) EXPECT_NEAR(Radius(p, i), 1.0, 1e-12);
}

TEST(Shapes, FourSplinesSplitEachTurnIntoQuarterSectors) {
    const sim::MeshDef def{30, 30};
    sim::BSplineShape s{sim::SplineRegion::Entire, {{1, 1, 1, 1}, {2, 2, 2, 2}, {3, 3, 3, 3}, {4, 4, 4, 4}}};
    const auto p = sim::BuildInitialPositions(s, def);
    for (int i = 0; i < 900; ++i) {
        const int sector = ((i % 30) * 4) / 30;  // 0-7 -> 0, 8-14 -> 1, 15-22 -> 2, 23-29 -> 3
        EXPECT_NEAR(Radius(p, i), sector + 1.0, 1e-12) << "vertex " << i;
    }
}

TEST(Shapes, SineFollowsItsPhaseRangeAndMayPassThroughTheAxis) {
    const sim::MeshDef def{30, 30};
    const auto p = sim::BuildInitialPositions(sim::SineShape{2.0, 0.0, 2 * std::numbers::pi}, def);
    // t = i/(N-1); rho = 2 sin(2 pi t). Vertex 600: t = 600/899.
    const double rho = 2.0 * std::sin(2 * std::numbers::pi * 600 / 899.0);
    ASSERT_LT(rho, 0);
    EXPECT_NEAR(p.x[600], rho * std::sin(2 * std::numbers::pi * 600 / 30), 1e-12);
    EXPECT_NEAR(p.y[600], rho * std::cos(2 * std::numbers::pi * 600 / 30), 1e-12);
    const auto q = sim::BuildInitialPositions(sim::AbsSineShape{2.0, 0.0, 2 * std::numbers::pi}, def);
    EXPECT_NEAR(Radius(q, 600), -rho, 1e-12);
}

TEST(Shapes, FreeXYAddsOffsetsToTheHelix) {
    const sim::MeshDef def{30, 5};
    sim::FreeXYShape s{std::vector<double>(150, 0.25), std::vector<double>(150, -0.5)};
    const auto p = sim::BuildInitialPositions(s, def);
    const auto base = sim::BaseHelix(def);
    for (int i = 0; i < 150; ++i) {
        EXPECT_DOUBLE_EQ(p.x[i], base.x[i] + 0.25);
        EXPECT_DOUBLE_EQ(p.y[i], base.y[i] - 0.5);
        EXPECT_DOUBLE_EQ(p.z[i], base.z[i]);
    }
}

TEST(Shapes, ErrorsNameTheProblem) {
    const sim::MeshDef def{30, 30};
    EXPECT_EQ(sim::ShapeError(sim::CylinderShape{}, def), "");
    EXPECT_NE(sim::ShapeError(sim::BSplineShape{sim::SplineRegion::Middle, {{1, 2, 3}}}, def).find("at least 4"), std::string::npos);
    EXPECT_NE(sim::ShapeError(sim::BSplineShape{sim::SplineRegion::Middle, {{1, 2, 3, 4}, {1, 2, 3, 4}, {1, 2, 3, 4}}}, def)
                  .find("1, 2 or 4"),
              std::string::npos);
    EXPECT_NE(sim::ShapeError(sim::SineShape{NAN, 0, 1}, def).find("amplitude"), std::string::npos);
    EXPECT_NE(sim::ShapeError(sim::MeshShape{sim::BaseHelix({30, 29})}, def).find("870 vertices, expected 900"), std::string::npos);
    EXPECT_NE(sim::ShapeError(sim::CylinderShape{}, sim::MeshDef{30, 4}).find("turns"), std::string::npos);
}
