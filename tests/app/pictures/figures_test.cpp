// The report's pictures of several designs draw each design as it was evaluated: a GA's best of each
// run carries its own shape and fibre genes, and its stretch is measured from its own rest shape.
#include <gtest/gtest.h>

#include <numbers>

#include "pictures/figures.h"
#include "pictures/plots.h"
#include "sim/batch.h"

namespace {

// A small shell job (12 x 12, 1 kPa): the figures' code, not the mesh, is under test.
sim::EvalJob SmallShellJob(const sim::Shape& shape) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    job.shape = shape;
    job.Shell().geometry.ringVertices = 12;
    job.Shell().geometry.rings = 12;
    job.Shell().geometry.edgeSpacingMm = 0;  // twelve evenly spaced rings: these tests are about pictures
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
    // The dashes, beside the stripe that shows the one family's twist (marks).
    size_t dashes = 0;
    for (const render::Segment& segment : fibreAfter.segments) dashes += !segment.mark;
    EXPECT_EQ(dashes, fibreFields.fibres.size()) << "one family's dashes: one per wall triangle";
    sim::EvalJob braid = fibre;
    braid.Shell().fibres.plus = true;
    EXPECT_EQ(2 * dashes, sim::ShellFieldValues(braid.Shell(), braid.shape, true, fibreResult.final).fibres.size())
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

namespace {
std::vector<render::Segment> Marks(const render::Panel& panel) {
    std::vector<render::Segment> marks;
    for (const render::Segment& s : panel.segments)
        if (s.mark) marks.push_back(s);
    return marks;
}
}  // namespace

// Where the top turns, a stripe straight along the tube at rest is drawn wound by the twist: its top
// end (the cap's radius) turned by the result's twist_deg. A braid, which does not turn, has none.
TEST(BeforeAfterScene, ATurnedTopIsDrawnAsAStripeWoundByTheTwist) {
    sim::EvalJob single = SmallShellJob(sim::CylinderShape{});
    single.Shell().fibres.layout = sim::FibreLayout::Single;
    single.Shell().fibres.angleDeg = 40;
    const sim::SimResult r = sim::Evaluate(single);
    ASSERT_EQ(r.status, sim::Status::Ok);
    ASSERT_GT(std::fabs(r.shell.twistDeg), 5) << "one family turns the top";
    const render::Scene scene = app::BeforeAfterScene("twist", r, single);
    ASSERT_EQ(scene.panels.size(), 2u);
    const auto before = Marks(scene.panels[0]), after = Marks(scene.panels[1]);
    ASSERT_EQ(before.size(), 12u) << "one segment between each pair of rings and the top cap's radius";
    ASSERT_EQ(after.size(), before.size());
    auto angle = [](const float p[3]) { return std::atan2(double(p[1]), double(p[0])) * 180 / std::numbers::pi; };
    // At rest the stripe runs along the axis: every vertex within half a ring spacing of one angle
    // (a staggered ring's two nearest vertices can tie at exactly half a spacing).
    for (size_t k = 0; k + 1 < before.size(); ++k)  // the last is the cap's radius, from the axis
        EXPECT_LT(std::fabs(std::remainder(angle(before[k].a) - angle(before.front().a), 360)), 360.0 / 12 / 2 + 1e-3);
    EXPECT_NEAR(std::remainder(angle(after.back().b) - angle(before.back().b), 360), r.shell.twistDeg, 1e-3) << "the cap's radius turns with the top";

    sim::EvalJob braid = single;
    braid.Shell().fibres.layout = sim::FibreLayout::Braid;
    const sim::SimResult b = sim::Evaluate(braid);
    ASSERT_EQ(b.status, sim::Status::Ok);
    for (const render::Panel& panel : app::BeforeAfterScene("braid", b, braid).panels) EXPECT_TRUE(Marks(panel).empty());
}

// The colour scale of the wall's stretch (and stress) reaches the largest value the subtitle states:
// the colours are vertex means of the triangles' values, whose largest lies below the largest triangle's.
TEST(BeforeAfterScene, TheScaleReachesTheLargestValueTheResultStates) {
    sim::EvalJob job = SmallShellJob(sim::SineShape{1.5, 0.5, std::numbers::pi - 0.5});
    const sim::SimResult r = sim::Evaluate(job);
    ASSERT_EQ(r.status, sim::Status::Ok);
    const render::Scene stretch = app::BeforeAfterScene("stretch", r, job, app::Colouring::Stretch);
    ASSERT_TRUE(stretch.colorMax.has_value());
    EXPECT_DOUBLE_EQ(*stretch.colorMax, r.shell.maxStretch);
    double vertexLargest = 0;
    for (double v : stretch.panels.back().values) vertexLargest = std::max(vertexLargest, v);
    EXPECT_LT(vertexLargest, r.shell.maxStretch) << "the vertex means stay below it: the scale would otherwise stop short";
    const render::Scene stress = app::BeforeAfterScene("stress", r, job, app::Colouring::Stress);
    ASSERT_TRUE(stress.colorMax.has_value());
    EXPECT_DOUBLE_EQ(*stress.colorMax, r.shell.maxStressKpa);
}

namespace {

// One legend serves the three panels of 5.2's evolution figure: it must not name run 1's number alone
// while runs 2 and 3 draw theirs.
TEST(EvolutionLegend, NamesEveryRunsThesisValueWhenThereAreSeveralRuns) {
    EXPECT_EQ(app::ThesisBestLegend({1.13, 1.09, 1.14}, 3), "thesis's best of that run (runs 1-3: 1.13, 1.09, 1.14)");
    EXPECT_EQ(app::ThesisBestLegend({3.5}, 1), "thesis's best: 3.5");
    EXPECT_EQ(app::ThesisBestLegend({1.13, 1.09, 1.14}, 2), "thesis's best of that run (runs 1-2: 1.13, 1.09)");
    EXPECT_EQ(app::ThesisBestLegend({}, 3), "");
}

}  // namespace

namespace {

// 4.3's three designs of Table 4.4 share one displacement scale that the exploded third sets: the
// picture must say that the third exploded and that the first two use a small part of the scale.
TEST(PairsScene, SaysWhenAMeshExplodedAndWhenADesignUsesLittleOfTheSharedScale) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Thesis);
    const sim::SimResult calm = sim::Evaluate(job);
    ASSERT_EQ(calm.status, sim::Status::Ok);
    sim::SimResult exploded = calm;
    for (int i = 0; i < exploded.final.Size(); ++i) exploded.final.x[i] = exploded.initial.x[i] + 40.0 * (i % 7);  // far beyond the mesh's size
    ASSERT_FALSE(app::EscapeWarning(exploded).empty());
    ASSERT_TRUE(app::EscapeWarning(calm).empty());

