#include "sim/surface.h"

#include <cmath>

namespace sim {

Surface HelixSurface(const MeshDef& def) {
    Surface s;
    s.vertexCount = VertexCount(def);
    // docs/models/thesis.md's quads (i, i+1, i+R+1, i+R) wind inward on the helix (it turns clockwise seen from
    // above, since x = sin and y = cos): swap two corners to face outward.
    for (const auto& t : Triangles(def)) s.triangles.push_back({t[0], t[2], t[1]});
    for (int offset : SpringOffsets(def))
        for (int a = 0; a + offset < s.vertexCount; ++a) s.edges.push_back({a, a + offset});
    return s;
}

std::vector<double> EdgeStrainPerVertex(const Surface& surface, const Positions& rest, const Positions& deformed) {
    const int n = deformed.Size();
    std::vector<double> strain(n, 0.0);
    std::vector<int> count(n, 0);
    auto length = [](const Positions& p, int a, int b) { return std::hypot(p.x[a] - p.x[b], p.y[a] - p.y[b], p.z[a] - p.z[b]); };
    for (const auto& [a, b] : surface.edges) {
        if (a >= n || b >= n || a >= rest.Size() || b >= rest.Size()) continue;
        const double restLength = length(rest, a, b);
        if (!(restLength > 0)) continue;
        const double e = length(deformed, a, b) / restLength - 1;
        strain[a] += e;
        strain[b] += e;
        ++count[a];
        ++count[b];
    }
    for (int v = 0; v < n; ++v)
        if (count[v]) strain[v] /= count[v];
    return strain;
}

}  // namespace sim
