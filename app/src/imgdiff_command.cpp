// `actuator imgdiff A.png B.png`: the visual tests' comparison, for people and scripts.
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli_options.h"
#include "commands.h"
#include "mesh_io.h"
#include "render/image.h"

namespace app {
namespace {

std::vector<OptionSpec> Specs() {
    const render::ImageTolerance d;
    return {
        {"diff", "FILE", "", "write a diff image: the expected image faded, differing pixels red"},
        {"threshold", "0-255", std::to_string(d.channelThreshold), "a pixel differs when a channel differs by more than this"},
        {"max-fraction", "F", "0.003", "images match when at most this fraction of pixels differ"},
        {"help", "", "", "show this help"},
    };
}

}  // namespace

render::Image ReadPngFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw UsageError("cannot open '" + path + "'");
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    render::Image image;
    std::string error;
    if (!render::DecodePng(bytes, &image, &error)) throw UsageError("'" + path + "': " + error);
    return image;
}

std::string ImgDiffHelp() {
    return "usage: actuator imgdiff EXPECTED.png ACTUAL.png [--diff out.png] [--threshold N] [--max-fraction F]\n\n"
           "Compares two images pixel by pixel with a tolerance. Prints one line with the share of differing\n"
           "pixels and the largest and mean channel differences. Exit code 0 when they match, 1 when they\n"
           "differ (or differ in size), 2 on bad input.\n\nOptions:\n" + FormatOptions(Specs());
}

int RunImgDiff(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, Specs(), 2);
    if (args.Has("help")) {
        std::cout << ImgDiffHelp();
        return 0;
    }
    if (args.positionals.size() != 2) throw UsageError("expected two PNG files: EXPECTED.png ACTUAL.png");
    render::ImageTolerance tolerance;
    if (args.Has("threshold")) tolerance.channelThreshold = ParseInt(args.Get("threshold"), "--threshold", 0, 255);
    if (args.Has("max-fraction")) {
        tolerance.maxDifferingFraction = ParseNumber(args.Get("max-fraction"), "--max-fraction");
        if (tolerance.maxDifferingFraction < 0 || tolerance.maxDifferingFraction > 1)
            throw UsageError("--max-fraction: must be between 0 and 1");
    }
    if (args.Has("diff")) CheckOutputPath(args.Get("diff"), "--diff");
    const render::Image expected = ReadPngFile(args.positionals[0]);
    const render::Image actual = ReadPngFile(args.positionals[1]);
    const render::ImageComparison comparison = render::CompareImages(expected, actual, tolerance);
    if (args.Has("diff") && comparison.sameSize) {
        const auto bytes = render::EncodePng(comparison.diff, 6);
        WriteFileAtomically(args.Get("diff"), std::string(bytes.begin(), bytes.end()));
    }
    std::cout << (comparison.matches ? "match: " : "differ: ") << comparison.Summary() << "\n";
    return comparison.matches ? 0 : 1;
}

}  // namespace app
