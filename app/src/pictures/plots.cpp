#include "pictures/plots.h"

#include <algorithm>
#include <map>

#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "support/errors.h"
#include "render/plot.h"

namespace app {

std::string AxisLabel(sim::SweepParameter parameter) {
    switch (parameter) {
        case sim::SweepParameter::Amplitude: return "amplitude A";
        case sim::SweepParameter::Cycles: return "cycles n (phase 0 to n pi)";
        case sim::SweepParameter::PhaseEnd: return "phase end (radians)";
        case sim::SweepParameter::PressureKpa: return "gauge pressure (kPa)";
        case sim::SweepParameter::FibreAngleDeg: return "fibre angle to the axis (degrees)";
    }
    return "";
}

namespace {

// One value of a sweep's axis as a legend names it: in words, with its unit ("cycles 2", "1 kPa").
std::string ValueLabel(sim::SweepParameter parameter, double value) {
    switch (parameter) {
        case sim::SweepParameter::Amplitude: return fmt::format("A = {:.4g}", value);
        case sim::SweepParameter::Cycles: return fmt::format("{:.4g} cycles", value);
        case sim::SweepParameter::PhaseEnd: return fmt::format("phase end {:.4g} rad", value);
        case sim::SweepParameter::PressureKpa: return fmt::format("{:.4g} kPa", value);
        case sim::SweepParameter::FibreAngleDeg: return fmt::format("fibres at {:.4g} deg", value);
    }
    return fmt::format("{:.4g}", value);
}

std::unique_ptr<render::PlotRenderer> MakePlots(int width, int height) {
    std::string error;
    auto plots = render::PlotRenderer::Create(width, height, &error);
    if (!plots) throw UsageError("cannot render: " + error);
    return plots;
}

}  // namespace

render::Image LandscapeImage(const PlotContext& e, const std::vector<double>& fitness, int best, const std::string& bestText) {
    auto plots = MakePlots(1024, 640);
    const std::string title = e.title + "  -  fitness landscape";
    const auto& axes = e.axes;
    if (axes.size() == 1) {
        render::LinePlot plot;
        plot.xLabel = AxisLabel(axes[0].parameter);
        plot.yLabel = e.fitnessLabel;
        plot.zeroLine = true;
        render::LineSeries series{e.seriesLabel, axes[0].values, fitness, {0.13f, 0.35f, 0.75f}, true};
        series.markFailed = true;
        plot.series.push_back(series);
        if (best >= 0) {
            plot.highlight = std::pair{axes[0].values[static_cast<size_t>(best)], fitness[static_cast<size_t>(best)]};
            plot.highlightLabel = bestText;
        }
        // The thesis's own numbers where it gives them (Figure 4.1's peak).
        render::LineSeries thesis{"", {}, {}, {0.85f, 0.45f, 0.10f}, true};
        thesis.lines = false;
        for (const auto& point : e.thesisPoints)
            for (const auto& [parameter, value] : point.at)
                if (parameter == axes[0].parameter) {
                    thesis.x.push_back(value);
                    thesis.y.push_back(point.value);
                    thesis.label += (thesis.label.empty() ? "thesis: " : ", ") + fmt::format("{:g} at {} = {:g}", point.value, sim::Name(parameter), value);
                }
        if (!thesis.x.empty()) plot.series.push_back(thesis);
        return plots->RenderLines(title, {plot});
    }
    // A short axis (a few pressures, say) reads better as one curve per value than as a heat map.
    const size_t shortAxis = axes[0].values.size() <= axes[1].values.size() ? 0 : 1, longAxis = 1 - shortAxis;
    if (axes[shortAxis].values.size() <= 6 && axes[longAxis].values.size() > axes[shortAxis].values.size()) {
        render::LinePlot plot;
        plot.xLabel = AxisLabel(axes[longAxis].parameter);
        plot.yLabel = e.fitnessLabel;
        plot.zeroLine = true;
        const render::Rgb colours[] = {{0.13f, 0.35f, 0.75f}, {0.85f, 0.45f, 0.10f}, {0.15f, 0.60f, 0.25f},
                                       {0.60f, 0.20f, 0.65f}, {0.55f, 0.35f, 0.20f}, {0.30f, 0.30f, 0.30f}};
        const size_t n1 = axes[1].values.size();
        for (size_t s = 0; s < axes[shortAxis].values.size(); ++s) {
            render::LineSeries series{ValueLabel(axes[shortAxis].parameter, axes[shortAxis].values[s]), axes[longAxis].values, {}, colours[s % 6], true};
            series.markFailed = true;
            for (size_t k = 0; k < axes[longAxis].values.size(); ++k)
                series.y.push_back(fitness[shortAxis == 0 ? s * n1 + k : k * n1 + s]);
            plot.series.push_back(series);
        }
        if (axes[longAxis].parameter == sim::SweepParameter::FibreAngleDeg) {
            // The ideal McKibben muscle's free contraction, 1 - cos(54.74 deg) / cos(alpha): what an
            // inextensible braid on a wall of no stiffness reaches at any pressure.
            // Drawn down to a little below the data: past about 70 degrees it falls away steeply.
            double low = INFINITY, high = -INFINITY;
            for (double f : fitness)
                if (std::isfinite(f)) {
                    low = std::min(low, f);
                    high = std::max(high, f);
                }
            const double floor = std::isfinite(low) ? low - 0.25 * std::max(high - low, 1.0) : -50;
            render::LineSeries ideal{"ideal McKibben muscle (inextensible braid, no wall)", {}, {}, {0.2f, 0.2f, 0.2f}, false};
            for (double a = 0; a <= 89.01; a += 0.5) {
                const double y = 100 * (1 - std::cos(54.7356 * std::numbers::pi / 180) / std::cos(a * std::numbers::pi / 180));
                if (y < floor) break;
                ideal.x.push_back(a);
                ideal.y.push_back(y);
            }
            plot.series.push_back(ideal);
        }
        if (best >= 0) {
            const size_t b = static_cast<size_t>(best);
            plot.highlight = std::pair{axes[longAxis].values[shortAxis == 0 ? b % n1 : b / n1], fitness[b]};
            plot.highlightLabel = bestText;
        }
        return plots->RenderLines(title, {plot});
    }
    render::Heatmap heatmap;
    heatmap.xLabel = AxisLabel(axes[1].parameter);
    heatmap.yLabel = AxisLabel(axes[0].parameter);
    heatmap.valueLabel = e.valueLabel;
    heatmap.xValues = axes[1].values;
    heatmap.yValues = axes[0].values;
    heatmap.values = fitness;
    if (best >= 0) {
        heatmap.highlight = static_cast<size_t>(best);
        heatmap.highlightLabel = bestText;
    }
    const size_t failed = static_cast<size_t>(std::count_if(fitness.begin(), fitness.end(), [](double f) { return !std::isfinite(f); }));
    heatmap.failedLabel = fmt::format("failed\n({} of {})", failed, fitness.size());
    // The designs the thesis names (Table 4.4), at their parameters.
    for (size_t k = 0; k < e.thesisPoints.size(); ++k) {
        const auto& point = e.thesisPoints[k];
        render::Heatmap::Mark mark{NAN, NAN, fmt::format("T{}: {:g}", k + 1, point.value)};
        for (const auto& [parameter, value] : point.at) {
            if (parameter == axes[1].parameter) mark.x = value;
            if (parameter == axes[0].parameter) mark.y = value;
        }
        if (std::isfinite(mark.x) && std::isfinite(mark.y)) heatmap.marks.push_back(mark);
    }
    if (!heatmap.marks.empty()) heatmap.marksLegend = "black dots: the thesis's own designs and fitness (T1, T2, ... in the order of its table)";
    return plots->RenderHeatmap(title, heatmap);
}

render::Image EvolutionImage(const PlotContext& e, const std::vector<RunCurve>& runs) {
    auto plots = MakePlots(std::min(2400, 560 * static_cast<int>(runs.size()) + 200), 640);
    std::vector<render::LinePlot> panels;
    for (const RunCurve& run : runs) {
        render::LinePlot plot;
        plot.title = run.title;
        plot.xLabel = "generation";
        plot.integerX = true;
        plot.yLabel = e.fitnessLabel;
        // The whole population's spread (worst to best) and its middle half (interquartile range),
        // with the best and the median: bands that cannot rise above the best line.
        const render::Rgb blue{0.13f, 0.35f, 0.75f};
        render::LineSeries bestLine{"best", {}, {}, {0.10f, 0.55f, 0.20f}}, medianLine{"median", {}, {}, blue};
        render::Band range{"worst to best", {}, {}, {}, {0.55f, 0.60f, 0.70f}}, middle{"interquartile range", {}, {}, {}, blue};
        for (const auto& row : run.logbook) {
            const double g = row.generation;
            bestLine.x.push_back(g);
            bestLine.y.push_back(row.best);
            medianLine.x.push_back(g);
            medianLine.y.push_back(row.median);
            range.x.push_back(g);
            range.low.push_back(std::min(row.worst, row.best));
            range.high.push_back(std::max(row.worst, row.best));
            middle.x.push_back(g);
            middle.low.push_back(row.q1);
            middle.high.push_back(row.q3);
        }
        plot.bands = {range, middle};
        plot.series = {bestLine, medianLine};
        if (run.showBestSoFar) {
            bestLine.label = "generation's best";
            render::LineSeries soFar{"best so far", {}, {}, {0.05f, 0.05f, 0.05f}};
            for (const auto& row : run.logbook) {
                soFar.x.push_back(row.generation);
                soFar.y.push_back(row.bestSoFar);
            }
            plot.series = {soFar, bestLine, medianLine};
        }
        if (std::isfinite(run.reference) && !run.logbook.empty()) {
            // The thesis's number for this run, as a reference line across the generations.
            render::LineSeries reference{run.referenceLabel, {double(run.logbook.front().generation), double(run.logbook.back().generation)},
                                         {run.reference, run.reference}, {0.85f, 0.45f, 0.10f}};
            plot.series.push_back(reference);
        }
        if (!run.logbook.empty()) {
            const auto& last = run.logbook.back();
            const double best = run.showBestSoFar ? last.bestSoFar : last.best;
            plot.highlight = std::pair{double(last.generation), best};
            plot.highlightLabel = fmt::format("best {:.4f}", best);
        }
        panels.push_back(plot);
    }
    return plots->RenderLines(e.title + "  -  evolution", panels);
}

std::string ThesisBestLegend(const std::vector<double>& runBest, size_t runs) {
    if (runs <= 1 || runBest.size() <= 1) return runBest.empty() ? "" : fmt::format("thesis's best: {:g}", runBest[0]);
    std::string values;
    for (size_t r = 0; r < runs && r < runBest.size(); ++r) values += fmt::format("{}{:g}", r ? ", " : "", runBest[r]);
    return fmt::format("thesis's best of that run (runs 1-{}: {})", std::min(runs, runBest.size()), values);
}

render::Image ParetoImage(const PlotContext& e, const std::vector<ParetoPoint>& all, const std::vector<ParetoPoint>& front) {
    auto plots = MakePlots(1200, 800);
    const sim::Objective& a = e.objectives[0];
    const sim::Objective& b = e.objectives[1];
    render::LinePlot plot;
    plot.xLabel = fmt::format("{} ({})", sim::ObjectiveUnit(a.kind), a.maximise ? "better to the right" : "better to the left");
    plot.yLabel = fmt::format("{} ({})", sim::ObjectiveUnit(b.kind), b.maximise ? "better up" : "better down");
    render::LineSeries cloud{fmt::format("every valid design ({})", all.size()), {}, {}, {0.45f, 0.45f, 0.50f}, true};
    cloud.lines = false;
    cloud.alpha = 0.3f;
    for (const auto& p : all) {
        cloud.x.push_back(p.x);
        cloud.y.push_back(p.y);
    }
    // The front drawn as a staircase-free polyline through its designs sorted by the first objective.
    render::LineSeries line{fmt::format("non-dominated front ({} designs, numbered as in pareto_front.csv)", front.size()), {}, {}, {0.80f, 0.20f, 0.15f}, true};
    for (size_t k = 0; k < front.size(); ++k) {
        line.x.push_back(front[k].x);
        line.y.push_back(front[k].y);
        line.pointLabels.push_back(std::to_string(k + 1));
    }
    plot.series = {cloud, line};
    std::string extra = e.objectives.size() > 2 ? fmt::format(" (first two of {} objectives)", e.objectives.size()) : "";
    return plots->RenderLines(e.title + "  -  Pareto front, run 1" + extra, {plot});
}

render::Image HypervolumeImage(const PlotContext& e, const std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>>& runs) {
    auto plots = MakePlots(1024, 640);
    render::LinePlot plot;
    plot.xLabel = "generation";
    plot.integerX = true;
    std::string units;
    for (const sim::Objective& o : e.objectives) units += (units.empty() ? "" : " x ") + std::string(sim::ObjectiveUnit(o.kind));
    plot.yLabel = "hypervolume of every valid design so far (" + units + ")";
    const render::Rgb colours[] = {{0.13f, 0.35f, 0.75f}, {0.80f, 0.20f, 0.15f}, {0.10f, 0.55f, 0.20f}, {0.55f, 0.25f, 0.65f}, {0.85f, 0.55f, 0.10f}};
    for (size_t r = 0; r < runs.size(); ++r) {
        render::LineSeries series{runs[r].first, {}, {}, colours[r % 5], true};
        for (const auto& [g, hv] : runs[r].second) {
            series.x.push_back(g);
            series.y.push_back(hv);
        }
        plot.series.push_back(series);
    }
    return plots->RenderLines(e.title + "  -  hypervolume (reference point fixed at generation 0)", {plot});
}

render::Image PressureCurveImage(const std::string& title, const sim::SimResult& r, bool topHeld) {
    const sim::ShellOutputs& o = r.shell;
    auto plots = MakePlots(1024, 640);
    render::LinePlot plot;
    plot.xLabel = "gauge pressure (kPa)";
    plot.zeroLine = true;
    // A blocked test (topHeld) holds the top clamp: its curve is the force on it (the contraction is
    // the held stroke at every step). Else the contraction, from rest: zero pressure, zero contraction.
    const bool held = topHeld && o.curveForceN.size() == o.curvePressureKpa.size();
    const std::vector<double>& along = held ? o.curveForceN : o.curveContractionPercent;
    plot.yLabel = held ? "force on the held top clamp (N, + pulls on the supports)" : "contraction (percent, positive = shorter)";
    render::LineSeries curve{"equilibrium at each load step", {}, {}, {0.13f, 0.35f, 0.75f}, true};
    if (!held || o.displacementMm == 0) {  // held at its rest place: no force at no pressure
        curve.x.push_back(0.0);
        curve.y.push_back(0.0);
    }
    for (size_t k = 0; k < o.curvePressureKpa.size() && k < along.size(); ++k) {
        curve.x.push_back(o.curvePressureKpa[k]);
        curve.y.push_back(along[k]);
    }
    plot.series.push_back(curve);
    if (std::isfinite(o.collapsePressureKpa) && curve.y.size() > 1) {
        // Vacuum: where the round wall buckled and folded in, a dashed line across the curve's range.
        const auto [low, high] = std::minmax_element(curve.y.begin(), curve.y.end());
        render::LineSeries collapse{fmt::format("collapse at {:.3g} kPa", o.collapsePressureKpa),
                                    {o.collapsePressureKpa, o.collapsePressureKpa}, {*low, *high}, {0.45f, 0.45f, 0.45f}};
        collapse.dashed = true;
        plot.series.push_back(collapse);
    }
    if (std::isfinite(o.limitPressureKpa)) {
        // The limit point: the step at the pressure maximum.
        size_t top = 0;
        for (size_t k = 1; k < curve.x.size(); ++k)
            if (curve.x[k] > curve.x[top]) top = k;
        plot.highlight = std::pair{curve.x[top], curve.y[top]};
        plot.highlightLabel = fmt::format("limit point: pressure maximum {:.3g} kPa", o.limitPressureKpa);
    } else if (curve.x.size() > 1) {
        plot.highlight = std::pair{curve.x.back(), curve.y.back()};
        plot.highlightLabel = !std::isfinite(r.contractionPercent) ? std::string("last converged step (") + sim::Name(r.status) + ")"
                              : held ? fmt::format("{:.3g} N at {:.3g} kPa ({})", o.strokeForceN, o.targetPressureKpa, sim::Name(r.status))
                                     : fmt::format("{:.2f} % at {:.3g} kPa ({})", r.contractionPercent, o.targetPressureKpa, sim::Name(r.status));
    }
    return plots->RenderLines(title + (held ? "  -  force on the held clamp against pressure" : "  -  contraction against pressure"), {plot});
}

render::Image TensileCurveImage(const TensileFigure& f) {
    auto plots = MakePlots(1024, 640);
    render::LinePlot plot;
    plot.title = f.subtitle;
    plot.xLabel = "engineering strain (percent)";
    plot.yLabel = "engineering stress (kPa)";
    const render::Rgb lawColours[] = {{0.13f, 0.35f, 0.75f}, {0.80f, 0.33f, 0.10f}, {0.20f, 0.55f, 0.25f}, {0.45f, 0.30f, 0.60f}};
    double top = 0;
    std::map<int, render::LineSeries> specimens;
    for (const sim::TensilePoint& p : f.measured) {
        if (p.strain > f.maxStrain) continue;
        render::LineSeries& s = specimens[p.specimen];
        if (s.x.empty()) s = {specimens.size() == 1 ? f.measuredLabel : "", {}, {}, {0.15f, 0.15f, 0.15f}, true, false};
        s.x.push_back(100 * p.strain);
        s.y.push_back(p.stressKpa);
        top = std::max(top, p.stressKpa);
    }
    constexpr int kSamples = 200;
    for (size_t k = 0; k < f.laws.size(); ++k) {
        render::LineSeries s{f.laws[k].label, {}, {}, lawColours[k % 4], false};
        s.dashed = f.laws[k].dashed;
        for (int i = 0; i <= kSamples; ++i) {
            const double strain = f.maxStrain * i / kSamples;
            s.x.push_back(100 * strain);
            s.y.push_back(sim::UniaxialStressKpa(f.laws[k].material, 1 + strain));
            top = std::max(top, s.y.back());
        }
        plot.series.push_back(s);
    }
    if (f.fitMaxStrain > 0)
        plot.bands.push_back({fmt::format("range fitted: 0-{:g} %", 100 * f.fitMaxStrain), {0, 100 * f.fitMaxStrain}, {0, 0}, {top, top}, {0.55f, 0.65f, 0.85f}});
    for (auto& [specimen, s] : specimens) plot.series.insert(plot.series.begin(), s);
    return plots->RenderLines(f.title, {plot});
}

CharacteristicImages CharacteristicCurveImages(const std::string& title, const std::vector<double>& pressures,
                                               const std::vector<std::vector<double>>& contraction, const std::vector<std::vector<double>>& force,
                                               const std::vector<std::vector<double>>& ideal, const sim::SimResult& isometric,
                                               const sim::SimResult& freeStroke) {
    auto plots = MakePlots(1024, 640);
    CharacteristicImages images;
    // Lighter to darker with pressure.
    auto shade = [&](size_t k) {
        const float t = pressures.size() > 1 ? static_cast<float>(k) / static_cast<float>(pressures.size() - 1) : 1.0f;
        return render::Rgb{0.55f - 0.45f * t, 0.65f - 0.45f * t, 0.95f - 0.25f * t};
    };
    render::LinePlot isobaric;
    isobaric.xLabel = "contraction (percent of the length, positive = shorter)";
    isobaric.yLabel = "force (N, positive = pulls on its supports)";
    isobaric.zeroLine = true;
    render::LineSeries strokes{"free stroke", {}, {}, {0.1f, 0.1f, 0.1f}, true, false};
    for (size_t k = 0; k < pressures.size(); ++k) {
        if (k < ideal.size() && !ideal[k].empty()) {
            // Dashed in its pressure's colour, as muscle papers set theory beside measurement.
            render::LineSeries theory{k == 0 ? "ideal muscle at each pressure, dashed (Tondu and Lopez 2000)" : "", contraction[k], ideal[k], shade(k), false};
            theory.dashed = true;
            isobaric.series.push_back(theory);
        }
        isobaric.series.push_back({fmt::format("{:g} kPa", pressures[k]), contraction[k], force[k], shade(k), true});
        if (!contraction[k].empty() && force[k].back() == 0) {  // the curve ends at the free state
            strokes.x.push_back(contraction[k].back());
            strokes.y.push_back(0);
        }
    }
    if (!strokes.x.empty()) isobaric.series.push_back(strokes);
    images.forceContraction = plots->RenderLines(title + "  -  isobaric force against contraction", {isobaric});

    // Both curves start at rest: no pressure, no force, no contraction.
    auto overPressure = [&](const char* yLabel, const char* label, const std::vector<double>& values, const sim::SimResult& r, render::Rgb colour) {
        render::LinePlot plot;
        plot.xLabel = "gauge pressure (kPa)";
        plot.yLabel = yLabel;
        plot.zeroLine = true;
        render::LineSeries curve{label, {0.0}, {0.0}, colour, true};
        for (size_t s = 0; s < r.shell.curvePressureKpa.size() && s < values.size(); ++s) {
            curve.x.push_back(r.shell.curvePressureKpa[s]);
            curve.y.push_back(values[s]);
        }
        plot.series.push_back(curve);
        return plot;
    };
    images.forcePressure = plots->RenderLines(title + "  -  isometric force against pressure",
                                              {overPressure("force with the top held at its rest place (N)", "isometric (no contraction)",
                                                            isometric.shell.curveForceN, isometric, {0.75f, 0.3f, 0.15f})});
    images.strokePressure = plots->RenderLines(title + "  -  free stroke against pressure",
                                               {overPressure("free stroke (contraction, percent, positive = shorter)", "free (no load on the top)",
                                                             freeStroke.shell.curveContractionPercent, freeStroke, {0.13f, 0.35f, 0.75f})});
    return images;
}

}  // namespace app
