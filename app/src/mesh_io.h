// Meshes on disk: OBJ with vertices in helix order and the model's triangles, written at full
// (round-trip) precision, and plain offset files for free-xy shapes.
#pragma once

#include <string>

#include "sim/mesh.h"

namespace app {

// Text of an OBJ file: a comment naming the mesh size, one "v" line per vertex (shortest round-trip
// digits, so reading it back gives the same doubles), then the model's triangles as 1-based "f" lines.
std::string FormatObj(const sim::Positions& positions, const sim::MeshDef& def);

// Reads the "v" lines of an OBJ file in order. Ignores faces, normals, texture coordinates, groups
// and comments; anything else is an error naming the file and line. Throws UsageError.
sim::Positions ReadObjVertices(const std::string& path);

// The whole file. Throws UsageError naming the file when it cannot be read.
std::string ReadTextFile(const std::string& path);

// Whitespace-separated numbers (comments after '#'): a free-xy offset file holds "dx dy" per vertex.
std::vector<double> ReadNumberFile(const std::string& path);

// Writes the whole file or nothing: a temporary file beside the target, renamed over it when complete.
// Throws UsageError (with the path and the system's reason) on failure.
void WriteFileAtomically(const std::string& path, const std::string& contents);

// Refuses early, before any long work, an output path whose folder is missing or not writable.
void CheckOutputPath(const std::string& path, const std::string& what);

}  // namespace app
