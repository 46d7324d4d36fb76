// Pictures shared by the commands: titles and result lines for a shape, the before/after scene,
// and PNG files written whole or not at all.
#pragma once

#include <string>

#include "render/image.h"
#include "render/mesh_renderer.h"
#include "sim/solver.h"

namespace app {

std::string ShapeTitle(const sim::Shape& shape);  // "sine  A = 4.1, phase 0.5 to 2.642"
std::string ResultLine(const sim::SimResult& result, const sim::MeshDef& mesh);  // status, fitness, contraction

// The mesh before (plain material) and after (coloured by the renderer's mode), one camera and scale.
render::Scene BeforeAfterScene(const std::string& title, const sim::SimResult& result, const sim::MeshDef& mesh);

// One turntable frame: the final mesh turned `angleDegrees` about its axis. The renderer's default
// framing (a cylinder about the axis) and colour scale do not change with the angle: frames hold still.
render::Scene TurntableScene(const std::string& title, const sim::SimResult& result, const sim::MeshDef& mesh, double angleDegrees);

void WritePng(const std::string& path, const render::Image& image, int compressionLevel);

std::string FormatNumber(const char* pattern, double value);

}  // namespace app
