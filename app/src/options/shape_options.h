// The shape options shared by simulate, render and export: one actuator design from the command
// line (a shape family with its parameters, a free-xy offset file or an OBJ mesh), on the thesis
// helix of --resolution x --turns.
#pragma once

#include <string>

#include "options/cli.h"
#include "sim/batch.h"
#include "sim/shape.h"
#include "sim/surface.h"

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

// The design the options describe on a model's mesh of `vertices` (free-xy offsets number 2 x
// vertices; an OBJ file must be of `surface`, cap centres allowed). Refuses options that do not apply
// to the chosen shape. Throws UsageError. (Check the job with sim::JobError after.)
sim::Shape BuildShape(const Cli& cli, const ShapeOptions& options, const sim::Surface& surface, int vertices);

// The job's shape and model from the options, checked as a whole: refuses the helix's --resolution
// and --turns under the shell models, and a design the model cannot evaluate. Throws UsageError.
struct ModelOptions;
enum class ModelUse;
sim::EvalJob BuildJob(const Cli& cli, const ShapeOptions& shape, const ModelOptions& model, ModelUse use);

// The shape options' names, to refuse them where a design comes from elsewhere (--from ARCHIVE).
const std::vector<std::string>& ShapeOptionNames();

// Control points as text: ',' between points, ';' between sector splines.
std::vector<std::vector<double>> ParseControlPoints(const std::string& text, const std::string& what);

}  // namespace app
