// [SECTION] Colours
// [SECTION] Axes
// [SECTION] Line plots
// [SECTION] Heatmaps
#include <GL/gl.h>

#include "render/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "colour_bar.h"
#include "gl_context.h"
#include "overlay_context.h"

namespace render {

// ---------------------------------------------------------------------------------------------
// [SECTION] Colours
// ---------------------------------------------------------------------------------------------

namespace {

ImU32 Color(const Rgb& c, float alpha = 1) { return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, alpha)); }

// An x of half-width r centred on `at`: a point that has no value.
void AddCross(ImDrawList* draw, ImVec2 at, float r, ImU32 color) {
    draw->AddLine(ImVec2(at.x - r, at.y - r), ImVec2(at.x + r, at.y + r), color, r * 0.5f);
    draw->AddLine(ImVec2(at.x - r, at.y + r), ImVec2(at.x + r, at.y - r), color, r * 0.5f);
}

// A dashed segment from a to b: dashes `dash` long with `gap` between them (pixels), starting `phase`
// pixels into the pattern. Returns the phase at b, for the next segment of the same polyline.
float AddDashedLine(ImDrawList* draw, ImVec2 a, ImVec2 b, ImU32 color, float width, float dash, float gap, float phase) {
    const float period = dash + gap;
    const float length = std::hypot(b.x - a.x, b.y - a.y);
    if (!(length > 0)) return phase;
    const ImVec2 unit((b.x - a.x) / length, (b.y - a.y) / length);
    for (float s = -phase; s < length; s += period) {
        const float from = std::max(s, 0.0f), to = std::min(s + dash, length);
        if (to > from) draw->AddLine(ImVec2(a.x + unit.x * from, a.y + unit.y * from), ImVec2(a.x + unit.x * to, a.y + unit.y * to), color, width);
    }
    return std::fmod(phase + length, period);
}
const ImU32 kInk = IM_COL32(30, 30, 30, 255);

// Draws a figure's title across the top; returns how much taller it wrapped than one line, so that
// what sits under it (panel titles, axis labels) moves down instead of under the title.
float TitleBeyondOneLine(const OverlayContext& o, ImDrawList* draw, float W, const std::string& title) {
    const float fs = o.FontSize(), size = fs * 1.37f;
    const float height = o.DrawTitle(draw, size, ImVec2(fs * 0.7f, fs * 0.5f), W - fs * 1.4f, kInk, title);
    return std::max(0.0f, height - o.TextFont()->CalcTextSizeA(size, FLT_MAX, 0, "Ag").y);
}

const ImU32 kGrid = IM_COL32(225, 225, 225, 255);

