#include "render/scene.h"

#include <algorithm>
#include <cmath>

namespace render {

RenderDef DefaultRenderDef() { return RenderDef{}; }

namespace {

bool Finite(const sim::Positions& p, int i) { return std::isfinite(p.x[i]) && std::isfinite(p.y[i]) && std::isfinite(p.z[i]); }

double Distance(const sim::Positions& p, int a, const sim::Positions& q, int b) {
    return std::sqrt((p.x[a] - q.x[b]) * (p.x[a] - q.x[b]) + (p.y[a] - q.y[b]) * (p.y[a] - q.y[b]) + (p.z[a] - q.z[b]) * (p.z[a] - q.z[b]));
}

}  // namespace

Framing FrameMeshes(const std::vector<const sim::Positions*>& meshes) {
    Framing f{0, INFINITY, -INFINITY};
    for (const sim::Positions* p : meshes) {
        for (int i = 0; i < p->Size(); ++i) {
            if (!Finite(*p, i)) continue;
            f.radius = std::max(f.radius, std::hypot(p->x[i], p->y[i]));
            f.zMin = std::min(f.zMin, p->z[i]);
            f.zMax = std::max(f.zMax, p->z[i]);
        }
    }
    if (!(f.zMin <= f.zMax)) f = Framing{};
    f.radius = std::max(f.radius, 1e-3);
    return f;
}

std::vector<double> VertexValues(ColorBy colorBy, const sim::Surface& surface, const Panel& panel) {
    const sim::Positions& p = panel.positions;
    const sim::Positions& reference = panel.reference;
    const int n = p.Size();
    std::vector<double> values(n, 0.0);
    for (int i = 0; i < n; ++i)
        if (!Finite(p, i)) values[i] = NAN;
    if (colorBy == ColorBy::Values) {
        for (int i = 0; i < n && i < static_cast<int>(panel.values.size()); ++i)
            if (std::isfinite(values[i])) values[i] = panel.values[i];
        return values;
    }
    if (colorBy == ColorBy::Shading || reference.Size() != n) return values;
    if (colorBy == ColorBy::Displacement) {
        for (int i = 0; i < n; ++i)
            if (std::isfinite(values[i])) values[i] = Distance(p, i, reference, i);
        return values;
    }
    std::vector<int> edges(n, 0);
    for (const auto& [a, b] : surface.edges) {
        if (a >= n || b >= n) continue;
        const double rest = Distance(reference, a, reference, b);
        if (!(rest > 0)) continue;
        const double strain = 100.0 * std::fabs(Distance(p, a, p, b) / rest - 1.0);
        values[a] += strain;
        values[b] += strain;
        ++edges[a];
        ++edges[b];
    }
    for (int i = 0; i < n; ++i)
        if (edges[i]) values[i] /= edges[i];
    return values;
}

double RobustColorMax(const std::vector<std::vector<double>>& values) {
    std::vector<double> all;
    for (const auto& panel : values)
        for (double v : panel)
            if (std::isfinite(v)) all.push_back(v);
    if (all.empty()) return 0;
    const size_t k = std::min(all.size() - 1, static_cast<size_t>(0.98 * (all.size() - 1)));
    std::nth_element(all.begin(), all.begin() + k, all.end());
    return all[k];
}

}  // namespace render
