// PNG files in tests: decoded, or the test fails saying which file and why.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <source_location>

#include "render/image.h"
#include "process.h"

namespace testing_support {

inline render::Image LoadPng(const std::filesystem::path& path, std::source_location where = std::source_location::current()) {
    const std::string bytes = Slurp(path);
    render::Image image;
    std::string error;
    if (!render::DecodePng(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), &image, &error))
        ADD_FAILURE_AT(where.file_name(), static_cast<int>(where.line())) << path << " is not a PNG: " << error;
    return image;
}

// A real picture: decodes and is not one flat colour.
inline void ExpectPicture(const std::filesystem::path& path, std::source_location where = std::source_location::current()) {
    const render::Image image = LoadPng(path, where);
    if (image.Empty() || render::IsUniform(image)) ADD_FAILURE_AT(where.file_name(), static_cast<int>(where.line())) << path << " is blank";
}

}  // namespace testing_support
