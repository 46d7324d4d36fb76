#include "render/image.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace render {

Image BoxDownsample(const std::uint8_t* rgba, int width, int height, int factor, bool bottomUp) {
    Image out;
    factor = std::max(1, factor);
    out.width = width / factor;
    out.height = height / factor;
    out.rgba.resize(static_cast<size_t>(out.width) * out.height * 4);
    const size_t stride = static_cast<size_t>(width) * 4;
    if (factor == 2) {
        // The default: average 2x2 pixels with the channels split into two words of 16-bit lanes
        // (even and odd bytes), so one pixel is a handful of integer operations that vectorise.
        for (int y = 0; y < out.height; ++y) {
            const auto* top = reinterpret_cast<const std::uint32_t*>(rgba + static_cast<size_t>(2 * y) * stride);
            const auto* below = reinterpret_cast<const std::uint32_t*>(rgba + static_cast<size_t>(2 * y + 1) * stride);
            const int outRow = bottomUp ? out.height - 1 - y : y;
            auto* dst = reinterpret_cast<std::uint32_t*>(&out.rgba[static_cast<size_t>(outRow) * out.width * 4]);
            for (int x = 0; x < out.width; ++x) {
                const std::uint32_t a = top[2 * x], b = top[2 * x + 1], c = below[2 * x], d = below[2 * x + 1];
                const std::uint32_t even = (a & 0x00FF00FFu) + (b & 0x00FF00FFu) + (c & 0x00FF00FFu) + (d & 0x00FF00FFu) + 0x00020002u;
                const std::uint32_t odd = ((a >> 8) & 0x00FF00FFu) + ((b >> 8) & 0x00FF00FFu) + ((c >> 8) & 0x00FF00FFu) +
                                          ((d >> 8) & 0x00FF00FFu) + 0x00020002u;
                dst[x] = ((even >> 2) & 0x00FF00FFu) | (((odd >> 2) & 0x00FF00FFu) << 8);
            }
        }
        return out;
    }
    const int area = factor * factor;
    std::vector<std::uint16_t> sums(static_cast<size_t>(out.width) * 4);
    for (int y = 0; y < out.height; ++y) {
        // Sum the block's rows column by column (a plain loop the compiler vectorises), then average.
        std::fill(sums.begin(), sums.end(), 0);
        for (int dy = 0; dy < factor; ++dy) {
            const std::uint8_t* row = rgba + static_cast<size_t>(y * factor + dy) * stride;
            for (int x = 0; x < out.width; ++x)
                for (int dx = 0; dx < factor; ++dx)
                    for (int c = 0; c < 4; ++c) sums[x * 4 + c] += row[(x * factor + dx) * 4 + c];
        }
        const int outRow = bottomUp ? out.height - 1 - y : y;
        std::uint8_t* dst = &out.rgba[static_cast<size_t>(outRow) * out.width * 4];
        for (size_t i = 0; i < sums.size(); ++i) dst[i] = static_cast<std::uint8_t>((sums[i] + area / 2) / area);
    }
    return out;
}

std::vector<std::uint8_t> EncodePng(const Image& image, int compressionLevel) {
    std::vector<std::uint8_t> bytes;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return {};
    }
    png_set_write_fn(
        png, &bytes,
        [](png_structp p, png_bytep data, png_size_t length) {
            auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(p));
            out->insert(out->end(), data, data + length);
        },
        nullptr);
    png_set_compression_level(png, std::clamp(compressionLevel, 0, 9));
    if (compressionLevel <= 1) png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
    png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y)
        png_write_row(png, const_cast<png_bytep>(&image.rgba[static_cast<size_t>(y) * image.width * 4]));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return bytes;
}

