// `actuator render` and `actuator imgdiff` as a user runs them.
#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "render/image.h"

namespace fs = std::filesystem;
using testing_support::LoadPng;
using ::testing::HasSubstr;

namespace {

class RenderCli : public CliTest {
protected:
    static render::Image Load(const fs::path& path, std::source_location where = std::source_location::current()) { return LoadPng(path, where); }
    static int CountFiles(const fs::path& folder) {
        int count = 0;
        for (const auto& entry : fs::directory_iterator(folder)) count += entry.path().extension() == ".png";
        return count;
    }
};

}  // namespace

TEST_F(RenderCli, WritesInflationAndStretchFigures) {
    const Result r = Run("render --model thesis --shape sine --amplitude 4.1 --size 320x240 --out " + Path("fig"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["inflation"]["status"], "ok");
    EXPECT_NEAR(json["stretch"]["fitness"].get<double>(), -1.718, 0.005);
    for (const char* name : {"inflation.png", "stretch.png"}) {
        const render::Image image = Load(dir_ / "fig" / name);
        EXPECT_EQ(image.width, 320);
        EXPECT_EQ(image.height, 240);
        EXPECT_FALSE(render::IsUniform(image)) << name;
    }
}

TEST_F(RenderCli, SameInputGivesTheSameBytes) {
    ASSERT_EQ(Run("render --model thesis --shape abs-sine --size 200x150 --iterations 500 --out " + Path("a")).exitCode, 0);
    ASSERT_EQ(Run("render --model thesis --shape abs-sine --size 200x150 --iterations 500 --out " + Path("b")).exitCode, 0);
    EXPECT_EQ(Slurp(dir_ / "a" / "inflation.png"), Slurp(dir_ / "b" / "inflation.png"));
}

TEST_F(RenderCli, TurntableAndTimelapseWriteTheirFrames) {
    const Result r = Run("render --model thesis --shape sine --size 160x120 --iterations 400 --turntable --timelapse 4 --out " + Path("seq"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(CountFiles(dir_ / "seq" / "turntable"), 60);  // --turntable alone means 60 frames
    EXPECT_EQ(CountFiles(dir_ / "seq" / "timelapse"), 4);   // --timelapse N writes N frames: iterations 0, 133, 266, 400
    // The turntable moves: frame 15 (a quarter turn) differs from frame 0.
    const auto comparison = render::CompareImages(Load(dir_ / "seq" / "turntable" / "frame_0000.png"),
                                                  Load(dir_ / "seq" / "turntable" / "frame_0015.png"), render::ImageTolerance{});
    EXPECT_FALSE(comparison.matches);
}

TEST_F(RenderCli, VideoNeedsFfmpegAndSaysSoWhenMissing) {
    const Result r = Run("render --model thesis --shape cylinder --size 160x120 --iterations 100 --turntable 3 --video --out " + Path("v"),
                         "PATH=" + Path("empty-path"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("ffmpeg is not installed"));
    EXPECT_FALSE(fs::exists(dir_ / "v" / "turntable.mp4"));
    if (std::system("command -v ffmpeg > /dev/null 2>&1") == 0) {
        const Result withFfmpeg = Run("render --model thesis --shape cylinder --size 160x120 --iterations 100 --turntable 3 --video --out " + Path("v"));
        ASSERT_EQ(withFfmpeg.exitCode, 0) << withFfmpeg.err;
        EXPECT_GT(fs::file_size(dir_ / "v" / "turntable.mp4"), 100u);
    }
}

TEST_F(RenderCli, BadOptionsAreRefused) {
    ExpectRefused("render --model thesis --shape sine", "--out");
    ExpectRefused("render --model thesis --size 10x10 --out " + Path("x"), "--size");
    ExpectRefused("render --model thesis --size huge --out " + Path("x"), "--size");
    ExpectRefused("render --model thesis --turntable 0 --out " + Path("x"), "--turntable");
    ExpectRefused("render --model thesis --color-by purple --out " + Path("x"), "purple");
    ExpectRefused("render --model thesis --load stretch --out " + Path("x"), "--load");
    ExpectRefused("render --model thesis --iterations 100 --timelapse 500 --out " + Path("x"), "--timelapse");
    ExpectRefused("render --model thesis --resolution 256 --turns 256 --iterations 100000 --timelapse 100000 --out " + Path("x"), "GB of snapshots");
    ExpectRefused("render --model thesis --video --out " + Path("x"), "--video needs");
    ExpectRefused("render --model thesis --gl-backend vulkan --out " + Path("x"), "choose osmesa or egl");
    ExpectRefused("render --model thesis --png-level 12 --out " + Path("x"), "--png-level");
    std::ofstream(Path("file")) << "not a folder";
    ExpectRefused("render --model thesis --out " + Path("file"), "--out");
    // Every output is checked before any is written: stretch.png being a folder stops the run
    // before inflation.png exists.
    fs::create_directories(dir_ / "partial" / "stretch.png");
    ExpectRefused("render --model thesis --out " + Path("partial"), "stretch.png");
    EXPECT_FALSE(fs::exists(dir_ / "partial" / "inflation.png"));
}

TEST_F(RenderCli, BothGlBackendsDrawTheSamePicture) {
    ASSERT_EQ(Run("render --model thesis --shape sine --size 320x240 --iterations 500 --gl-backend osmesa --out " + Path("osmesa")).exitCode, 0);
    const Result egl = Run("render --model thesis --shape sine --size 320x240 --iterations 500 --gl-backend egl --out " + Path("egl"));
    ASSERT_EQ(egl.exitCode, 0) << egl.err;
    EXPECT_THAT(egl.out, HasSubstr("egl surfaceless"));
    const auto comparison = render::CompareImages(Load(dir_ / "osmesa" / "inflation.png"), Load(dir_ / "egl" / "inflation.png"), render::ImageTolerance{});
    EXPECT_TRUE(comparison.matches) << comparison.Summary();
}

TEST_F(RenderCli, ImgDiffExitCodes) {
    ASSERT_EQ(Run("render --model thesis --shape sine --size 200x150 --iterations 300 --out " + Path("a")).exitCode, 0);
    ASSERT_EQ(Run("render --model thesis --shape sine --size 200x150 --iterations 300 --elevation 45 --out " + Path("b")).exitCode, 0);
    const std::string a = Path("a/inflation.png"), b = Path("b/inflation.png");

    Result same = Run("imgdiff " + a + " " + a);
    EXPECT_EQ(same.exitCode, 0);
    EXPECT_NE(same.out.find("match"), std::string::npos);

    Result differ = Run("imgdiff " + a + " " + b + " --diff " + Path("diff.png"));
    EXPECT_EQ(differ.exitCode, 1);
    EXPECT_THAT(differ.out, HasSubstr("% of pixels differ"));
    EXPECT_FALSE(render::IsUniform(Load(Path("diff.png"))));

    // A looser tolerance accepts the same pair.
    EXPECT_EQ(Run("imgdiff " + a + " " + b + " --max-fraction 1").exitCode, 0);

    std::ofstream(Path("fake.png")) << "GIF89a";
    ExpectRefused("imgdiff " + a + " " + Path("fake.png"), "fake.png");
    ExpectRefused("imgdiff " + a + " " + Path("missing.png"), "missing.png");
    ExpectRefused("imgdiff " + a, "actual");
    ExpectRefused("imgdiff " + a + " " + b + " --diff " + a, "also an input");
    ExpectRefused("imgdiff " + a + " " + b + " --threshold 300", "--threshold");
}
