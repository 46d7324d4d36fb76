// The envelope (docs/models/shell.md section 12, envelope): a design's rest measures against closed
// forms, and a design beyond a bound is outside-envelope before anything is simulated.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/model.h"
#include "sim/optimize.h"

namespace {

sim::EvalJob ShortTube(const sim::Shape& shape) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Membrane);
    job.shape = shape;
    job.Shell().geometry.lengthMm = 40;
    job.Shell().geometry.ringVertices = 24;
    job.Shell().geometry.rings = 12;
    job.Shell().load.pressureKpa = 0.5;
    job.Shell().load.steps = 2;
    return job;
}

// The rest wall of a plain tube: its vertices on the circle of radius R, its triangles' area that of
// the inscribed prism of R's polygon (staggered rings: each band's triangles span a polygon's side).
TEST(Envelope, ATubesRestMeasuresAreItsClosedForms) {
    const sim::EvalJob job = ShortTube(sim::CylinderShape{});
    const sim::SimResult r = sim::Evaluate(job);
    ASSERT_EQ(r.status, sim::Status::Ok);
    const sim::GeometryDef& g = job.Shell().geometry;
    EXPECT_NEAR(r.shell.restMaxRadiusMm, g.radiusMm, 1e-12);
    const int n = g.ringVertices;
    const double prismArea = n * 2 * g.radiusMm * std::sin(std::numbers::pi / n) * g.lengthMm;  // mm^2
    const double expectedG = prismArea * g.thicknessMm * job.Shell().material.densityKgPerM3 * 1e-6;
    // Staggered rings make the bands' triangles slant a little: within 0.5 % of the prism.
    EXPECT_NEAR(r.shell.siliconeG / expectedG, 1, 5e-3);
    EXPECT_GT(r.shell.siliconeG, expectedG * (1 - 1e-12));
}

TEST(Envelope, ADesignBeyondABoundIsOutsideItBeforeAnythingIsSimulated) {
    // A sine bulb of amplitude 2: its widest ring lies near 2 R.
    sim::EvalJob bulb = ShortTube(sim::SineShape{2.0, 0.5, std::numbers::pi - 0.5});
    const sim::SimResult free = sim::Evaluate(bulb);
    ASSERT_EQ(free.status, sim::Status::Ok);
    const double reach = free.shell.restMaxRadiusMm, mass = free.shell.siliconeG;
    ASSERT_GT(reach, 1.9 * bulb.Shell().geometry.radiusMm);

    auto judged = [&](sim::EnvelopeDef envelope) {
        sim::EvalJob job = bulb;
        job.Shell().envelope = envelope;
        return sim::Evaluate(job);
    };
    const double ratio = reach / bulb.Shell().geometry.radiusMm;
    for (const sim::EnvelopeDef outside : {sim::EnvelopeDef{ratio * 0.99, 0, 0}, sim::EnvelopeDef{0, reach * 0.99, 0}, sim::EnvelopeDef{0, 0, mass * 0.99}}) {
        const sim::SimResult r = judged(outside);
        EXPECT_EQ(r.status, sim::Status::OutsideEnvelope);
        EXPECT_EQ(r.shell.newtonIterations, 0) << "nothing is simulated";
        EXPECT_TRUE(std::isnan(r.fitness) && std::isnan(r.contractionPercent)) << "a failed design reads as no number";
        EXPECT_EQ(r.shell.restMaxRadiusMm, reach) << "the measures that put it outside are reported";
        EXPECT_EQ(r.shell.siliconeG, mass);
        EXPECT_TRUE(std::isnan(sim::ObjectiveValue(sim::ObjectiveKind::Contraction, r, nullptr)));
    }
    const sim::SimResult inside = judged({ratio * 1.01, reach * 1.01, mass * 1.01});
    EXPECT_EQ(inside.status, sim::Status::Ok);
    EXPECT_EQ(inside.contractionPercent, free.contractionPercent) << "an envelope that holds changes nothing";
    // Per gram: the blocking force over the wall's silicone.
    EXPECT_DOUBLE_EQ(sim::ObjectiveValue(sim::ObjectiveKind::ForcePerGram, inside, nullptr), inside.shell.blockingForceN / mass);
}

TEST(Envelope, BoundsThatCannotHoldAreRefused) {
    sim::ShellDef def = sim::DefaultShellDef();
    def.envelope.maxRadiusRatio = 0.8;
    EXPECT_NE(sim::ShellDefError(def).find("not even the plain tube"), std::string::npos);
    def.envelope = {};
    def.envelope.maxSiliconeG = 10;
    def.material.densityKgPerM3 = 0;
    EXPECT_NE(sim::ShellDefError(def).find("needs the material's density"), std::string::npos);
    def.envelope.maxSiliconeG = -1;
    EXPECT_NE(sim::ShellDefError(def).find("0 (none) or positive"), std::string::npos);
}

}  // namespace
