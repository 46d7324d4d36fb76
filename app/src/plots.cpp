#include "plots.h"

#include <fmt/format.h>

#include "errors.h"
#include "render/plot.h"

namespace app {

std::string AxisLabel(sim::SweepParameter parameter) {
    switch (parameter) {
        case sim::SweepParameter::Amplitude: return "amplitude A";
        case sim::SweepParameter::Cycles: return "cycles n (phase 0 to n pi)";
        case sim::SweepParameter::PhaseEnd: return "phase end (radians)";
    }
    return "";
}

namespace {

std::unique_ptr<render::PlotRenderer> MakePlots(int width, int height) {
    std::string error;
    auto plots = render::PlotRenderer::Create(width, height, &error);
    if (!plots) throw UsageError("cannot render: " + error);
    return plots;
}

}  // namespace

render::Image LandscapeImage(const Experiment& e, const std::vector<double>& fitness, int best, const std::string& bestText) {
    auto plots = MakePlots(1024, 640);
    const std::string title = ExperimentTitle(e) + "  -  fitness landscape";
    const auto& axes = e.sweep.axes;
    if (axes.size() == 1) {
        render::LinePlot plot;
        plot.xLabel = AxisLabel(axes[0].parameter);
        plot.yLabel = "fitness (contraction, mesh units)";
        plot.zeroLine = true;
        render::LineSeries series{"fitness after " + std::to_string(e.params.iterations) + " iterations", axes[0].values, fitness, {0.13f, 0.35f, 0.75f}, true};
        plot.series.push_back(series);
        if (best >= 0) {
            plot.highlight = std::pair{axes[0].values[static_cast<size_t>(best)], fitness[static_cast<size_t>(best)]};
            plot.highlightLabel = bestText;
        }
        return plots->RenderLines(title, {plot});
    }
    render::Heatmap heatmap;
    heatmap.xLabel = AxisLabel(axes[1].parameter);
    heatmap.yLabel = AxisLabel(axes[0].parameter);
    heatmap.valueLabel = "fitness";
    heatmap.xValues = axes[1].values;
    heatmap.yValues = axes[0].values;
    heatmap.values = fitness;
    if (best >= 0) {
        heatmap.highlight = static_cast<size_t>(best);
        const bool anyFailed = std::any_of(fitness.begin(), fitness.end(), [](double f) { return !std::isfinite(f); });
        heatmap.highlightLabel = bestText + (anyFailed ? "  (grey cells: failed evaluations)" : "");
    }
    return plots->RenderHeatmap(title, heatmap);
}

render::Image EvolutionImage(const Experiment& e, const std::vector<RunCurve>& runs) {
    auto plots = MakePlots(std::min(2400, 560 * static_cast<int>(runs.size()) + 200), 640);
    std::vector<render::LinePlot> panels;
    for (const RunCurve& run : runs) {
        render::LinePlot plot;
        plot.title = run.title;
        plot.xLabel = "generation";
        plot.yLabel = "fitness";
        render::LineSeries bestLine{"best", {}, {}, {0.10f, 0.55f, 0.20f}}, worstLine{"worst", {}, {}, {0.80f, 0.20f, 0.15f}},
            meanLine{"mean", {}, {}, {0.13f, 0.35f, 0.75f}};
        render::Band band{"mean +/- std", {}, {}, {}, {0.13f, 0.35f, 0.75f}};
        for (const auto& row : run.logbook) {
            const double g = row.generation;
            bestLine.x.push_back(g);
            bestLine.y.push_back(row.best);
            worstLine.x.push_back(g);
            worstLine.y.push_back(row.worst);
            meanLine.x.push_back(g);
            meanLine.y.push_back(row.mean);
            band.x.push_back(g);
            band.low.push_back(row.mean - row.stddev);
            band.high.push_back(row.mean + row.stddev);
        }
        plot.bands = {band};
        plot.series = {bestLine, meanLine, worstLine};
        if (!run.logbook.empty()) {
            const auto& last = run.logbook.back();
            plot.highlight = std::pair{double(last.generation), last.best};
            plot.highlightLabel = fmt::format("best {:.4f}", last.best);
        }
        panels.push_back(plot);
    }
    return plots->RenderLines(ExperimentTitle(e) + "  -  evolution", panels);
}

}  // namespace app
