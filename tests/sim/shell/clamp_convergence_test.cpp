// The same physical problem at every mesh (docs/models/shell.md section 2): each end clamp holds a
// length in millimetres, not a number of rings. The clamp is checked on the built problem at several
// meshes, and the plain tube's contraction converges as the mesh refines with it fixed, where a
// clamp of two rings (L / (H - 1), shrinking with the mesh) made a different problem at each
// refinement and the sequence turned back. Label `verification`.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shell/shell_problem.h"
#include "sim/batch.h"

namespace {

sim::ShellDef Tube(int ringVertices, int rings) {
    sim::ShellDef d;
    d.geometry.ringVertices = ringVertices;
    d.geometry.rings = rings;
    return d;
}

// The held length at the bottom: the highest rest height of a vertex the bottom clamp fixes.
double BottomClampMm(const sim::ShellProblem& p) {
    double held = 0;
    for (int v = 0; v < p.rest.Size(); ++v)
        if (p.dofOf[3 * v + 2] == sim::kFixed && p.rest.z[v] < 0.5 * p.rest.z[p.rest.Size() - 1]) held = std::max(held, p.rest.z[v]);
    return held;
}

TEST(ClampInMillimetres, EveryMeshHoldsTheSameLengthWithARingAtTheClampsEdge) {
    for (const auto& [vertices, rings] : std::vector<std::pair<int, int>>{{30, 30}, {60, 59}, {30, 45}, {24, 0}, {120, 117}, {30, 12}}) {
        for (const double clampMm : {sim::kThesisTubeClampMm, 8.0, 12.5}) {
            sim::ShellDef d = Tube(vertices, rings);
            d.geometry.clampMm = clampMm;
            ASSERT_EQ(sim::ShellDefError(d), "") << vertices << " x " << rings << ", clamp " << clampMm;
            std::string error;
            const sim::ShellProblem p = sim::BuildTubeProblem(d, sim::CylinderShape{}, true, &error);
            ASSERT_EQ(error, "");
            EXPECT_NEAR(BottomClampMm(p), clampMm, 1e-9 * d.geometry.lengthMm) << vertices << " x " << rings << ", clamp " << clampMm;
            // Heights rise ring by ring, and the top clamp mirrors the bottom.
            const int H = sim::RingCount(d.geometry);
            for (int j = 1; j < H; ++j) EXPECT_GT(sim::RingHeightMm(d.geometry, j), sim::RingHeightMm(d.geometry, j - 1));
            EXPECT_NEAR(sim::RingHeightMm(d.geometry, H - 1 - sim::ClampIntervals(d.geometry)), d.geometry.lengthMm - clampMm, 1e-9 * d.geometry.lengthMm);
        }
    }
    // The default is one ring spacing of the 30-ring thesis tube: two rings there, three at 59 rings.
    EXPECT_EQ(sim::ClampRingCount(Tube(30, 30).geometry), 2);
    EXPECT_EQ(sim::ClampRingCount(Tube(60, 59).geometry), 3);
    EXPECT_EQ(sim::ClampRingCount(Tube(120, 117).geometry), 5);
}

TEST(ClampInMillimetres, ATubeWithoutFreeLengthOrFreeRingsIsRefused) {
    sim::ShellDef d = Tube(30, 30);
    d.geometry.clampMm = 80;
    EXPECT_NE(sim::ShellDefError(d).find("no free length"), std::string::npos) << sim::ShellDefError(d);
    d.geometry.clampMm = 70;
    EXPECT_NE(sim::ShellDefError(d).find("free rings"), std::string::npos) << sim::ShellDefError(d);
    d.geometry.clampMm = 0;
    EXPECT_NE(sim::ShellDefError(d).find("clamp length"), std::string::npos) << sim::ShellDefError(d);
}

// The plain tube of the thesis's size (R 5 mm, L 150 mm, 1 mm of Ecoflex 00-30) inflated to 1 kPa,
// meshed 30 x 30, 60 x 59 and 120 x 117 (every edge halved twice). With the clamp fixed at 5.17 mm
// the contraction converges monotonically at about second order (measured: -0.7032, -0.6434,
// -0.6341 %, differences 0.060 and 0.0092: order 2.7). With clamps of two rings it read -0.7032,
// -0.6646, -0.6660 %: not a sequence that converges to anything.
TEST(ClampInMillimetres, ThePlainTubeConvergesAsTheMeshRefinesWithTheClampFixed) {
    std::vector<double> contraction;
    for (const auto& [vertices, rings] : std::vector<std::pair<int, int>>{{30, 30}, {60, 59}, {120, 117}}) {
        sim::EvalJob job;
        job.SetModel(sim::ModelKind::Shell);
        job.shape = sim::CylinderShape{};
        job.Shell().geometry.ringVertices = vertices;
        job.Shell().geometry.rings = rings;
        job.Shell().load.pressureKpa = 1;
        const sim::SimResult r = sim::Evaluate(job);
        ASSERT_EQ(r.status, sim::Status::Ok) << vertices << " x " << rings;
        contraction.push_back(r.contractionPercent);
    }
    const double first = contraction[1] - contraction[0], second = contraction[2] - contraction[1];
    EXPECT_GT(first * second, 0) << "monotone: " << contraction[0] << ", " << contraction[1] << ", " << contraction[2];
    const double order = std::log2(std::fabs(first / second));
    EXPECT_GT(order, 1.5) << "observed order " << order;
    EXPECT_LT(std::fabs(second), 0.02 * std::fabs(contraction[2])) << "the finest two within 2 %";
}

}  // namespace
