// The report's pictures of several designs draw each design as it was evaluated: a GA's best of each
// run carries its own shape and fibre genes, and its stretch is measured from its own rest shape.
#include <gtest/gtest.h>

#include <numbers>

#include "pictures/figures.h"
#include "sim/batch.h"

namespace {

// A small shell job (12 x 12, 1 kPa): the figures' code, not the mesh, is under test.
sim::EvalJob SmallShellJob(const sim::Shape& shape) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    job.shape = shape;
    job.Shell().geometry.ringVertices = 12;
    job.Shell().geometry.rings = 12;
    job.Shell().load.pressureKpa = 1;
    return job;
}

TEST(PairsScene, EachDesignIsColouredAndGivenFibresByItsOwnJob) {
    // A wavy design with one fibre family (a GA's fibre genes: the braid's +alpha off) and an isotropic
    // one of another shape, as the "best of each run" figure puts them side by side.
    sim::EvalJob fibre = SmallShellJob(sim::SineShape{1.3, 0.5, std::numbers::pi - 0.5});
    fibre.Shell().fibres.layout = sim::FibreLayout::Braid;
    fibre.Shell().fibres.plus = false;
    fibre.Shell().fibres.angleDeg = 40;
    const sim::EvalJob plain = SmallShellJob(sim::SineShape{1.1, 0.3, std::numbers::pi - 0.3});
    const sim::SimResult fibreResult = sim::Evaluate(fibre), plainResult = sim::Evaluate(plain);
    ASSERT_EQ(fibreResult.status, sim::Status::Ok);
    ASSERT_EQ(plainResult.status, sim::Status::Ok);

    const render::Scene scene =
        app::PairsScene("pairs", {}, {{&fibreResult, &fibre, "fibre"}, {&plainResult, &plain, "plain"}, {&fibreResult, &fibre, "fibre again"}}, 3);
    ASSERT_EQ(scene.panels.size(), 6u);  // before and after of each
    const render::Panel& fibreAfter = scene.panels[1];
    const render::Panel& plainAfter = scene.panels[3];

    const sim::ShellFields fibreFields = sim::ShellFieldValues(fibre.Shell(), fibre.shape, true, fibreResult.final);
    const sim::ShellFields plainFields = sim::ShellFieldValues(plain.Shell(), plain.shape, true, plainResult.final);
    EXPECT_EQ(fibreAfter.values, fibreFields.stretch) << "the fibre design's stretch, from its own rest shape";
    EXPECT_EQ(plainAfter.values, plainFields.stretch) << "the isotropic design's stretch, from its own rest shape";
    EXPECT_EQ(fibreAfter.segments.size(), fibreFields.fibres.size()) << "one family's dashes: one per wall triangle";
    sim::EvalJob braid = fibre;
    braid.Shell().fibres.plus = true;
    EXPECT_EQ(2 * fibreAfter.segments.size(), sim::ShellFieldValues(braid.Shell(), braid.shape, true, fibreResult.final).fibres.size())
        << "one family drawn, not the braid's two";
    EXPECT_TRUE(plainAfter.segments.empty()) << "no fibres drawn on a design without them";
    // The test can tell: the other design's job gives other stretches.
    EXPECT_NE(sim::ShellFieldValues(plain.Shell(), plain.shape, true, fibreResult.final).stretch, fibreFields.stretch);
    // The legend line about fibres appears once, however many panels have fibres (two here).
    int fibreLines = 0;
    for (const std::string& line : scene.lines) fibreLines += line.find("lines: the fibres") == 0;
    EXPECT_EQ(fibreLines, 1);
}

}  // namespace
