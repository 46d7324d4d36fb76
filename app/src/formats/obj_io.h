// Meshes on disk as OBJ: vertices in helix order at full (round-trip) precision and the model's
// triangles, so that --mesh reads back exactly what --save-mesh wrote.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "sim/mesh.h"
#include "sim/surface.h"

namespace app {

// Text of an OBJ file: a comment line, one "v" line per vertex (shortest round-trip digits), then
// the surface's triangles as 1-based "f" lines.
std::string FormatObj(const sim::Positions& positions, const sim::Surface& surface, const std::string& comment);

// An OBJ file's vertices in order and its triangles (0-based; polygons are not triangles and are
// refused). Normals, texture coordinates, groups and comments are ignored; anything else is an error
// naming the file and line. Throws UsageError.
struct ObjMesh {
    sim::Positions positions;
    std::vector<std::array<int, 3>> triangles;
};
ObjMesh ReadObj(const std::string& path);

}  // namespace app
