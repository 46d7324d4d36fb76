// Meshes with fields as VTK's XML formats, which ParaView, VTK, meshio and PyVista read: an
// unstructured grid of triangles (.vtu) and a series of them over load steps (.pvd). Arrays are
// inline binary (base64, little-endian, UInt32 headers): exact doubles, NaN where a field has no
// value.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "sim/mesh.h"

namespace app {

struct FieldArray {
    std::string name;      // with its unit: "displacement_mm", "max_principal_stress_kpa"
    int components = 1;    // 1 (a scalar) or 3 (a vector)
    std::vector<double> values;  // components per tuple, tuple after tuple
    bool integer = false;  // written as Int32 (a region's code)
};

struct FieldMesh {
    sim::Positions points;
    std::vector<std::array<int, 3>> triangles;
    std::vector<FieldArray> pointData, cellData, fieldData;  // fieldData: one tuple each
    std::string comment;   // written as an XML comment after the header: what the file holds and its units
};

// The .vtu file's text.
std::string FormatVtu(const FieldMesh& mesh);

// A .pvd collection of .vtu files (relative to the .pvd's folder), each at its time value.
struct SeriesEntry {
    double time = 0;
    std::string file;
};
std::string FormatPvd(const std::vector<SeriesEntry>& entries);

}  // namespace app