    auto linesWith = [](const render::Scene& scene, const std::string& text) {
        int n = 0;
        for (const std::string& line : scene.lines) n += line.find(text) != std::string::npos;
        return n;
    };
    const render::Scene mixed = app::PairsScene("pairs", {}, {{&calm, &job, "design 1"}, {&exploded, &job, "design 2"}}, 2);
    EXPECT_EQ(mixed.panels[3].caption.rfind("! after", 0), 0u) << mixed.panels[3].caption;
    EXPECT_NE(mixed.panels[1].caption.rfind("! after", 0), 0u) << mixed.panels[1].caption;
    EXPECT_EQ(linesWith(mixed, "design 2 moved"), 1);
    EXPECT_EQ(linesWith(mixed, "one colour scale for all designs"), 1);
    EXPECT_EQ(linesWith(mixed, "design 1 reaches"), 1);

    const render::Scene alike = app::PairsScene("pairs", {}, {{&calm, &job, "design 1"}, {&calm, &job, "design 2"}}, 2);
    EXPECT_EQ(linesWith(alike, "one colour scale"), 0) << "designs of one size need no note";
    EXPECT_EQ(linesWith(alike, "exploded"), 0);
}

}  // namespace

namespace {

// SF1 sweeps a braided straight tube given as a sine of one phase: its titles call it a cylinder.
TEST(ShapeTitle, ASineOfOnePhaseIsACylinder) {
    EXPECT_EQ(app::ShapeTitle(sim::SineShape{1, std::numbers::pi / 2, std::numbers::pi / 2}), "cylinder");
    EXPECT_EQ(app::ShapeTitle(sim::SineShape{2, std::numbers::pi / 2, std::numbers::pi / 2}), "cylinder of 2 x the base radius");
    EXPECT_EQ(app::ShapeTitle(sim::SineShape{4.1, 0.5, std::numbers::pi - 0.5}).rfind("sine  A = 4.1", 0), 0u);
}

}  // namespace

