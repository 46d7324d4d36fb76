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

// Per vertex, the mean strain (length over rest length, less 1) of the edges (springs) that meet
// there, from the rest positions to the deformed ones: the thesis model's field. 0 for a vertex no
// edge reaches.
std::vector<double> EdgeStrainPerVertex(const Surface& surface, const Positions& rest, const Positions& deformed);

}  // namespace sim
