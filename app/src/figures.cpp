#include "figures.h"

#include <cstdio>

#include "mesh_io.h"

namespace app {

std::string FormatNumber(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

std::string ShapeTitle(const sim::Shape& shape) {
    std::string title = sim::ShapeName(shape);
    auto sine = [&](double amplitude, double a, double b) {
        title += "  A = " + FormatNumber("%g", amplitude) + ", phase " + FormatNumber("%.4g", a) + " to " + FormatNumber("%.4g", b);
    };
    if (const auto* s = std::get_if<sim::SineShape>(&shape)) sine(s->amplitude, s->phaseStart, s->phaseEnd);
    else if (const auto* a = std::get_if<sim::AbsSineShape>(&shape)) sine(a->amplitude, a->phaseStart, a->phaseEnd);
    else if (const auto* b = std::get_if<sim::BSplineShape>(&shape)) {
        title += std::string(b->region == sim::SplineRegion::Entire ? " (entire)" : " (middle)") + "  ";
        for (size_t k = 0; k < b->splines.size(); ++k) {
            if (k) title += " | ";
            for (size_t j = 0; j < b->splines[k].size(); ++j) title += (j ? "," : "") + FormatNumber("%g", b->splines[k][j]);
        }
    }
    return title;
}

std::string ResultLine(const sim::SimResult& r, const sim::MeshDef& mesh) {
    std::string line = std::string("status ") + sim::StatusName(r.status) + ",  ";
    if (r.status == sim::Status::Ok)
        line += "fitness " + FormatNumber("%.4f", r.fitness) + ",  contraction " + FormatNumber("%.2f %%", r.contractionPercent) + ",  ";
    return line + std::to_string(r.iterationsRun) + " iterations,  " + std::to_string(mesh.resolution) + " x " +
           std::to_string(mesh.turns) + " mesh";
}

render::Scene BeforeAfterScene(const std::string& title, const sim::SimResult& r, const sim::MeshDef& mesh) {
    render::Scene scene;
    scene.mesh = mesh;
    scene.title = title;
    scene.lines = {ResultLine(r, mesh)};
    scene.panels = {{r.initial, {}, "before", 0}, {r.final, r.initial, "after " + std::to_string(r.iterationsRun) + " iterations", 0}};
    return scene;
}

render::Scene TurntableScene(const std::string& title, const sim::SimResult& r, const sim::MeshDef& mesh, double angleDegrees) {
    render::Scene scene;
    scene.mesh = mesh;
    scene.title = title;
    scene.lines = {ResultLine(r, mesh)};
    scene.panels = {{r.final, r.initial, "turned " + FormatNumber("%.0f", angleDegrees) + " degrees", angleDegrees}};
    return scene;
}

void WritePng(const std::string& path, const render::Image& image, int compressionLevel) {
    const auto bytes = render::EncodePng(image, compressionLevel);
    WriteFileAtomically(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace app
