// Visual regression: fixed cases rendered and compared with tests/golden/*.png by a tolerant metric.
// On a mismatch the expected, actual and diff images are written under the build folder and their
// paths printed. UPDATE_GOLDENS=1 ctest -L visual rewrites the baselines instead.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "render/mesh_renderer.h"
#include "sim/solver.h"
#include "sim/surface.h"

namespace fs = std::filesystem;

namespace {

constexpr double kPi = std::numbers::pi;

std::vector<std::uint8_t> ReadBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void WriteBytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

struct Case {
    std::string name;
    sim::Shape shape;
    sim::Load load = sim::Load::Inflate;
    bool wireframe = false;
    bool overlay = false;
    double rotationDegrees = 0;
    bool singlePanel = false;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

render::RenderDef SmallDef(const Case& c) {
    render::RenderDef def = render::DefaultRenderDef();
    def.width = c.overlay ? 640 : 320;
    def.height = c.overlay ? 480 : 240;
    def.wireframe = c.wireframe;
    def.overlay = c.overlay;
    return def;
}

render::Image RenderCase(const Case& c, const render::RenderDef& def) {
    sim::SimParams params = sim::DefaultSimParams();
    params.load = c.load;
    const auto result = sim::Evaluate(c.shape, sim::DefaultMeshDef(), params);
    std::string error;
    auto renderer = render::MeshRenderer::Create(def, &error);
    EXPECT_TRUE(renderer) << error;
    if (!renderer) return {};
    render::Scene scene;
    scene.surface = std::make_shared<const sim::Surface>(sim::HelixSurface(sim::DefaultMeshDef()));
    scene.title = c.name;
    scene.lines = {"fitness " + std::to_string(result.fitness), "status " + std::string(sim::Name(result.status))};
    if (c.singlePanel) scene.panels = {{result.final, result.initial, "turned", c.rotationDegrees}};
    else scene.panels = {{result.initial, {}, "before", 0}, {result.final, result.initial, "after", 0}};
    return renderer->Render(scene);
}

std::vector<Case> Cases() {
    return {
        {"cylinder", sim::CylinderShape{}},
        {"sine_a41", sim::SineShape{4.1, 0.5, kPi - 0.5}},
        {"abs_sine_a4", sim::AbsSineShape{4.0, 0.0, 4 * kPi}},
        {"four_splines_wireframe",
         sim::BSplineShape{sim::SplineRegion::Middle, {{4, 6, 2, 5}, {2, 3, 7, 4, 6}, {5, 5, 1, 2}, {3, 3, 3, 3}}}, sim::Load::Inflate, true},
        {"sine_a41_stretch", sim::SineShape{4.1, 0.5, kPi - 0.5}, sim::Load::Stretch},
        {"turntable_frame_90", sim::SineShape{4.1, 0.5, kPi - 0.5}, sim::Load::Inflate, false, false, 90.0, true},
        {"overlay_text", sim::AbsSineShape{4.0, 0.0, 4 * kPi}, sim::Load::Inflate, false, true},
    };
}

class Visual : public ::testing::TestWithParam<Case> {};

}  // namespace

TEST_P(Visual, MatchesGolden) {
    const Case& c = GetParam();
    const render::Image actual = RenderCase(c, SmallDef(c));
    ASSERT_FALSE(actual.Empty());
    ASSERT_FALSE(render::IsUniform(actual)) << c.name << ": the frame is blank (one colour)";

    const fs::path golden = fs::path(ACTUATOR_GOLDEN_DIR) / (c.name + ".png");
    const char* update = std::getenv("UPDATE_GOLDENS");
    if (update && std::string(update) == "1") {
        WriteBytes(golden, render::EncodePng(actual, 9));
        std::cout << "updated " << golden << "\n";
        return;
    }
    render::Image expected;
    std::string error;
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing; run UPDATE_GOLDENS=1 ctest -L visual to create it";
    ASSERT_TRUE(render::DecodePng(ReadBytes(golden), &expected, &error)) << golden << ": " << error;
    const auto comparison = render::CompareImages(expected, actual, render::ImageTolerance{});
    if (!comparison.matches) {
        const fs::path out = fs::path(ACTUATOR_VISUAL_OUT_DIR);
        fs::create_directories(out);
        WriteBytes(out / (c.name + ".expected.png"), render::EncodePng(expected, 1));
        WriteBytes(out / (c.name + ".actual.png"), render::EncodePng(actual, 1));
        if (comparison.sameSize) WriteBytes(out / (c.name + ".diff.png"), render::EncodePng(comparison.diff, 1));
        ADD_FAILURE() << c.name << ": " << comparison.Summary() << "\n  expected: " << (out / (c.name + ".expected.png")).string()
                      << "\n  actual:   " << (out / (c.name + ".actual.png")).string()
                      << "\n  diff:     " << (out / (c.name + ".diff.png")).string()
                      << "\n  accept the new picture with: UPDATE_GOLDENS=1 ctest -L visual";
    }
}

INSTANTIATE_TEST_SUITE_P(Goldens, Visual, ::testing::ValuesIn(Cases()), [](const auto& info) { return info.param.name; });

TEST(VisualSensitivity, ACameraOrColourChangeIsCaught) {
    // The tolerance must not be so loose that a real rendering change passes.
    const Case c = Cases()[1];  // sine_a41
    render::Image expected;
    std::string error;
    ASSERT_TRUE(render::DecodePng(ReadBytes(fs::path(ACTUATOR_GOLDEN_DIR) / "sine_a41.png"), &expected, &error)) << error;
    render::RenderDef moved = SmallDef(c);
    moved.elevationDegrees += 6;
    EXPECT_FALSE(render::CompareImages(expected, RenderCase(c, moved), render::ImageTolerance{}).matches) << "camera moved 6 degrees";
    render::RenderDef recoloured = SmallDef(c);
    recoloured.colorBy = render::ColorBy::Strain;
    EXPECT_FALSE(render::CompareImages(expected, RenderCase(c, recoloured), render::ImageTolerance{}).matches) << "strain colouring";
}

TEST(VisualSensitivity, RenderingIsRepeatable) {
    const Case c = Cases()[3];
    const auto a = RenderCase(c, SmallDef(c)), b = RenderCase(c, SmallDef(c));
    EXPECT_EQ(render::EncodePng(a, 1), render::EncodePng(b, 1)) << "same scene, different bytes";
}
