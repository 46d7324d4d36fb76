// Figures of numbers: line plots (fitness landscapes, evolution curves) and heatmaps (2-D
// landscapes), drawn by our own renderer with axes, ticks, labels, legends and colour bars.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/colormap.h"
#include "render/image.h"

namespace render {

struct LineSeries {
    std::string label;           // in the legend; empty: not listed
    std::vector<double> x, y;    // non-finite y values leave a gap
    Rgb color;
    bool markers = false;
    bool lines = true;                    // false: markers alone (a scatter plot)
    bool dashed = false;                  // lines drawn dashed, e.g. a theory beside the model
    float alpha = 1;                      // < 1: faint, e.g. every design behind a Pareto front
    std::vector<std::string> pointLabels{}; // drawn beside the markers (e.g. front numbers); may be shorter than x
    bool markFailed = false;              // a non-finite y at a finite x: a cross on the plot's floor, listed in the legend
};

struct Band {                    // a filled range, e.g. mean +/- std
    std::string label;
    std::vector<double> x, low, high;
    Rgb color;                   // drawn translucent
};

struct LinePlot {
    std::string title;           // above the plot area
    std::string xLabel, yLabel;
    std::vector<Band> bands;     // drawn first
    std::vector<LineSeries> series;
    std::optional<std::pair<double, double>> highlight;  // a ringed point, e.g. the best
    std::string highlightLabel;
    bool zeroLine = false;       // a thin line at y = 0
    bool integerX = false;       // x counts things (generations): ticks only at whole numbers
};

struct Heatmap {
    std::string title;
    std::string xLabel, yLabel, valueLabel;
    std::vector<double> xValues, yValues;  // cell centres
    std::vector<double> values;            // yValues.size() rows of xValues.size(); NaN: failed (grey)
    std::optional<size_t> highlight;       // index into values, ringed
    std::string highlightLabel;
    // Points drawn over the cells at their (x, y) values, e.g. the thesis's own numbers.
    struct Mark {
        double x = 0, y = 0;
        std::string label;
    };
    std::vector<Mark> marks;
    std::string marksLegend;               // one line under the plot saying what the marks are
    std::string failedLabel = "failed";    // beside a grey swatch under the colour bar, drawn when a value is NaN
};

// Drawn by the GL backend module, loaded on first use like MeshRenderer.
class PlotRenderer {
public:
    static std::unique_ptr<PlotRenderer> Create(int width, int height, std::string* error);
    virtual ~PlotRenderer() = default;

    // Several line plots side by side (e.g. one per GA run) under one figure title, sharing the y range.
    virtual Image RenderLines(const std::string& title, const std::vector<LinePlot>& plots) = 0;
    virtual Image RenderHeatmap(const std::string& title, const Heatmap& heatmap) = 0;
};

// "Nice" tick positions (1, 2, 5 x 10^k steps) covering [low, high], about `count` of them.
std::vector<double> NiceTicks(double low, double high, int count);

// A value on a scale `span` wide, with enough decimals to tell that scale's ticks apart.
std::string ScaleTickText(double value, double span);

// A colour bar's labelled ticks from `low` (bottom) to `high` (top): both ends always, then nice
// ticks between them that keep at least `minGap` of the range from either end and do not read the
// same as an end at the range's digits (a top of 1.104 and a tick at 1.1 are both "1.10"). Values
// with their texts, the ends first; the top's text is prefixed "> " when values above it were clipped.
struct ScaleTick {
    double value;
    std::string text;
};
std::vector<ScaleTick> ColourBarTicks(double low, double high, bool clippedTop, double minGap);

}  // namespace render
