// Images in memory (RGBA8, top row first), PNG encoding and decoding through libpng, and the
// tolerant comparison behind the visual regression tests and `actuator imgdiff`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace render {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // width * height * 4 bytes

    bool Empty() const { return width == 0 || height == 0; }
};

// Averages each factor x factor block: the anti-aliasing step after rendering at factor x the size.
// With bottomUp, the source rows are in OpenGL's order and the result is flipped to top row first.
Image BoxDownsample(const std::uint8_t* rgba, int width, int height, int factor, bool bottomUp);
inline Image BoxDownsample(const Image& image, int factor) {
    return BoxDownsample(image.rgba.data(), image.width, image.height, factor, false);
}

// PNG bytes: 8-bit RGBA, no timestamp or other varying chunks, so the same image gives the same bytes.
// compressionLevel 0-9 (zlib); levels 0 and 1 also skip row filtering, which is most of the time.
std::vector<std::uint8_t> EncodePng(const Image& image, int compressionLevel);

// Any 8- or 16-bit PNG, converted to RGBA8. False with *error set on data that is not a valid PNG.
bool DecodePng(const std::vector<std::uint8_t>& bytes, Image* image, std::string* error);

struct ImageTolerance {
    int channelThreshold = 24;        // a pixel differs when any channel differs by more than this (0-255)
    double maxDifferingFraction = 0.003;  // images match when at most this fraction of pixels differ
    // And, when > 0, at most this many differing pixels in any 16 x 16 tile: a new or lost mark (a
    // cross, a one-pixel zero line) is concentrated where noise is spread thin, and a fraction of the
    // whole picture cannot see it. 0: off (3-D scenes, whose shading noise is not spread thin).
    int maxDifferingPerTile = 0;
};

struct ImageComparison {
    bool sameSize = false;
    bool matches = false;
    double differingFraction = 1.0;  // share of pixels over the channel threshold
    int maxChannelDelta = 255;
    double meanAbsoluteDelta = 255;  // over all channels, 0-255
    int maxDifferingInTile = 0;      // the most differing pixels in one 16 x 16 tile
    Image diff;                      // expected faded to grey, differing pixels in red
    std::string Summary() const;     // one line with the numbers
};

ImageComparison CompareImages(const Image& expected, const Image& actual, const ImageTolerance& tolerance);

// True when every pixel has the same colour: a blank or failed frame.
bool IsUniform(const Image& image);

}  // namespace render
