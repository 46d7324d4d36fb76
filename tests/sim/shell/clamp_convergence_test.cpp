// The same physical problem at every mesh (docs/models/shell.md section 2): each end clamp holds a
// length in millimetres, not a number of rings. The clamp is checked on the built problem at several
// meshes, evenly spaced and graded, and four designs' contractions converge as the graded mesh
// refines with it fixed, where a clamp of two rings (L / (H - 1), shrinking with the mesh) made a
// different problem at each refinement. Label `verification`.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
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
    for (const auto& [vertices, rings] : std::vector<std::pair<int, int>>{{30, 30}, {60, 59}, {30, 45}, {24, 0}, {120, 117}, {30, 12}})
        for (const double edgeSpacingMm : {0.0, 0.35, 2.0})
        for (const double clampMm : {sim::kThesisTubeClampMm, 8.0, 12.5}) {
            sim::ShellDef d = Tube(vertices, rings);
            d.geometry.clampMm = clampMm;
            d.geometry.edgeSpacingMm = edgeSpacingMm;
            d.contact.mode = sim::ContactMode::Off;  // only the rings are looked at (a fine mesh's contact surface takes a second)
            SCOPED_TRACE(::testing::Message() << vertices << " x " << rings << " / " << edgeSpacingMm << " mm, clamp " << clampMm);
            ASSERT_EQ(sim::ShellDefError(d), "") << vertices << " x " << rings << ", clamp " << clampMm;
            std::string error;
            const sim::ShellProblem p = sim::BuildTubeProblem(d, sim::CylinderShape{}, true, &error);
            ASSERT_EQ(error, "");
            EXPECT_NEAR(BottomClampMm(p), clampMm, 1e-9 * d.geometry.lengthMm) << vertices << " x " << rings << ", clamp " << clampMm;
            // Heights rise ring by ring, and the top clamp mirrors the bottom.
            const int H = sim::RingCount(d.geometry);
            const std::vector<double> z = sim::RingHeightsMm(d.geometry);
            ASSERT_EQ(static_cast<int>(z.size()), H);
            for (int j = 1; j < H; ++j) EXPECT_GT(z[j], z[j - 1]);
            EXPECT_NEAR(z[H - 1 - sim::ClampIntervals(d.geometry)], d.geometry.lengthMm - clampMm, 1e-9 * d.geometry.lengthMm);
            // Graded: the first free spacing is the edge spacing asked for, mirrored inside the clamp,
            // and no spacing is longer than the middle's.
            sim::GeometryDef evenly = d.geometry;
            evenly.edgeSpacingMm = 0;
            if (edgeSpacingMm > 0 && edgeSpacingMm < d.geometry.lengthMm / (sim::RingCount(evenly) - 1)) {
                const int k = sim::ClampIntervals(d.geometry);
                EXPECT_NEAR(z[k + 1] - z[k], edgeSpacingMm, 1e-9);
                EXPECT_NEAR(z[k] - z[k - 1], edgeSpacingMm, 1e-9);
                EXPECT_NEAR(z[H - k] - z[H - 1 - k], edgeSpacingMm, 1e-9);
            }
        }
    // Evenly spaced, the default clamp is one ring spacing of the 30-ring thesis tube: two rings there,
    // three at 59 rings. Graded, each clamp holds three rings, and 30 rings become 40.
    auto even = [](int vertices, int rings) {
        sim::ShellDef d = Tube(vertices, rings);
        d.geometry.edgeSpacingMm = 0;
        return d.geometry;
    };
    EXPECT_EQ(sim::ClampRingCount(even(30, 30)), 2);
    EXPECT_EQ(sim::ClampRingCount(even(60, 59)), 3);
    EXPECT_EQ(sim::ClampRingCount(even(120, 117)), 5);
    EXPECT_EQ(sim::ClampRingCount(Tube(30, 30).geometry), 3);
    EXPECT_EQ(sim::RingCount(Tube(30, 30).geometry), 40);
}

