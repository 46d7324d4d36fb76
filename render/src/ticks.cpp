#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/plot.h"

namespace render {

std::vector<double> NiceTicks(double low, double high, int count) {
    if (!std::isfinite(low) || !std::isfinite(high)) return {};
    if (!(high > low)) {
        const double pad = std::max(std::fabs(low) * 0.1, 0.5);
        low -= pad;
        high += pad;
    }
    const double rough = (high - low) / std::max(1, count);
    const double magnitude = std::pow(10.0, std::floor(std::log10(rough)));
    double step = magnitude;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * magnitude >= rough) {
            step = m * magnitude;
            break;
        }
    std::vector<double> ticks;
    for (double t = std::ceil(low / step - 1e-9) * step; t <= high + step * 1e-9; t += step) ticks.push_back(std::fabs(t) < step * 1e-9 ? 0.0 : t);
    return ticks;
}

std::string ScaleTickText(double value, double span) {
    char text[32];
    const int decimals = span >= 10 ? 0 : std::min(6, static_cast<int>(std::ceil(-std::log10(span / 10) - 1e-9)));
    std::snprintf(text, sizeof text, "%.*f", std::max(0, decimals), std::fabs(value) < 1e-12 * span ? 0.0 : value);
    return text;
}

std::vector<ScaleTick> ColourBarTicks(double low, double high, bool clippedTop, double minGap) {
    const double span = high - low;
    std::vector<ScaleTick> ticks{{low, ScaleTickText(low, span)}, {high, ScaleTickText(high, span)}};
    for (double t : NiceTicks(low, high, 4))
        if (std::string text = ScaleTickText(t, span);
            std::fabs(high - t) > minGap * span && std::fabs(t - low) > minGap * span && text != ticks[0].text && text != ticks[1].text)
            ticks.push_back({t, std::move(text)});
    if (clippedTop) ticks[1].text = "> " + ticks[1].text;
    return ticks;
}

}  // namespace render
