#include "render/colormap.h"

#include <algorithm>
#include <cmath>

namespace render {

Rgb ViridisColor(double t) {
    static const float kStops[][3] = {{0.267f, 0.005f, 0.329f}, {0.283f, 0.141f, 0.458f}, {0.254f, 0.265f, 0.530f},
                                      {0.207f, 0.372f, 0.553f}, {0.164f, 0.471f, 0.558f}, {0.128f, 0.567f, 0.551f},
                                      {0.135f, 0.659f, 0.518f}, {0.267f, 0.749f, 0.441f}, {0.478f, 0.821f, 0.318f},
                                      {0.741f, 0.873f, 0.150f}, {0.993f, 0.906f, 0.144f}};
    constexpr int kCount = sizeof kStops / sizeof kStops[0];
    const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * (kCount - 1);
    const int i = std::min(static_cast<int>(x), kCount - 2);
    const float u = static_cast<float>(x - i);
    return {kStops[i][0] * (1 - u) + kStops[i + 1][0] * u, kStops[i][1] * (1 - u) + kStops[i + 1][1] * u,
            kStops[i][2] * (1 - u) + kStops[i + 1][2] * u};
}

Rgb DivergingColor(double t) {
    static constexpr Rgb kStops[] = {{0.230f, 0.299f, 0.754f}, {0.552f, 0.690f, 0.996f}, {0.865f, 0.865f, 0.865f}, {0.958f, 0.604f, 0.482f}, {0.706f, 0.016f, 0.150f}};
    if (!std::isfinite(t)) t = 0.5;
    t = std::clamp(t, 0.0, 1.0) * 4;
    const int k = std::min(3, static_cast<int>(t));
    const float f = static_cast<float>(t - k);
    const Rgb& a = kStops[k];
    const Rgb& b = kStops[k + 1];
    return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

}  // namespace render