TEST(ClampInMillimetres, ATubeWithoutFreeLengthOrFreeRingsIsRefused) {
    sim::ShellDef d = Tube(30, 30);
    d.geometry.clampMm = 80;
    EXPECT_NE(sim::ShellDefError(d).find("no free length"), std::string::npos) << sim::ShellDefError(d);
    d.geometry.clampMm = 70;
    d.geometry.edgeSpacingMm = 0;
    EXPECT_NE(sim::ShellDefError(d).find("free rings"), std::string::npos) << sim::ShellDefError(d);
    d.geometry.clampMm = 0;
    EXPECT_NE(sim::ShellDefError(d).find("clamp length"), std::string::npos) << sim::ShellDefError(d);
}

// Convergence of the four designs of docs/models/shell.md section 2 on the thesis tube (R 5 mm, L 150
// mm, 1 mm of Ecoflex 00-30, clamps 5.17 mm) at 1 kPa, on the graded family R x rings / edge spacing
// 15 x 15 / 2 mm, 30 x 30 / 1 mm (the default), 60 x 59 / 0.5 mm (every length halved, the clamps
// the same length). The differences shrink at about second order (1.5-1.8 on these coarse levels,
// 1.9-2.0 from 60 x 59 to 120 x 117): the hinge on each clamp's edge weighs its angle over the free
// triangle alone (section 4). Over both triangles, as before, the plain tube and the sine converged at
// order 0.7 and 1.0 and the default was 3.6 % and 2.8 % off. The default is within 2 % of the
// converged answer, section 2's reference (the finer family up to 120 x 117, extrapolated), which
// this family's own second-order extrapolation reproduces within 0.5 %, and nearer than the evenly
// spaced 30 x 30 it replaced. Had the clamp followed the ring count again, each level would be
// another problem and the sequence would not converge to it.
struct Design {
    const char* name;
    sim::Shape shape;
    double referencePercent;  // contraction at 1 kPa, docs/models/shell.md section 2
    sim::FibreLayout fibres = sim::FibreLayout::None;
    double fibreAngleDeg = 0;
};

double ContractionAt1Kpa(const Design& design, int ringVertices, int rings, double edgeSpacingMm) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    job.shape = design.shape;
    sim::ShellDef& d = job.Shell();
    d.geometry.ringVertices = ringVertices;
    d.geometry.rings = rings;
    d.geometry.edgeSpacingMm = edgeSpacingMm;
    d.fibres.layout = design.fibres;
    d.fibres.angleDeg = design.fibreAngleDeg;
    d.load.pressureKpa = 1;
    const sim::SimResult r = sim::Evaluate(job);
    EXPECT_EQ(r.status, sim::Status::Ok) << design.name << " " << ringVertices << " x " << rings << " / " << edgeSpacingMm << " mm";
    return r.contractionPercent;
}

struct Convergence {
    double coarse, middle, fine, order, extrapolated;
};

Convergence GradedFamily(const Design& design) {
    const sim::GeometryDef defaults;
    EXPECT_EQ(defaults.edgeSpacingMm, 1) << "the family's middle level is the default mesh";
    Convergence c;
    c.coarse = ContractionAt1Kpa(design, 15, 15, 2.0);
    c.middle = ContractionAt1Kpa(design, defaults.ringVertices, defaults.rings, defaults.edgeSpacingMm);
    c.fine = ContractionAt1Kpa(design, 60, 59, 0.5);
    const double first = c.middle - c.coarse, second = c.fine - c.middle;
    c.order = std::log2(std::fabs(first / second));
    c.extrapolated = c.fine + (c.fine - c.middle) / 3;  // Richardson, second order
    return c;
}

void ExpectTheDefaultNearTheConvergedAnswer(const Design& design, const Convergence& c) {
    EXPECT_LT(std::fabs(c.middle / design.referencePercent - 1), 0.02) << "the default mesh against the reference " << design.referencePercent << " %";
    EXPECT_LT(std::fabs(c.extrapolated / design.referencePercent - 1), 0.005) << "the family's extrapolation against the reference";
}