std::string TickText(double value, double step) {
    char text[32];
    const int decimals = step >= 1 ? 0 : std::min(6, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

struct Box {
    float x0, y0, x1, y1;
};

// ---------------------------------------------------------------------------------------------
// [SECTION] Axes
// ---------------------------------------------------------------------------------------------

// Maps data to pixels inside a plot box and draws its frame, grid, ticks and labels.
struct Axes {
    Box box;
    double xMin, xMax, yMin, yMax;
    float X(double x) const { return box.x0 + float((x - xMin) / (xMax - xMin)) * (box.x1 - box.x0); }
    float Y(double y) const { return box.y1 - float((y - yMin) / (yMax - yMin)) * (box.y1 - box.y0); }

    void Draw(ImDrawList* draw, const OverlayContext& overlay, const std::vector<double>& xTicks, const std::vector<double>& yTicks,
              const std::string& xLabel, const std::string& yLabel, bool grid) const {
        const float fs = overlay.FontSize(), line = fs * 0.07f;
        const double xStep = xTicks.size() > 1 ? xTicks[1] - xTicks[0] : 1, yStep = yTicks.size() > 1 ? yTicks[1] - yTicks[0] : 1;
        for (double t : yTicks) {
            if (t < yMin - 1e-12 || t > yMax + 1e-12) continue;
            if (grid) draw->AddLine(ImVec2(box.x0, Y(t)), ImVec2(box.x1, Y(t)), kGrid, line);
            draw->AddLine(ImVec2(box.x0 - fs * 0.3f, Y(t)), ImVec2(box.x0, Y(t)), kInk, line);
            const std::string text = TickText(t, yStep);
            const ImVec2 size = overlay.TextFont()->CalcTextSizeA(fs * 0.85f, FLT_MAX, 0, text.c_str());
            draw->AddText(overlay.TextFont(), fs * 0.85f, ImVec2(box.x0 - fs * 0.45f - size.x, Y(t) - size.y / 2), kInk, text.c_str());
        }
        for (double t : xTicks) {
            if (t < xMin - 1e-12 || t > xMax + 1e-12) continue;
            if (grid) draw->AddLine(ImVec2(X(t), box.y0), ImVec2(X(t), box.y1), kGrid, line);
            draw->AddLine(ImVec2(X(t), box.y1), ImVec2(X(t), box.y1 + fs * 0.3f), kInk, line);
            const std::string text = TickText(t, xStep);
            const ImVec2 size = overlay.TextFont()->CalcTextSizeA(fs * 0.85f, FLT_MAX, 0, text.c_str());
            draw->AddText(overlay.TextFont(), fs * 0.85f, ImVec2(X(t) - size.x / 2, box.y1 + fs * 0.4f), kInk, text.c_str());
        }
        draw->AddRect(ImVec2(box.x0, box.y0), ImVec2(box.x1, box.y1), kInk, 0, 0, line);
        const ImVec2 xSize = overlay.TextFont()->CalcTextSizeA(fs, FLT_MAX, 0, xLabel.c_str());
        draw->AddText(overlay.TextFont(), fs, ImVec2((box.x0 + box.x1 - xSize.x) / 2, box.y1 + fs * 1.6f), kInk, xLabel.c_str());
        // The y label goes above the axis, left-aligned: ImGui draws no rotated text.
        draw->AddText(overlay.TextFont(), fs, ImVec2(box.x0 - fs * 0.2f, box.y0 - fs * 1.45f), kInk, yLabel.c_str());
    }
};

}  // namespace

class PlotRendererGl final : public PlotRenderer {
public:
    Image RenderLines(const std::string& title, const std::vector<LinePlot>& plots) override;
    Image RenderHeatmap(const std::string& title, const Heatmap& heatmap) override;

    int width = 0, height = 0;
    static constexpr int kSupersample = 2;
    std::unique_ptr<GlContext> context;
    OverlayContext overlay;

    ImDrawList* Begin() {
        context->MakeCurrent(width * kSupersample, height * kSupersample);
        glViewport(0, 0, width * kSupersample, height * kSupersample);
        glClearColor(1, 1, 1, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        return overlay.Begin(width * kSupersample, height * kSupersample);
    }
    Image End() {
        overlay.End();
        return BoxDownsample(context->FinishAndGetPixels(), width * kSupersample, height * kSupersample, kSupersample, true);
    }
};

std::unique_ptr<PlotRenderer> CreateGlPlotRenderer(int width, int height, std::string* error) {
    auto r = std::make_unique<PlotRendererGl>();
    r->width = width;
    r->height = height;
    r->context = CreateGlContext(error);
    if (!r->context || !r->context->MakeCurrent(width * PlotRendererGl::kSupersample, height * PlotRendererGl::kSupersample)) {
        if (error && error->empty()) *error = std::string(kBackendName) + " could not make the context current";
        return nullptr;
    }
    if (!r->overlay.Create(PlotRendererGl::kSupersample * std::max(0.85f, height / 768.0f), error)) return nullptr;
    return r;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Line plots
// ---------------------------------------------------------------------------------------------

Image PlotRendererGl::RenderLines(const std::string& title, const std::vector<LinePlot>& plots) {
    ImDrawList* draw = Begin();
    const OverlayContext& o = overlay;
    const float W = float(width * kSupersample), H = float(height * kSupersample), fs = o.FontSize();
    const float titleExtra = TitleBeyondOneLine(o, draw, W, title);

    // One y range for all plots, so runs side by side compare at a glance.
    double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
    auto extend = [&](const std::vector<double>& xs, const std::vector<double>& ys) {
        for (size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
            if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) continue;
            xMin = std::min(xMin, xs[i]); xMax = std::max(xMax, xs[i]);
            yMin = std::min(yMin, ys[i]); yMax = std::max(yMax, ys[i]);
        }
    };
    for (const auto& plot : plots) {
        for (const auto& series : plot.series) extend(series.x, series.y);
        for (const auto& band : plot.bands) { extend(band.x, band.low); extend(band.x, band.high); }
        if (plot.zeroLine) { yMin = std::min(yMin, 0.0); yMax = std::max(yMax, 0.0); }
    }
    if (!(xMax >= xMin)) { xMin = 0; xMax = 1; }
    if (!(yMax >= yMin)) { yMin = 0; yMax = 1; }
    auto xTicks = NiceTicks(xMin, xMax, 6);
    const auto yTicks = NiceTicks(yMin, yMax, 6);
    // A count's axis has no 0.2 of a generation: keep whole ticks (two generations: 0, 1, 2).
    if (std::all_of(plots.begin(), plots.end(), [](const LinePlot& p) { return p.integerX; })) {
        auto whole = xTicks;
        std::erase_if(whole, [](double t) { return std::fabs(t - std::round(t)) > 1e-9; });
        if (whole.size() >= 2) xTicks = whole;
    }
    if (xMax == xMin) { xMin = xTicks.front(); xMax = xTicks.back(); }
    // A little room around the data, so that lines, markers and rings at the extremes stay visible.
    const double xPad = 0.02 * (xMax - xMin), yPad = 0.07 * (yMax - yMin);
    xMin -= xPad; xMax += xPad; yMin -= yPad; yMax += yPad;

    const int count = std::max<int>(1, plots.size());
    bool titled = false;
    for (const auto& plot : plots) titled = titled || !plot.title.empty();
    const float left = fs * 4.2f, right = fs * 1.2f, top = fs * (titled ? 6.0f : 4.6f) + titleExtra, bottom = fs * 7.0f, gap = fs * 4.0f;
    const float plotWidth = (W - left - right - gap * (count - 1)) / count;
    for (int p = 0; p < int(plots.size()); ++p) {
        const LinePlot& plot = plots[p];
        const float x0 = left + p * (plotWidth + gap);
        Axes axes{{x0, top, x0 + plotWidth, H - bottom}, xMin, xMax, yMin, yMax};
        if (!plot.title.empty()) {
            const ImVec2 size = o.TextFont()->CalcTextSizeA(fs * 1.05f, FLT_MAX, 0, plot.title.c_str());
            draw->AddText(o.TextFont(), fs * 1.05f, ImVec2(x0 + (plotWidth - size.x) / 2, top - fs * 3.1f), kInk, plot.title.c_str());
        }
        axes.Draw(draw, o, xTicks, yTicks, plot.xLabel, plot.yLabel, true);
        draw->PushClipRect(ImVec2(axes.box.x0, axes.box.y0), ImVec2(axes.box.x1, axes.box.y1), true);
        if (plot.zeroLine) draw->AddLine(ImVec2(axes.box.x0, axes.Y(0)), ImVec2(axes.box.x1, axes.Y(0)), IM_COL32(120, 120, 120, 255), fs * 0.06f);
        // Bands are drawn as adjacent quads; anti-aliased edges would show as seams between them.
        const ImDrawListFlags flags = draw->Flags;
        draw->Flags &= ~ImDrawListFlags_AntiAliasedFill;
        for (const Band& band : plot.bands)
            for (size_t i = 1; i < band.x.size(); ++i) {
                if (!std::isfinite(band.low[i - 1] + band.low[i] + band.high[i - 1] + band.high[i])) continue;
                const ImVec2 quad[4] = {ImVec2(axes.X(band.x[i - 1]), axes.Y(band.low[i - 1])), ImVec2(axes.X(band.x[i]), axes.Y(band.low[i])),
                                        ImVec2(axes.X(band.x[i]), axes.Y(band.high[i])), ImVec2(axes.X(band.x[i - 1]), axes.Y(band.high[i - 1]))};
                draw->AddConvexPolyFilled(quad, 4, Color(band.color, 0.22f));
            }
        draw->Flags = flags;
        for (const LineSeries& series : plot.series) {
            float dashPhase = 0;  // carried along the polyline, so that dashes do not restart at every point
            for (size_t i = 1; series.lines && i < series.x.size(); ++i) {
                if (!std::isfinite(series.y[i - 1]) || !std::isfinite(series.y[i])) continue;
                const ImVec2 a(axes.X(series.x[i - 1]), axes.Y(series.y[i - 1])), b(axes.X(series.x[i]), axes.Y(series.y[i]));
                if (series.dashed) dashPhase = AddDashedLine(draw, a, b, Color(series.color), fs * 0.16f, fs * 0.7f, fs * 0.45f, dashPhase);
                else draw->AddLine(a, b, Color(series.color), fs * 0.16f);
            }
            // Failed points are not left out in silence: a cross on the floor at their x.
            for (size_t i = 0; series.markFailed && i < series.x.size(); ++i)
                if (!std::isfinite(series.y[i]) && std::isfinite(series.x[i])) AddCross(draw, ImVec2(axes.X(series.x[i]), axes.box.y1 - fs * 0.5f), fs * 0.3f, Color(series.color));
            if (series.markers)
                for (size_t i = 0; i < series.x.size(); ++i)
                    if (std::isfinite(series.y[i])) draw->AddCircleFilled(ImVec2(axes.X(series.x[i]), axes.Y(series.y[i])), fs * 0.22f, Color(series.color, series.alpha));
            // A label that would overlap one already drawn is left out (crowded fronts stay legible).
            std::vector<ImVec2> drawn;
            for (size_t i = 0; i < series.pointLabels.size() && i < series.x.size(); ++i) {
                if (!std::isfinite(series.y[i]) || series.pointLabels[i].empty()) continue;
                const ImVec2 at(axes.X(series.x[i]) + fs * 0.3f, axes.Y(series.y[i]) - fs * 1.0f);
                const ImVec2 size = o.TextFont()->CalcTextSizeA(fs * 0.8f, FLT_MAX, 0, series.pointLabels[i].c_str());
                bool clear = true;
                for (const ImVec2& d : drawn) clear = clear && (std::fabs(d.x - at.x) > size.x + fs * 0.3f || std::fabs(d.y - at.y) > fs * 0.9f);
                if (!clear) continue;
                drawn.push_back(at);
                draw->AddText(o.TextFont(), fs * 0.8f, at, Color(series.color), series.pointLabels[i].c_str());
            }
        }
        if (plot.highlight) {
            const ImVec2 at(axes.X(plot.highlight->first), axes.Y(plot.highlight->second));
            draw->AddCircle(at, fs * 0.55f, IM_COL32(200, 30, 30, 255), 24, fs * 0.14f);
        }
        draw->PopClipRect();
        // The highlight's note sits in the plot's top-left corner on a white card: never clipped.
        if (plot.highlight && !plot.highlightLabel.empty()) {
            const ImVec2 size = o.TextFont()->CalcTextSizeA(fs * 0.9f, FLT_MAX, 0, plot.highlightLabel.c_str());
            const ImVec2 corner(axes.box.x0 + fs * 0.5f, axes.box.y0 + fs * 0.4f);
            draw->AddRectFilled(corner, ImVec2(corner.x + size.x + fs * 2.2f, corner.y + size.y + fs * 0.4f), IM_COL32(255, 255, 255, 230));
            draw->AddCircle(ImVec2(corner.x + fs * 0.8f, corner.y + size.y / 2 + fs * 0.2f), fs * 0.4f, IM_COL32(200, 30, 30, 255), 24, fs * 0.12f);
            draw->AddText(o.TextFont(), fs * 0.9f, ImVec2(corner.x + fs * 1.6f, corner.y + fs * 0.2f), IM_COL32(170, 20, 20, 255), plot.highlightLabel.c_str());
        }
    }
    // Legend under the plots, from the first plot's series and bands; on two rows when one would run
    // past the right edge.
    if (!plots.empty()) {
        struct Entry {
            std::string label;
            ImU32 color;
            int kind;  // 0 line, 1 filled, 2 dot, 3 dashed line, 4 cross
            float width;
        };
        std::vector<Entry> entries;
        auto add = [&](const std::string& label, ImU32 color, int kind) {
            if (!label.empty()) entries.push_back({label, color, kind, fs * 3.8f + o.TextFont()->CalcTextSizeA(fs * 0.9f, FLT_MAX, 0, label.c_str()).x});
        };
        for (const auto& series : plots[0].series) add(series.label, Color(series.color, std::max(series.alpha, 0.5f)), !series.lines ? 2 : series.dashed ? 3 : 0);
        for (const auto& band : plots[0].bands) add(band.label, Color(band.color, 0.35f), 1);
        bool failed = false;
        for (const auto& plot : plots)
            for (const auto& series : plot.series)
                for (size_t i = 0; series.markFailed && i < series.x.size() && i < series.y.size(); ++i) failed = failed || !std::isfinite(series.y[i]);
        if (failed) add("failed (no value)", kInk, 4);
        float total = 0;
        for (const Entry& e : entries) total += e.width;
        const bool twoRows = left + total > W - right;
        float x = left, y = H - fs * (twoRows ? 2.7f : 2.2f);
        for (const Entry& e : entries) {
            if (twoRows && x > left && x + e.width > W - right) {
                x = left;
                y += fs * 1.3f;
            }
            if (e.kind == 1) draw->AddRectFilled(ImVec2(x, y + fs * 0.15f), ImVec2(x + fs * 1.6f, y + fs * 0.85f), e.color);
            else if (e.kind == 2) draw->AddCircleFilled(ImVec2(x + fs * 0.8f, y + fs * 0.5f), fs * 0.3f, e.color);
            else if (e.kind == 4) AddCross(draw, ImVec2(x + fs * 0.8f, y + fs * 0.5f), fs * 0.3f, e.color);
            else if (e.kind == 3) AddDashedLine(draw, ImVec2(x, y + fs * 0.5f), ImVec2(x + fs * 1.6f, y + fs * 0.5f), e.color, fs * 0.18f, fs * 0.5f, fs * 0.3f, 0);
            else draw->AddLine(ImVec2(x, y + fs * 0.5f), ImVec2(x + fs * 1.6f, y + fs * 0.5f), e.color, fs * 0.18f);
            draw->AddText(o.TextFont(), fs * 0.9f, ImVec2(x + fs * 2.0f, y), kInk, e.label.c_str());
            x += e.width;
        }
    }
    return End();
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Heatmaps
// ---------------------------------------------------------------------------------------------

Image PlotRendererGl::RenderHeatmap(const std::string& title, const Heatmap& h) {
    ImDrawList* draw = Begin();
    const OverlayContext& o = overlay;
    const float W = float(width * kSupersample), H = float(height * kSupersample), fs = o.FontSize();
    const float titleExtra = TitleBeyondOneLine(o, draw, W, title);

    const size_t nx = h.xValues.size(), ny = h.yValues.size();
    double vMin = INFINITY, vMax = -INFINITY;
    for (double v : h.values)
        if (std::isfinite(v)) { vMin = std::min(vMin, v); vMax = std::max(vMax, v); }
    if (!(vMax > vMin)) { vMin = std::isfinite(vMin) ? vMin - 0.5 : 0; vMax = vMin + 1; }
    // Values of both signs: a diverging map centred on 0, so the sign reads at a glance.
    const bool diverging = vMin < 0 && vMax > 0;
    if (diverging) {
        const double reach = std::max(-vMin, vMax);
        vMin = -reach;
        vMax = reach;
    }
    Rgb (*const map)(double) = diverging ? &DivergingColor : &ViridisColor;

    // Cells are centred on the grid values; the axes span half a cell beyond the outer ones.
    auto edges = [](const std::vector<double>& v) {
        std::vector<double> e(v.size() + 1);
        if (v.size() == 1) { e[0] = v[0] - 0.5; e[1] = v[0] + 0.5; return e; }
        for (size_t i = 1; i < v.size(); ++i) e[i] = (v[i - 1] + v[i]) / 2;
        e[0] = v[0] - (e[1] - v[0]);
        e[v.size()] = v.back() + (v.back() - e[v.size() - 1]);
        return e;
    };
    const auto xe = edges(h.xValues), ye = edges(h.yValues);
    const float left = fs * 4.6f, right = fs * 9.0f, top = fs * 4.6f + titleExtra, bottom = fs * (h.marksLegend.empty() ? 4.2f : 5.8f);
    Axes axes{{left, top, W - right, H - bottom}, xe.front(), xe.back(), ye.front(), ye.back()};
    for (size_t j = 0; j < ny; ++j)
        for (size_t i = 0; i < nx; ++i) {
            const double v = h.values[j * nx + i];
            const ImU32 c = std::isfinite(v) ? Color(map((v - vMin) / (vMax - vMin))) : IM_COL32(170, 170, 170, 255);
            draw->AddRectFilled(ImVec2(axes.X(xe[i]), axes.Y(ye[j + 1])), ImVec2(axes.X(xe[i + 1]) + 0.5f, axes.Y(ye[j]) + 0.5f), c);
        }
    // Integer-valued axes (cycles) get one tick per value; continuous ones get nice ticks.
    auto ticksFor = [](const std::vector<double>& v) {
        bool integers = v.size() <= 12;
        for (double x : v) integers = integers && x == std::round(x);
        return integers ? v : NiceTicks(v.front(), v.back(), 6);
    };
    axes.Draw(draw, o, ticksFor(h.xValues), ticksFor(h.yValues), h.xLabel, h.yLabel, false);
    if (h.highlight && *h.highlight < h.values.size()) {
        const size_t i = *h.highlight % nx, j = *h.highlight / nx;
        draw->AddRect(ImVec2(axes.X(xe[i]), axes.Y(ye[j + 1])), ImVec2(axes.X(xe[i + 1]), axes.Y(ye[j])), IM_COL32(220, 30, 30, 255), 0, 0, fs * 0.18f);
        draw->AddText(o.TextFont(), fs * 0.9f, ImVec2(axes.box.x0, H - fs * 1.5f), IM_COL32(200, 30, 30, 255), h.highlightLabel.c_str());
    }
    // Marks: a ringed dot at each point, its label beside it, and what they are under the plot.
    for (const Heatmap::Mark& mark : h.marks) {
        const ImVec2 at(axes.X(mark.x), axes.Y(mark.y));
        draw->AddCircleFilled(at, fs * 0.32f, IM_COL32(255, 255, 255, 255));
        draw->AddCircleFilled(at, fs * 0.22f, IM_COL32(20, 20, 20, 255));
        const ImVec2 size = o.TextFont()->CalcTextSizeA(fs * 0.8f, FLT_MAX, 0, mark.label.c_str());
        const float x = at.x + fs * 0.45f + size.x < axes.box.x1 ? at.x + fs * 0.45f : at.x - fs * 0.45f - size.x;
        draw->AddRectFilled(ImVec2(x - fs * 0.12f, at.y - size.y / 2), ImVec2(x + size.x + fs * 0.12f, at.y + size.y / 2), IM_COL32(255, 255, 255, 210));
        draw->AddText(o.TextFont(), fs * 0.8f, ImVec2(x, at.y - size.y / 2), IM_COL32(20, 20, 20, 255), mark.label.c_str());
    }
    if (!h.marksLegend.empty())
        draw->AddText(o.TextFont(), fs * 0.9f, ImVec2(axes.box.x0, H - fs * 2.9f), IM_COL32(20, 20, 20, 255), h.marksLegend.c_str());
    ColourBar bar;
    bar.map = map;
    bar.x0 = W - right + fs * 1.6f;
    bar.x1 = bar.x0 + fs * 1.3f;
    bar.y0 = axes.box.y0;
    bar.y1 = axes.box.y1;
    bar.min = vMin;
    bar.max = vMax;
    bar.label = h.valueLabel;
    DrawColourBar(draw, o, bar);
    // Grey cells say what they are: a swatch and its label under the colour bar.
    if (std::any_of(h.values.begin(), h.values.end(), [](double v) { return !std::isfinite(v); })) {
        const float y = bar.y1 + fs * 1.2f;
        draw->AddRectFilled(ImVec2(bar.x0, y), ImVec2(bar.x1, y + fs * 0.9f), IM_COL32(170, 170, 170, 255));
        draw->AddRect(ImVec2(bar.x0, y), ImVec2(bar.x1, y + fs * 0.9f), IM_COL32(30, 30, 30, 255), 0, 0, fs * 0.06f);
        draw->AddText(o.TextFont(), fs * 0.8f, ImVec2(bar.x1 + fs * 0.4f, y), kInk, h.failedLabel.c_str());
    }
    return End();
}

}  // namespace render
