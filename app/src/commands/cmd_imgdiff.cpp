// `actuator imgdiff A.png B.png`: the visual tests' comparison, for people and scripts.
#include <iostream>

#include "options/cli.h"
#include "commands/registry.h"
#include "formats/files.h"
#include "pictures/figures.h"
#include "render/image.h"

namespace app {
namespace {

render::Image ReadPng(const std::string& path) {
    const std::string text = ReadInputFile(path);
    render::Image image;
    std::string error;
    if (!render::DecodePng(std::vector<std::uint8_t>(text.begin(), text.end()), &image, &error)) throw UsageError(Quote(path) + ": " + error);
    return image;
}

}  // namespace

static int RunImgDiff(int argc, char** argv, int first) {
    Cli cli("imgdiff", "Compares two images pixel by pixel with a tolerance. Prints one line with the share of differing pixels and the largest "
                       "and mean channel differences. Exit code 0 when they match, 1 when they differ (or differ in size), 2 on bad input.");
    std::string expectedPath, actualPath, diffPath;
    render::ImageTolerance tolerance;
    cli.App().add_option("expected", expectedPath, "the reference image")->required()->type_name("EXPECTED.png");
    cli.App().add_option("actual", actualPath, "the image to check")->required()->type_name("ACTUAL.png");
    cli.Text("--diff", diffPath, "write a diff image: the expected image faded, differing pixels red")->type_name("FILE.png");
    cli.Integer("--threshold", tolerance.channelThreshold, "a pixel differs when a channel differs by more than this (0-255)", 0, 255);
    cli.Number("--max-fraction", tolerance.maxDifferingFraction, "images match when at most this fraction of pixels differ", 0, 1);
    if (!cli.Parse(argc, argv, first)) return 0;
    if (cli.Given("--diff")) {
        CheckOutputPath(diffPath, "--diff");
        RefuseOutputThatIsInput(diffPath, "--diff", {expectedPath, actualPath});
    }
    const render::Image expected = ReadPng(expectedPath);
    const render::Image actual = ReadPng(actualPath);
    const render::ImageComparison comparison = render::CompareImages(expected, actual, tolerance);
    if (cli.Given("--diff") && comparison.sameSize) WritePng(diffPath, comparison.diff, 6);
    std::cout << (comparison.matches ? "match: " : "differ: ") << comparison.Summary() << "\n";
    return comparison.matches ? 0 : 1;
}

static const RegisterCommand kImgdiffCommand{{"imgdiff", "compare two PNG images with a tolerance (exit 0 match, 1 differ)", 100, RunImgDiff}};

}  // namespace app