void ExpectConvergesAtSecondOrder(const Design& design) {
    const Convergence c = GradedFamily(design);
    SCOPED_TRACE(::testing::Message() << design.name << ": " << c.coarse << ", " << c.middle << ", " << c.fine << " %, order " << c.order
                                      << ", extrapolated " << c.extrapolated << " %");
    EXPECT_GT((c.middle - c.coarse) * (c.fine - c.middle), 0) << "monotone";
    EXPECT_GE(c.order, 1.3);
    EXPECT_LE(c.order, 2.5);
    ExpectTheDefaultNearTheConvergedAnswer(design, c);
    const double evenlySpaced = ContractionAt1Kpa(design, 30, 30, 0);
    EXPECT_GT(std::fabs(evenlySpaced / design.referencePercent - 1), std::fabs(c.middle / design.referencePercent - 1))
        << "evenly spaced 30 x 30: " << evenlySpaced << " %";
}

TEST(MeshConvergence, ThePlainTube) { ExpectConvergesAtSecondOrder({"plain tube", sim::CylinderShape{}, -0.655}); }

TEST(MeshConvergence, TheSineOfAmplitude1_3) { ExpectConvergesAtSecondOrder({"sine A = 1.3", sim::SineShape{1.3, 0.5, std::numbers::pi - 0.5}, -0.771}); }

// The +/-70 deg braid's nearly inextensible threads are a constraint, read once per fibre cell (two
// triangles; docs/models/shell.md section 7). Read per triangle they locked the wall: evenly spaced
// 30 x 30 was 7.9 % short of the reference and the graded family converged from 1.1 % short. With
// cells the default and evenly spaced 30 x 30 are within 0.05 %, 60 x 59 / 0.5 mm and 120 x 117 /
// 0.25 mm within 0.2 % (-3.0800, -3.0793 %: no order to observe; those levels, whose held states
// bow, cost 20 s and are left to docs/models/shell.md section 2's table).
TEST(MeshConvergence, TheBraidAt70Degrees) {
    const Design braid{"braid +/-70 deg", sim::CylinderShape{}, -3.075, sim::FibreLayout::Braid, 70};
    const double coarse = ContractionAt1Kpa(braid, 15, 15, 2.0), middle = ContractionAt1Kpa(braid, 30, 30, 1.0);
    SCOPED_TRACE(::testing::Message() << "15 x 15 / 2 mm " << coarse << " %, default " << middle << " %");
    EXPECT_LT(std::fabs(middle / braid.referencePercent - 1), 0.005);
    EXPECT_LT(std::fabs(middle - braid.referencePercent), std::fabs(coarse - braid.referencePercent));
    const double evenlySpaced = ContractionAt1Kpa(braid, 30, 30, 0);
    EXPECT_LT(std::fabs(evenlySpaced / braid.referencePercent - 1), 0.005) << "evenly spaced 30 x 30: " << evenlySpaced << " % (locked: 7.9 % short)";
}

// The +/-30 deg braid's fibres hold the wall's shape: the three levels agree within 1.4 %, and the
// 120 x 117 level reads the same as 60 x 59 within 0.01 %, so there is no order to observe.
TEST(MeshConvergence, TheBraidAt30Degrees) {
    const Design braid{"braid +/-30 deg", sim::CylinderShape{}, 3.093, sim::FibreLayout::Braid, 30};
    const Convergence c = GradedFamily(braid);
    SCOPED_TRACE(::testing::Message() << c.coarse << ", " << c.middle << ", " << c.fine << " %");
    EXPECT_LT(std::fabs(c.middle - c.fine), std::fabs(c.coarse - c.fine));
    ExpectTheDefaultNearTheConvergedAnswer(braid, c);
}

