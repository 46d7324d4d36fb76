// What a picture or an exported file needs of a model's mesh besides the positions: its triangles
// (oriented outward) and the edges drawn as a wireframe and measured for strain. Each model makes
// its own; the renderer draws any of them.
#pragma once

#include <array>
#include <vector>

#include "sim/mesh.h"

namespace sim {

struct Surface {
    int vertexCount = 0;
    std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside the tube
    std::vector<std::array<int, 2>> edges;      // springs (thesis) or element edges (shell models)

    bool operator==(const Surface&) const = default;
};

// The thesis helix: its drawing triangles turned outward, and its springs as edges.
Surface HelixSurface(const MeshDef& def);

}  // namespace sim
