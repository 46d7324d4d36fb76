// Closed triangle meshes as files for printers and CAD: binary or ASCII STL, Wavefront OBJ and binary
// PLY, bytes in memory (written whole by WriteFileAtomically), and binary STL read back (tests, and
// a check that what was written is what was built).
#pragma once

#include <string>

#include "sim/names.h"
#include "sim/solid.h"

namespace app {

enum class SolidFormat { Stl, Obj, Ply };

// `name` goes in the file's header or comment. STL is binary unless `ascii`; coordinates in mm.
std::string FormatSolid(const sim::TriangleMesh& mesh, SolidFormat format, bool ascii, const std::string& name);
const char* Extension(SolidFormat format);  // ".stl", ".obj", ".ply"

// A binary STL's triangles, vertices merged by exact coordinates. False (with `error`) on bytes that
// are not a binary STL.
bool ParseBinaryStl(const std::string& bytes, sim::TriangleMesh* mesh, std::string* error);

}  // namespace app

template <>
struct sim::EnumNames<app::SolidFormat> {
    static constexpr std::array<std::pair<app::SolidFormat, const char*>, 3> table{
        {{app::SolidFormat::Stl, "stl"}, {app::SolidFormat::Obj, "obj"}, {app::SolidFormat::Ply, "ply"}}};
};