// Held states at every mesh (docs/models/shell.md section 12): the +/-70 deg braid (it lengthens
// under pressure) held at its rest length at 3 kPa pushes on its clamps, and bowed sideways it has
// far lower energy than straight. Every mesh must report the bowed state, its force the same within
// the mesh error. With the fibres read per triangle the wall locked: the straight state (-0.172 N)
// was stable at 30 x 30 and 60 x 59, and once pushed to the bow its force converged at first order
// (30 x 30 / 1 mm, 60 x 59 / 0.5 mm, 60 x 117 / 0.25 mm: -0.071, -0.054, -0.046 N). Read per fibre
// cell (docs/models/shell.md section 7) Newton finds the bow by itself and the force reads -0.041 N at
// 30 x 30 and -0.039 N at 60 x 59 / 0.5 mm.
struct HeldState {
    double forceN, bowMm;
};

// The +/-70 deg braid on the thesis tube at 3 kPa, on the default mesh.
sim::EvalJob BraidAt3Kpa() {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    job.shape = sim::CylinderShape{};
    sim::ShellDef& d = job.Shell();
    d.fibres.layout = sim::FibreLayout::Braid;
    d.fibres.angleDeg = 70;
    d.load.pressureKpa = 3;
    return job;
}

HeldState BraidHeldAtRestLength(int ringVertices, int rings, double edgeSpacingMm) {
    sim::EvalJob job = BraidAt3Kpa();
    sim::ShellDef& d = job.Shell();
    d.geometry.ringVertices = ringVertices;
    d.geometry.rings = rings;
    d.geometry.edgeSpacingMm = edgeSpacingMm;
    d.load.kind = sim::ShellLoad::Blocked;
    d.load.steps = 1;  // the end state alone: each recorded step's push costs as much again
    const sim::SimResult r = sim::Evaluate(job);
    EXPECT_EQ(r.status, sim::Status::Ok) << ringVertices << " x " << rings;
    return {r.shell.blockingForceN, r.shell.heldBowMm};
}

TEST(HeldStates, ACompressedBraidBowsSidewaysAtEveryMesh) {
    // Refined along the axis, which decides a bow (60 x 59 / 0.5 mm reads -0.0387 N in 12 s, 30 x 59
    // / 0.5 mm -0.0385 N in 4 s; per triangle 30 x 59 read -0.054 N).
    const HeldState coarse = BraidHeldAtRestLength(30, 30, 1.0), fine = BraidHeldAtRestLength(30, 59, 0.5);
    SCOPED_TRACE(::testing::Message() << "30 x 30: " << coarse.forceN << " N, bowed " << coarse.bowMm << " mm; 30 x 59: " << fine.forceN << " N, "
                                      << fine.bowMm << " mm");
    for (const HeldState& held : {coarse, fine}) {
        EXPECT_GT(held.bowMm, 15);                                 // straight: 0
        EXPECT_LT(held.forceN, 0);                                 // it still pushes,
        EXPECT_GT(held.forceN, -0.09);                             // far less than straight (-0.172 N)
    }
    EXPECT_NEAR(coarse.forceN, fine.forceN, 0.1 * std::fabs(fine.forceN)) << "the same force within the mesh error (locked: 31 % apart)";
    EXPECT_NEAR(coarse.bowMm, fine.bowMm, 0.1 * fine.bowMm);
}

// Three routes to the braid held at its rest length end at the same bowed state: the blocking force
// (from the free inflation), the isobaric curve's point at no stroke (from half its stroke) and the
// blocked test (stepped with the pressure, each step pushed).
TEST(HeldStates, EveryRouteToTheHeldBraidEndsBowed) {
    sim::EvalJob job = BraidAt3Kpa();
    job.Shell().load.isobaricPoints = 3;
    const sim::SimResult r = sim::Evaluate(job);
    ASSERT_EQ(r.status, sim::Status::Ok);
    ASSERT_EQ(r.shell.isobaricForceN.size(), 3u);
    EXPECT_GT(r.shell.blockingForceN, -0.09) << "bowed";
    EXPECT_GT(r.shell.heldBowMm, 15);
    EXPECT_NEAR(r.shell.isobaricForceN[0], r.shell.blockingForceN, 1e-6);
    job.Shell().load.kind = sim::ShellLoad::Blocked;
    const sim::SimResult blocked = sim::Evaluate(job);
    ASSERT_EQ(blocked.status, sim::Status::Ok);
    EXPECT_NEAR(blocked.shell.strokeForceN, r.shell.blockingForceN, 1e-6);
    EXPECT_NEAR(blocked.shell.heldBowMm, r.shell.heldBowMm, 1e-3);
}

}  // namespace

