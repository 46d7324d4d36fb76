#include "colour_bar.h"

#include <cmath>
#include <cstdio>

#include "render/plot.h"

namespace render {
namespace {

ImU32 Colour(const Rgb& c) { return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1)); }

}  // namespace

void DrawColourBar(ImDrawList* draw, const OverlayContext& overlay, const ColourBar& bar) {
    const float fs = overlay.FontSize();
    const ImU32 ink = IM_COL32(30, 30, 30, 255);
    const int steps = 64;
    const float height = bar.y1 - bar.y0, width = bar.x1 - bar.x0;
    for (int s = 0; s < steps; ++s) {
        const float ya = bar.y1 - height * s / steps, yb = bar.y1 - height * (s + 1) / steps;
        const ImU32 bottom = Colour(bar.map(double(s) / steps)), top = Colour(bar.map(double(s + 1) / steps));
        draw->AddRectFilledMultiColor(ImVec2(bar.x0, yb), ImVec2(bar.x1, ya + 0.5f), top, top, bottom, bottom);
    }
    draw->AddRect(ImVec2(bar.x0, bar.y0), ImVec2(bar.x1, bar.y1), ink, 0, 0, fs * 0.06f);
    const double span = bar.max - bar.min;
    auto yOf = [&](double v) { return bar.y1 - float((v - bar.min) / span) * height; };
    auto tick = [&](double v, const std::string& text) {
        const float y = yOf(v);
        draw->AddLine(ImVec2(bar.x1, y), ImVec2(bar.x1 + width * 0.25f, y), ink, fs * 0.06f);
        draw->AddText(overlay.TextFont(), fs * 0.85f, ImVec2(bar.x1 + width * 0.35f, y - fs * 0.45f), ink, text.c_str());
    };
    // Both ends always, and nice ticks in between that neither crowd nor repeat them.
    for (const ScaleTick& t : ColourBarTicks(bar.min, bar.max, bar.clippedTop, fs * 1.1f / height)) tick(t.value, t.text);
    // Marks on the scale are lines; marks off it are named under the bar with their value, so that a
    // limit far above what the picture shows is still stated (a stretch of 1.3 against 5.5).
    const ImU32 red = IM_COL32(200, 30, 30, 255);
    float below = bar.y1 + fs * 0.25f;
    for (const ScaleMark& mark : bar.marks) {
        const double t = (mark.value - bar.min) / span;
        if (!(t >= 0 && t <= 1)) {
            const std::string text = mark.label + "\n" + ScaleTickText(mark.value, span) + (t > 1 ? ", above" : ", below");
            draw->AddText(overlay.TextFont(), fs * 0.7f, ImVec2(bar.x0 - width * 0.15f, below), red, text.c_str());
            below += fs * 1.6f;
            continue;
        }
        const float y = yOf(mark.value);
        draw->AddLine(ImVec2(bar.x0 - width * 0.15f, y), ImVec2(bar.x1, y), red, fs * 0.14f);
        draw->AddText(overlay.TextFont(), fs * 0.75f, ImVec2(bar.x1 + width * 0.35f, y + fs * 0.3f), red, mark.label.c_str());
    }
    const ImVec2 size = overlay.TextFont()->CalcTextSizeA(fs * 0.85f, FLT_MAX, 0, bar.label.c_str());
    const float labelX = bar.labelX >= 0 ? bar.labelX : bar.x0 - fs * 0.2f;
    draw->AddText(overlay.TextFont(), fs * 0.85f, ImVec2(labelX, bar.y0 - size.y - fs * 0.5f), ink, bar.label.c_str());
}

}  // namespace render
