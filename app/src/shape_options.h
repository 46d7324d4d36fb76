// The shape options shared by simulate, render and export: one actuator design from the command
// line (a shape family with its parameters, a free-xy offset file or an OBJ mesh), on the thesis
// helix of --resolution x --turns.
#pragma once

#include <string>

#include "cli.h"
#include "sim/shape.h"

namespace app {

struct ShapeOptions {
    sim::ShapeKind kind = sim::ShapeKind::Cylinder;
    double amplitude = 0;         // sine, abs-sine: given or the family's default
    std::string phase;            // "START,END"
    sim::SplineRegion region = sim::BSplineShape{}.region;
    std::string controlPoints;    // "8,8,0,4" or "4,6,2,5;2,3,7,4,6"
    std::string offsets;          // free-xy: a file (or an inline list) of dx dy per vertex
    std::string meshFile;         // OBJ of the rest mesh in helix order
    sim::MeshDef mesh;
};

// Adds --shape, --amplitude, --phase, --region, --control-points, --offsets, --mesh, --resolution
// and --turns under "Shape options".
void AddShapeOptions(Cli& cli, ShapeOptions& options);

// The design the options describe. Refuses options that do not apply to the chosen shape, and a
// shape that cannot be built on the mesh. Throws UsageError.
sim::Shape BuildShape(const Cli& cli, const ShapeOptions& options);

// The shape options' names, to refuse them where a design comes from elsewhere (--from ARCHIVE).
const std::vector<std::string>& ShapeOptionNames();

// Control points as text: ',' between points, ';' between sector splines.
std::vector<std::vector<double>> ParseControlPoints(const std::string& text, const std::string& what);

}  // namespace app