// A blocked test that follows a held tube as it bows: this design (reproduce part 2's S5.2 GA,
// Ecoflex 00-30 at 0.4 kPa) bows from its second step and ends bowed 18 mm. From the third step's
// bowed state the load step's tangent predicts a move of tens of metres, mostly the bow turning
// about the axis (a direction that costs almost nothing on a round tube), and Newton ran away from it
// at every increment down to 1.5 Pa: the test ended at a limit point at 0.3 kPa. From the last state
// the step converges, to the held state the free inflation's blocking force finds.
TEST(HeldStates, ABlockedTestFollowsTheTubeAsItBows) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    sim::BSplineShape shape;  // over the middle
    shape.splines = {{7, 3, 7, 4, 3, 3, 6, 0, 5, 1, 0, 7, 0, 0}};
    job.shape = shape;
    job.Shell().load.pressureKpa = 0.4;
    const sim::SimResult free = sim::Evaluate(job);
    ASSERT_EQ(free.status, sim::Status::Ok);
    EXPECT_GT(free.shell.heldBowMm, 15);
    job.Shell().load.kind = sim::ShellLoad::Blocked;
    const sim::SimResult blocked = sim::Evaluate(job);
    ASSERT_EQ(blocked.status, sim::Status::Ok) << "limit point at " << blocked.shell.limitPressureKpa << " kPa";
    EXPECT_NEAR(blocked.shell.strokeForceN, free.shell.blockingForceN, 1e-6);
    EXPECT_NEAR(blocked.shell.heldBowMm, free.shell.heldBowMm, 1e-3);
    ASSERT_EQ(blocked.shell.curveForceN.size(), 4u);
    for (size_t k = 1; k < blocked.shell.curveForceN.size(); ++k) EXPECT_LT(blocked.shell.curveForceN[k], blocked.shell.curveForceN[k - 1]) << "pushing harder as the pressure rises";
}

// A held state through itself has no force to report. This S5.2 design (a row of bulbs up to six
// radii wide) inflates freely to 0.4 kPa without meeting itself, but held at its rest length its
// bulbs are pushed into one another: the blocked test ends self-intersection, and with contact on the
// walls touch (hundreds of pairs) and hold the clamp with about -0.18 N. The free inflation's
// blocking force reported -0.081 N from the state through itself; it reports none.
TEST(HeldStates, AHeldStateThroughItselfHasNoForce) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    sim::BSplineShape shape;  // over the middle
    shape.splines = {{5, 1, 6, 0, 2, 6, 1, 6, 2, 4, 0, 6, 3, 4, 8, 1}};
    job.shape = shape;
    job.Shell().load.pressureKpa = 0.4;
    job.Shell().contact.mode = sim::ContactMode::Off;
    const sim::SimResult free = sim::Evaluate(job);
    ASSERT_EQ(free.status, sim::Status::Ok);
    EXPECT_TRUE(std::isnan(free.shell.blockingForceN)) << free.shell.blockingForceN << " N";
    EXPECT_TRUE(std::isnan(free.shell.heldBowMm));
    job.Shell().load.kind = sim::ShellLoad::Blocked;
    EXPECT_EQ(sim::Evaluate(job).status, sim::Status::SelfIntersection);
    job.Shell().contact.mode = sim::ContactMode::On;
    const sim::SimResult touching = sim::Evaluate(job);
    ASSERT_EQ(touching.status, sim::Status::Ok);
    EXPECT_GT(touching.shell.contactPairs, 100);
    EXPECT_NEAR(touching.shell.strokeForceN, -0.18, 0.01);
}