namespace {

// A time-lapse's frames share one scale: it must reach the largest stretch the result states, which
// lies above the largest vertex mean the frames colour with.
TEST(ShareFramingAndScale, TheSharedScaleReachesTheStatedLargestStretch) {
    const sim::EvalJob job = SmallShellJob(sim::SineShape{1.3, 0.5, std::numbers::pi - 0.5});
    const sim::SimResult r = sim::Evaluate(job);
    ASSERT_EQ(r.status, sim::Status::Ok);
    std::vector<render::Scene> scenes{app::TurntableScene("t", r, job, 0, app::Colouring::Stretch), app::TurntableScene("t", r, job, 90, app::Colouring::Stretch)};
    double vertexHigh = 0;
    for (double v : render::VertexValues(render::ColorBy::Values, *scenes[0].surface, scenes[0].panels.front())) vertexHigh = std::max(vertexHigh, v);
    ASSERT_LT(vertexHigh, r.shell.maxStretch) << "the test needs vertex means below the stated largest stretch";
    app::ShareFramingAndScale(scenes);
    for (const auto& scene : scenes) {
        ASSERT_TRUE(scene.colorMax.has_value());
        EXPECT_GE(*scene.colorMax, r.shell.maxStretch);
    }
}

}  // namespace

namespace {

// 4.3's best (A = 10, 8 cycles) flies apart under the thesis model: its picture must not say only
// "status ok" above it.
TEST(BeforeAfterScene, AnExplodedMeshIsWarnedOfUnderTheTitle) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Thesis);
    sim::SimResult r = sim::Evaluate(job);
    ASSERT_EQ(r.status, sim::Status::Ok);
    auto warned = [](const render::Scene& scene) {
        for (const std::string& line : scene.lines)
            if (line.find("the mesh exploded") != std::string::npos) return true;
        return false;
    };
    EXPECT_FALSE(warned(app::BeforeAfterScene("t", r, job)));
    for (int i = 0; i < r.final.Size(); ++i) r.final.z[i] += 50.0 * (i % 5);
    EXPECT_TRUE(warned(app::BeforeAfterScene("t", r, job)));
    EXPECT_TRUE(warned(app::TurntableScene("t", r, job, 0, app::Colouring::Auto)));
}

}  // namespace

namespace {

// The line under the title says how the fibres are drawn: coloured by stretch under stretch
// colouring, plain under stress colouring (where "coloured by their stretch" described another picture).
TEST(BeforeAfterScene, TheFibreLineDescribesTheColouringShown) {
    sim::EvalJob job = SmallShellJob(sim::SineShape{1.3, 0.5, std::numbers::pi - 0.5});
    job.Shell().fibres.layout = sim::FibreLayout::Braid;
    const sim::SimResult r = sim::Evaluate(job);
    ASSERT_EQ(r.status, sim::Status::Ok);
    auto has = [](const render::Scene& scene, const std::string& text) {
        return std::any_of(scene.lines.begin(), scene.lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
    };
    const render::Scene stretch = app::BeforeAfterScene("t", r, job, app::Colouring::Stretch);
    const render::Scene stress = app::BeforeAfterScene("t", r, job, app::Colouring::Stress);
    EXPECT_TRUE(has(stretch, "coloured by their stretch"));
    EXPECT_FALSE(has(stress, "coloured by their stretch"));
    EXPECT_TRUE(has(stress, "not on this scale"));
    for (const render::Segment& segment : stress.panels.back().segments)
        if (!segment.mark) EXPECT_FALSE(std::isfinite(segment.value)) << "stress colouring draws plain fibres";
}

}  // namespace

namespace {

// A title names the families the model carries (sim::FamiliesOn): a single family switched off is none.
TEST(FibreTitle, NamesTheFamiliesTheModelCarries) {
    sim::FibreDef f;
    f.layout = sim::FibreLayout::Single;
    f.plus = false;
    EXPECT_EQ(app::FibreTitle(f), "fibres switched off");
    f.plus = true;
    EXPECT_EQ(app::FibreTitle(f), "one fibre family +30 deg");
    f.layout = sim::FibreLayout::Braid;
    f.minus = false;
    EXPECT_EQ(app::FibreTitle(f), "one fibre family +30 deg");
    f.plus = false;
    EXPECT_EQ(app::FibreTitle(f), "fibres switched off");
}

}  // namespace
