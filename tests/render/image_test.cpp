#include "render/image.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "render/plot.h"

namespace {
render::Image Gradient(int w, int h) {
    render::Image image{w, h, std::vector<std::uint8_t>(static_cast<size_t>(w) * h * 4)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c) image.rgba[(y * w + x) * 4 + c] = static_cast<std::uint8_t>((x * 7 + y * 13 + c * 50) % 256);
    return image;
}
}  // namespace

TEST(Image, BoxDownsampleAveragesBlocksAndFlipsBottomUpRows) {
    render::Image image{2, 4, {}};
    // Rows 0-1 (bottom in GL order) are 0 and 100, rows 2-3 are 200 and 255 (alpha too).
    for (int value : {0, 0, 100, 100, 200, 200, 255, 255})
        for (int c = 0; c < 4; ++c) image.rgba.push_back(static_cast<std::uint8_t>(value));
    const auto down = render::BoxDownsample(image.rgba.data(), 2, 4, 2, /*bottomUp=*/true);
    ASSERT_EQ(down.width, 1);
    ASSERT_EQ(down.height, 2);
    EXPECT_EQ(down.rgba[0], 228);  // (200+200+255+255)/4 = 227.5, rounded: top row came from the last rows
    EXPECT_EQ(down.rgba[4], 50);
    // The fast 2x path and the general path agree.
    const auto g = Gradient(64, 32);
    const auto fast = render::BoxDownsample(g, 2);
    render::Image three = render::BoxDownsample(g, 1);
    EXPECT_EQ(three.rgba, g.rgba);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 4; ++c) {
                int sum = 0;
                for (int dy = 0; dy < 2; ++dy)
                    for (int dx = 0; dx < 2; ++dx) sum += g.rgba[((2 * y + dy) * 64 + 2 * x + dx) * 4 + c];
                ASSERT_EQ(fast.rgba[(y * 32 + x) * 4 + c], (sum + 2) / 4) << x << "," << y;
            }
}

TEST(Image, PngRoundTripsAndIsByteStable) {
    const auto image = Gradient(37, 21);
    for (int level : {0, 1, 6, 9}) {
        const auto bytes = render::EncodePng(image, level);
        EXPECT_EQ(bytes, render::EncodePng(image, level)) << "level " << level;
        render::Image back;
        std::string error;
        ASSERT_TRUE(render::DecodePng(bytes, &back, &error)) << error;
        EXPECT_EQ(back.rgba, image.rgba);
    }
}

TEST(Image, DecodeRefusesNonPngData) {
    render::Image image;
    std::string error;
    EXPECT_FALSE(render::DecodePng({'G', 'I', 'F', '8'}, &image, &error));
    EXPECT_FALSE(error.empty());
    auto truncated = render::EncodePng(Gradient(8, 8), 6);
    truncated.resize(truncated.size() / 2);
    EXPECT_FALSE(render::DecodePng(truncated, &image, &error));
}

TEST(Image, ComparisonCountsPixelsOverTheThreshold) {
    const auto a = Gradient(10, 10);
    auto b = a;
    b.rgba[0] = static_cast<std::uint8_t>(a.rgba[0] + 100 > 255 ? a.rgba[0] - 100 : a.rgba[0] + 100);  // one pixel off
    b.rgba[4] = static_cast<std::uint8_t>(a.rgba[4] ^ 1);                                             // one within tolerance
    const auto r = render::CompareImages(a, b, render::ImageTolerance{24, 0.0});
    EXPECT_DOUBLE_EQ(r.differingFraction, 0.01);
    EXPECT_FALSE(r.matches);
    EXPECT_TRUE(render::CompareImages(a, b, render::ImageTolerance{24, 0.02}).matches);
    EXPECT_FALSE(render::CompareImages(a, Gradient(10, 11), render::ImageTolerance{}).sameSize);
    EXPECT_TRUE(render::IsUniform(render::Image{2, 1, std::vector<std::uint8_t>(8, 255)}));
    EXPECT_FALSE(render::IsUniform(a));
}

// A one-pixel line across a 200 x 200 picture is 0.5 % of it, but 16 pixels in each tile it crosses;
// the same number of changed pixels scattered one per tile passes the tile bound.
TEST(Image, TheTileBoundSeesAConcentratedMarkThatTheFractionBoundMisses) {
    const auto a = Gradient(200, 200);
    auto flip = [&](render::Image& image, int x, int y) {
        std::uint8_t& red = image.rgba[(static_cast<size_t>(y) * 200 + x) * 4];
        red = static_cast<std::uint8_t>(red > 127 ? red - 100 : red + 100);
    };
    auto line = a, scattered = a;
    for (int x = 0; x < 200; ++x) flip(line, x, 100);
    for (int k = 0; k < 144; ++k) flip(scattered, (k % 12) * 16 + 3, (k / 12) * 16 + 5);  // one per tile
    const render::ImageTolerance fractionOnly{24, 0.01}, tiled{24, 0.01, 12};
    EXPECT_TRUE(render::CompareImages(a, line, fractionOnly).matches);
    const auto r = render::CompareImages(a, line, tiled);
    EXPECT_FALSE(r.matches);
    EXPECT_EQ(r.maxDifferingInTile, 16);
    EXPECT_TRUE(render::CompareImages(a, scattered, tiled).matches);
}

// A colour bar labels both its ends and nice ticks between them; no two labels read the same. The
// S5.4F design's stretch scale ran to 1.1048 and showed "1.10" at its top and again just below it.
TEST(Image, AColourBarsLabelsNeverRepeatAndKeepClearOfItsEnds) {
    const auto texts = [](const std::vector<render::ScaleTick>& ticks) {
        std::vector<std::string> all;
        for (const auto& t : ticks) all.push_back(t.text);
        return all;
    };
    EXPECT_EQ(texts(render::ColourBarTicks(1.0, 1.1048, false, 0.03)), (std::vector<std::string>{"1.00", "1.10", "1.05"}));
    // Every range: labels distinct, ends first, the others inside and clear of the ends.
    for (double low : {-3.7, 0.0, 1.0, 12.5})
        for (double span : {0.013, 0.1048, 0.5, 1.0, 7.3, 120.0}) {
            const auto ticks = render::ColourBarTicks(low, low + span, true, 0.05);
            ASSERT_GE(ticks.size(), 2u);
            EXPECT_EQ(ticks[0].value, low);
            EXPECT_EQ(ticks[1].value, low + span);
            EXPECT_EQ(ticks[1].text.rfind("> ", 0), 0u) << "values above the top were clipped";
            std::set<std::string> seen{ticks[0].text, ticks[1].text.substr(2)};
            for (size_t k = 2; k < ticks.size(); ++k) {
                EXPECT_TRUE(seen.insert(ticks[k].text).second) << ticks[k].text << " twice on [" << low << ", " << low + span << "]";
                EXPECT_GT(ticks[k].value - low, 0.05 * span);
                EXPECT_GT(low + span - ticks[k].value, 0.05 * span);
            }
        }
    // A tick the gap would allow but that prints as the top is left out: [0, 1.004] has "1.0" once.
    EXPECT_EQ(texts(render::ColourBarTicks(0, 1.004, false, 0.001)), (std::vector<std::string>{"0.0", "1.0", "0.5"}));
}
