// Meshes on disk as OBJ: vertices in helix order at full (round-trip) precision and the model's
// triangles, so that --mesh reads back exactly what --save-mesh wrote.
#pragma once

#include <string>

#include "sim/mesh.h"
#include "sim/surface.h"

namespace app {

// Text of an OBJ file: a comment line, one "v" line per vertex (shortest round-trip digits), then
// the surface's triangles as 1-based "f" lines.
std::string FormatObj(const sim::Positions& positions, const sim::Surface& surface, const std::string& comment);

// Reads the "v" lines of an OBJ file in order. Ignores faces, normals, texture coordinates, groups
// and comments; anything else is an error naming the file and line. Throws UsageError.
sim::Positions ReadObjVertices(const std::string& path);

}  // namespace app