bool DecodePng(const std::vector<std::uint8_t>& bytes, Image* image, std::string* error) {
    png_image decoded;
    std::memset(&decoded, 0, sizeof decoded);
    decoded.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&decoded, bytes.data(), bytes.size())) {
        if (error) *error = std::string("not a PNG image (") + decoded.message + ")";
        return false;
    }
    decoded.format = PNG_FORMAT_RGBA;
    if (decoded.width == 0 || decoded.height == 0 || static_cast<size_t>(decoded.width) * decoded.height > (1u << 28)) {
        png_image_free(&decoded);
        if (error) *error = "PNG has an unsupported size";
        return false;
    }
    image->width = static_cast<int>(decoded.width);
    image->height = static_cast<int>(decoded.height);
    image->rgba.assign(PNG_IMAGE_SIZE(decoded), 0);
    if (!png_image_finish_read(&decoded, nullptr, image->rgba.data(), 0, nullptr)) {
        if (error) *error = std::string("damaged PNG (") + decoded.message + ")";
        png_image_free(&decoded);
        return false;
    }
    return true;
}

std::string ImageComparison::Summary() const {
    if (!sameSize) return "images differ in size";
    char line[200];
    std::snprintf(line, sizeof line, "%.4f%% of pixels differ (at most %d in one 16 x 16 tile), max channel delta %d, mean delta %.3f",
                  100.0 * differingFraction, maxDifferingInTile, maxChannelDelta, meanAbsoluteDelta);
    return line;
}

ImageComparison CompareImages(const Image& expected, const Image& actual, const ImageTolerance& tolerance) {
    ImageComparison result;
    result.sameSize = expected.width == actual.width && expected.height == actual.height;
    if (!result.sameSize) return result;
    const size_t pixels = static_cast<size_t>(expected.width) * expected.height;
    result.diff = expected;
    size_t differing = 0;
    long long deltaSum = 0;
    int maxDelta = 0;
    for (size_t p = 0; p < pixels; ++p) {
        int pixelDelta = 0;
        for (int c = 0; c < 4; ++c) {
            const int d = std::abs(int(expected.rgba[p * 4 + c]) - int(actual.rgba[p * 4 + c]));
            pixelDelta = std::max(pixelDelta, d);
            deltaSum += d;
        }
        maxDelta = std::max(maxDelta, pixelDelta);
        std::uint8_t* out = &result.diff.rgba[p * 4];
        if (pixelDelta > tolerance.channelThreshold) {
            ++differing;
            out[0] = 255; out[1] = 0; out[2] = 0; out[3] = 255;
        } else {
            const auto grey = static_cast<std::uint8_t>(200 + (out[0] + out[1] + out[2]) / 3 * 55 / 255);
            out[0] = out[1] = out[2] = grey;
            out[3] = 255;
        }
    }
    result.differingFraction = pixels ? double(differing) / pixels : 0.0;
    result.maxChannelDelta = maxDelta;
    result.meanAbsoluteDelta = pixels ? double(deltaSum) / (pixels * 4) : 0.0;
    constexpr int kTile = 16;
    for (int ty = 0; ty < expected.height; ty += kTile)
        for (int tx = 0; tx < expected.width; tx += kTile) {
            int inTile = 0;
            for (int y = ty; y < std::min(ty + kTile, expected.height); ++y)
                for (int x = tx; x < std::min(tx + kTile, expected.width); ++x) {
                    const std::uint8_t* out = &result.diff.rgba[(static_cast<size_t>(y) * expected.width + x) * 4];
                    inTile += out[0] == 255 && out[1] == 0 && out[2] == 0;  // marked red above
                }
            result.maxDifferingInTile = std::max(result.maxDifferingInTile, inTile);
        }
    result.matches = result.differingFraction <= tolerance.maxDifferingFraction &&
                     (tolerance.maxDifferingPerTile <= 0 || result.maxDifferingInTile <= tolerance.maxDifferingPerTile);
    return result;
}

bool IsUniform(const Image& image) {
    if (image.Empty()) return true;
    for (size_t i = 4; i < image.rgba.size(); i += 4)
        if (std::memcmp(&image.rgba[i], &image.rgba[0], 4) != 0) return false;
    return true;
}

}  // namespace render
