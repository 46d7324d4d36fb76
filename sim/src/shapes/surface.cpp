#include "sim/surface.h"

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

}  // namespace sim
