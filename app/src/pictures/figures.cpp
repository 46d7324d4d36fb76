#include "pictures/figures.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <numbers>

#include "support/errors.h"
#include "formats/files.h"
#include "support/number_expression.h"
#include "pictures/plots.h"
#include "render/backend.h"
#include "sim/surface.h"

namespace app {
namespace {

namespace fs = std::filesystem;

}  // namespace

std::string ShapeTitle(const sim::Shape& shape) {
    std::string title = sim::ShapeName(shape);
    auto sine = [&](double amplitude, double a, double b) {
        // One phase at both ends is a constant radius: a cylinder (SF1's braided tube), not a sine.
        if (a == b) {
            const double factor = std::fabs(amplitude * std::sin(a));
            title = std::fabs(factor - 1) < 1e-12 ? "cylinder" : fmt::format("cylinder of {:.3g} x the base radius", factor);
            return;
        }
        title += fmt::format("  A = {:.3g}, phase {} to {}", amplitude, FormatRadians(a), FormatRadians(b));
    };
    if (const auto* s = std::get_if<sim::SineShape>(&shape)) sine(s->amplitude, s->phaseStart, s->phaseEnd);
    else if (const auto* a = std::get_if<sim::AbsSineShape>(&shape)) sine(a->amplitude, a->phaseStart, a->phaseEnd);
    else if (const auto* b = std::get_if<sim::BSplineShape>(&shape)) {
        title += std::string(" (") + sim::Name(b->region) + ")  ";
        for (size_t k = 0; k < b->splines.size(); ++k) {
            if (k) title += " | ";
            for (size_t j = 0; j < b->splines[k].size(); ++j) title += (j ? "," : "") + fmt::format("{:g}", b->splines[k][j]);
        }
    }
    return title;
}

std::string FibreTitle(const sim::FibreDef& f) {
    if (f.layout == sim::FibreLayout::None) return "";
    if (f.layout == sim::FibreLayout::Meridian || f.layout == sim::FibreLayout::Hoop) return std::string(sim::Name(f.layout)) + " fibres";
    const bool braid = f.layout == sim::FibreLayout::Braid && f.plus && f.minus;
    std::string title = braid ? "braid" : "one fibre family";
    if (sim::FamiliesOn(f) == 0) return "fibres switched off";  // a single family's minus switch carries nothing
    const char* sign = braid ? "+/-" : (f.layout == sim::FibreLayout::Braid && !f.plus) ? "-" : "+";
    std::vector<double> angles;
    for (const auto& band : f.bands) angles.push_back(band.angleDeg);
    for (double a : f.sectorAnglesDeg) angles.push_back(a);
    if (angles.empty()) angles.push_back(f.angleDeg);
    title += angles.size() > 1 ? (f.bands.empty() ? " by sector " : " by band ") : std::string(" ");
    for (size_t k = 0; k < angles.size(); ++k) title += fmt::format("{}{}{:.0f}", k ? ", " : "", sign, angles[k]);
    return title + " deg";
}

std::string FibreTitle(const sim::EvalJob& job) {
    const sim::ShellDef* shell = std::get_if<sim::ShellDef>(&job.def);
    return shell ? FibreTitle(shell->fibres) : "";
}

std::string JobTitle(const sim::EvalJob& job) {
    if (job.model == sim::ModelKind::Thesis) return ShapeTitle(job.shape);
    const std::string fibres = FibreTitle(job);
    return fmt::format("{}  -  {} model{}", ShapeTitle(job.shape), sim::Name(job.model), fibres.empty() ? "" : ",  " + fibres);
}

// A turn of the top smaller than this is not drawn (a braid's numerical rest).
constexpr double kShownTwistDeg = 0.5;
constexpr const char* kStripeLegend = "red stripe: straight along the tube at rest";

std::string ResultLine(const sim::SimResult& r, const sim::EvalJob& job) {
    std::string line = std::string("status ") + sim::Name(r.status) + ",  ";
    if (job.model == sim::ModelKind::Thesis) {
        if (r.status == sim::Status::Ok) line += fmt::format("fitness {:.4f},  contraction {:.2f} %,  ", r.fitness, r.contractionPercent);
        return line + fmt::format("{} iterations,  {} x {} mesh", r.iterationsRun, job.Thesis().mesh.resolution, job.Thesis().mesh.turns);
    }
    const sim::ShellOutputs& o = r.shell;
    if (std::isfinite(r.contractionPercent)) line += fmt::format("contraction {:.2f} % at {:.3g} kPa,  ", r.contractionPercent, o.targetPressureKpa);
    if (std::isfinite(o.limitPressureKpa)) line += fmt::format("limit point {:.3g} kPa,  ", o.limitPressureKpa);
    if (std::isfinite(o.maxStretch)) line += fmt::format("stretch {:.2f} (limit {:.2f}),  ", o.maxStretch, o.stretchLimit);
    return line + fmt::format("{} Newton iterations,  {} x {} mesh,  {}", o.newtonIterations, job.Shell().geometry.ringVertices,
                              sim::RingCount(job.Shell().geometry), sim::Name(job.Shell().material.preset));
}

std::string FitnessCaption(const sim::SimResult& r) { return r.status == sim::Status::Ok ? fmt::format("{:.3f}", r.fitness) : sim::Name(r.status); }

std::string ColouringError(Colouring colouring, const sim::EvalJob& job) {
    if (job.model == sim::ModelKind::Thesis && (colouring == Colouring::Stretch || colouring == Colouring::Stress))
        return std::string("colouring by ") + sim::Name(colouring) + " needs --model membrane or shell (the thesis model has no material)";
    if (colouring == Colouring::Gap && (job.model == sim::ModelKind::Thesis || job.Shell().contact.mode != sim::ContactMode::On))
        return "colouring by gap needs --contact on (a membrane or shell model's walls that touch)";
    return "";
}

std::shared_ptr<const sim::Surface> SharedSurface(const sim::EvalJob& job) {
    // Surfaces are shared: a sweep draws thousands of meshes of one size.
    static std::mutex mutex;
    // A surface is its model's drawing of its design mesh: models that draw alike share one.
    using SurfaceFunction = sim::Surface (*)(const sim::EvalJob&);
    static std::map<std::tuple<SurfaceFunction, int, int>, std::shared_ptr<const sim::Surface>> cache;
    const sim::MeshDef mesh = sim::DesignMeshOf(job);
    const std::tuple<SurfaceFunction, int, int> key{sim::ModelOf(job).surface, mesh.resolution, mesh.turns};
    std::lock_guard lock(mutex);
    auto& surface = cache[key];
    if (!surface) surface = std::make_shared<const sim::Surface>(sim::SurfaceOf(job));
    return surface;
}

namespace {

// The fibres as dashes over the wall: valued by their stretch (on a stretch scale), or at the bottom
// of the scale (dark lines) when the surface shows something else.
void AddFibres(render::Panel& panel, const sim::ShellFields& fields, bool byStretch) {
    for (const sim::FibreDash& dash : fields.fibres) {
        render::Segment segment;
        for (int c = 0; c < 3; ++c) {
            segment.a[c] = static_cast<float>(dash.centre[c] - dash.halfLengthMm * dash.along[c]);
            segment.b[c] = static_cast<float>(dash.centre[c] + dash.halfLengthMm * dash.along[c]);
        }
        segment.value = byStretch ? static_cast<float>(dash.stretch) : -INFINITY;
        panel.segments.push_back(segment);
    }
}

// Where the top turned (|twist| of half a degree or more), the turn drawn as a bench shows it with a
// painted stripe: a red line straight along the tube at rest (each ring's vertex nearest one angle),
// wound into a helix by the twist, and a radius of the top cap from its centre.
bool ShowsTwist(const sim::SimResult& r, const sim::EvalJob& job) {
    return job.model != sim::ModelKind::Thesis && std::isfinite(r.shell.twistDeg) && std::fabs(r.shell.twistDeg) >= kShownTwistDeg;
}
void AddTwistStripe(render::Scene& scene, render::Panel& panel, const sim::Positions& x, const sim::SimResult& r, const sim::EvalJob& job) {
    const sim::MeshDef rings = sim::ModelOf(job).designMesh(job);  // ring vertices x rings, then the two cap centres
    const int R = rings.resolution, H = rings.turns;
    if (R <= 0 || H < 3 || x.Size() != R * H + 2 || r.initial.Size() != x.Size()) return;
    // The stripe's vertex in each ring: the one nearest (at rest) to the angle where the middle of the
    // wound stripe faces the default camera.
    const double az = render::DefaultRenderDef().azimuthDegrees * std::numbers::pi / 180;
    const double start = std::atan2(-std::cos(az), std::sin(az)) - 0.5 * r.shell.twistDeg * std::numbers::pi / 180;
    const sim::Positions& rest = r.initial;
    std::vector<int> stripe(static_cast<size_t>(H));
    for (int ring = 0; ring < H; ++ring) {
        double gap = INFINITY;
        for (int v = ring * R; v < (ring + 1) * R; ++v) {
            const double d = std::fabs(std::remainder(std::atan2(rest.y[v], rest.x[v]) - start, 2 * std::numbers::pi));
            if (d < gap) gap = d, stripe[ring] = v;
        }
    }
    auto point = [&](int v, float out[3]) {
        out[0] = static_cast<float>(x.x[v]);
        out[1] = static_cast<float>(x.y[v]);
        out[2] = static_cast<float>(x.z[v]);
    };
    for (int ring = 0; ring + 1 < H; ++ring) {
        render::Segment segment;
        point(stripe[ring], segment.a);
        point(stripe[ring + 1], segment.b);
        segment.mark = true;
        panel.segments.push_back(segment);
    }
    render::Segment radius;  // the top cap's centre to the stripe's vertex of its ring
    point(R * H + 1, radius.a);
    point(stripe[H - 1], radius.b);
    radius.mark = true;
    panel.segments.push_back(radius);
    // Its legend once a scene (a one-design scene has already named the turn).
    const bool named = std::any_of(scene.lines.begin(), scene.lines.end(), [](const std::string& l) { return l.rfind(kStripeLegend, 0) == 0; });
    if (!named) scene.lines.push_back(kStripeLegend + std::string(", wound by the top clamp's turn"));
}

// A panel of a deformed mesh coloured as asked; sets the scene's mode, label and marks.
render::Panel ColouredPanel(render::Scene& scene, const sim::Positions& deformed, const sim::SimResult& r, const sim::EvalJob& job,
                            Colouring colouring, std::string caption, double rotationDegrees = 0) {
    render::Panel panel{deformed, r.initial, std::move(caption), rotationDegrees, {}, {}};
    const bool thesis = job.model == sim::ModelKind::Thesis;
    if (colouring == Colouring::Auto) colouring = thesis ? Colouring::Displacement : Colouring::Stretch;
    switch (colouring) {
        case Colouring::Auto:
        case Colouring::Displacement:
            scene.colorBy = render::ColorBy::Displacement;
            if (!thesis) scene.colorLabel = "displacement\n(mm)";
            break;
        case Colouring::Strain: scene.colorBy = render::ColorBy::Strain; break;
        case Colouring::None: scene.colorBy = render::ColorBy::Shading; break;
        case Colouring::Gap: {
            if (thesis) break;  // refused earlier (ColouringError)
            // Vertices with no other wall within a wall thickness show at the top of the scale.
            const double h = job.Shell().geometry.thicknessMm;
            panel.values = sim::ContactGapValues(job.Shell(), job.shape, deformed);
            for (double& g : panel.values) g = std::isfinite(g) ? std::min(g, h) : h;
            scene.colorBy = render::ColorBy::Values;
            scene.colorLabel = "gap to the\nnext wall (mm)";
            scene.colorMin = 0.0;
            scene.colorMax = h;
            scene.scaleMarks = {{h * job.Shell().contact.gapFraction, "reach"}};  // the barrier's: walls nearer push apart
            break;
        }
        case Colouring::Stretch:
        case Colouring::Stress: {
            if (thesis) break;  // refused earlier (ColouringError)
            const sim::ShellFields fields = sim::ShellFieldValues(job.Shell(), job.shape, job.model == sim::ModelKind::Shell, deformed);
            AddFibres(panel, fields, colouring == Colouring::Stretch);
            // Said as drawn: under stress colouring the fibres are plain lines, not coloured by anything.
            const std::string fibreLine = colouring == Colouring::Stretch ? "lines: the fibres, coloured by their stretch on the same scale"
                                                                          : "dark lines: the fibres (their stress is not on this scale)";
            if (!fields.fibres.empty() && std::find(scene.lines.begin(), scene.lines.end(), fibreLine) == scene.lines.end())
                scene.lines.push_back(fibreLine);  // once for a scene of many panels
            const bool stretch = colouring == Colouring::Stretch;
            panel.values = stretch ? fields.stretch : fields.stressKpa;
            scene.colorBy = render::ColorBy::Values;
            scene.colorLabel = stretch ? "principal\nstretch" : "principal true\nstress (kPa)";
            const double limit = stretch ? sim::StretchLimit(job.Shell().material) : job.Shell().material.tensileStrengthKpa;
            if (limit > 0) scene.scaleMarks = {{limit, stretch ? "stretch limit" : "tensile strength"}};
            if (stretch) scene.colorMin = 1.0;
            // The colours are vertex means of the triangles' values; the scale reaches the largest
            // triangle's, the value the subtitle states (S5.4F's best: 1.12, where the bar stopped at 1.099).
            // A tube that cannot be built measures nothing (NaN): the scale is then the values'.
            const double largest = stretch ? r.shell.maxStretch : r.shell.maxStressKpa;
            if (std::isfinite(largest) && largest > 0) scene.colorMax = std::max(scene.colorMax.value_or(largest), largest);
            break;
        }
    }
    const bool fibres = !thesis && job.Shell().fibres.layout != sim::FibreLayout::None;
    if (fibres && colouring != Colouring::Stretch && colouring != Colouring::Stress)
        AddFibres(panel, sim::ShellFieldValues(job.Shell(), job.shape, job.model == sim::ModelKind::Shell, deformed), false);
    if (ShowsTwist(r, job)) AddTwistStripe(scene, panel, deformed, r, job);
    return panel;
}

std::string AfterCaption(const sim::SimResult& r, const sim::EvalJob& job) {
    if (job.model == sim::ModelKind::Thesis) return "after " + std::to_string(r.iterationsRun) + " iterations";
    return fmt::format("at {:.3g} kPa", r.shell.targetPressureKpa);
}

}  // namespace

std::vector<std::string> ResultLines(const sim::SimResult& r, const sim::EvalJob& job) {
    std::vector<std::string> lines{ResultLine(r, job)};
    // "status ok" under a mesh that flew apart would vouch for a number that is no contraction.
    if (const std::string escape = EscapeWarning(r); !escape.empty())
        lines.push_back("! the mesh exploded (" + escape + "): its fitness is not a contraction");
    return lines;
}

render::Scene BeforeAfterScene(const std::string& title, const sim::SimResult& r, const sim::EvalJob& job, Colouring colouring) {
    render::Scene scene;
    scene.surface = SharedSurface(job);
    scene.title = title;
    scene.lines = ResultLines(r, job);
    scene.panels = {{r.initial, {}, "before", 0, {}, {}}};
    if (job.model != sim::ModelKind::Thesis && job.Shell().fibres.layout != sim::FibreLayout::None)
        AddFibres(scene.panels.front(), sim::ShellFieldValues(job.Shell(), job.shape, job.model == sim::ModelKind::Shell, r.initial), false);
    if (ShowsTwist(r, job)) {
        scene.lines.push_back(fmt::format("{}; the top clamp turned {:+.1f} deg", kStripeLegend, r.shell.twistDeg));
        AddTwistStripe(scene, scene.panels.front(), r.initial, r, job);
    }
    scene.panels.push_back(ColouredPanel(scene, r.final, r, job, colouring, AfterCaption(r, job)));
    return scene;
}

render::Scene PairsScene(const std::string& title, const std::vector<std::string>& lines, const std::vector<DesignPair>& pairs, int pairsPerRow) {
    render::Scene scene;
    scene.surface = SharedSurface(*pairs.front().job);
    scene.title = title;
    scene.lines = lines;
    scene.columns = 2 * std::max(1, pairsPerRow);
    std::vector<const sim::Positions*> framed;
    std::vector<std::string> escaped;
    for (const DesignPair& pair : pairs) {
        const sim::SimResult& r = *pair.result;
        // A mesh that moved farther than its own size has exploded (the thesis model's low-resolution
        // meshes do): its number is no contraction, and the picture says so.
        const std::string escape = EscapeWarning(r);
        if (!escape.empty()) escaped.push_back(pair.label + " " + escape);
        scene.panels.push_back({r.initial, {}, pair.label + ": before", 0, {}, {}});
        scene.panels.push_back(ColouredPanel(scene, r.final, r, *pair.job, Colouring::Auto, (escape.empty() ? "after: " : "! after: ") + FitnessCaption(r)));
        framed.push_back(&r.initial);
        if (r.status == sim::Status::Ok) framed.push_back(&r.final);
    }
    scene.framing = render::FrameMeshes(framed);
    for (const std::string& e : escaped) scene.lines.push_back("! " + e + ": the mesh exploded; its number is not a contraction");
    // One colour scale serves every design: when one design's values span only a small part of it
    // (4.3's design 1 moves 2 units on a scale that design 3's 34 sets), the reader is told.
    std::vector<double> highs;
    double low = INFINITY, high = -INFINITY;
    for (size_t k = 1; k < scene.panels.size(); k += 2) {
        const std::vector<double> values = render::VertexValues(scene.colorBy.value_or(render::ColorBy::Displacement), *scene.surface, scene.panels[k]);
        double panelHigh = -INFINITY;
        for (double v : values)
            if (std::isfinite(v)) low = std::min(low, v), panelHigh = std::max(panelHigh, v);
        highs.push_back(panelHigh);
        high = std::max(high, panelHigh);
    }
    if (scene.colorMin) low = *scene.colorMin;
    if (scene.colorMax) high = *scene.colorMax;
    std::string small;
    for (size_t k = 0; k < highs.size(); ++k)
        if (std::isfinite(highs[k]) && high > low && (highs[k] - low) < 0.25 * (high - low))
            small += fmt::format("{}{} reaches {:.3g}", small.empty() ? "" : ", ", pairs[k].label, highs[k]);
    if (!small.empty()) scene.lines.push_back(fmt::format("one colour scale for all designs, up to {:.3g}: {}", high, small));
    return scene;
}

render::Scene StagesScene(const std::string& title, const std::vector<std::string>& lines, const std::vector<const sim::SimResult*>& stages,
                          const sim::EvalJob& job) {
    render::Scene scene;
    scene.surface = SharedSurface(job);
    scene.title = title;
    scene.lines = lines;
    if (stages.empty()) return scene;
    scene.panels.push_back({stages.front()->initial, {}, "before", 0, {}, {}});
    std::vector<const sim::Positions*> framed{&stages.front()->initial};
    for (const sim::SimResult* r : stages) {
        scene.panels.push_back(ColouredPanel(scene, r->final, *r, job, Colouring::Auto, AfterCaption(*r, job) + ": " + FitnessCaption(*r)));
        if (r->status == sim::Status::Ok) framed.push_back(&r->final);
    }
    scene.framing = render::FrameMeshes(framed);
    return scene;
}

void ShareFramingAndScale(std::vector<render::Scene>& scenes) {
    std::vector<const sim::Positions*> all;
    double low = INFINITY, high = -INFINITY;
    for (const auto& scene : scenes)
        for (const auto& panel : scene.panels) {
            all.push_back(&panel.positions);
            const render::ColorBy colorBy = scene.colorBy.value_or(render::ColorBy::Displacement);
            for (double v : render::VertexValues(colorBy, *scene.surface, panel))
                if (std::isfinite(v)) {
                    low = std::min(low, v);
                    high = std::max(high, v);
                }
        }
    // A scene's own top (the result's largest stretch or stress, which its subtitle states) is kept:
    // the vertex values are means of triangles' and fall short of it.
    for (const auto& scene : scenes)
        if (scene.colorMax) high = std::max(high, *scene.colorMax);
    const render::Framing framing = render::FrameMeshes(all);
    for (auto& scene : scenes) {
        scene.framing = framing;
        if (std::isfinite(high)) {
            scene.colorMax = high;
            if (!scene.colorMin) scene.colorMin = scene.colorBy == render::ColorBy::Values ? low : 0.0;
        }
    }
}

render::Image PairsImage(const render::Scene& scene) {
    const int columns = scene.columns > 0 ? scene.columns : std::max<int>(1, scene.panels.size());  // no grid: one row
    const int rows = static_cast<int>((scene.panels.size() + columns - 1) / columns);
    const int width = std::clamp(columns * 240 + 140, 900, 3000), height = std::clamp(rows * 420 + 120 + 24 * static_cast<int>(scene.lines.size()), 500, 3000);
    return MakeRenderer(width, height, 2, 0.9)->Render(scene);
}

namespace {

// Solids placed side by side as one panel over one surface, each vertex valued by its part's number.
struct PlacedSolid {
    const sim::TriangleMesh* mesh;
    double shiftX;
    bool turned;  // half a turn about the axis
};
render::Panel SolidsPanel(const std::vector<PlacedSolid>& solids, std::shared_ptr<sim::Surface>& surface) {
    surface = std::make_shared<sim::Surface>();
    render::Panel panel;
    for (size_t k = 0; k < solids.size(); ++k) {
        const auto& [mesh, shiftX, turned] = solids[k];
        const int base = surface->vertexCount;
        for (const auto& v : mesh->vertices) {
            panel.positions.x.push_back((turned ? -v[0] : v[0]) + shiftX);
            panel.positions.y.push_back(turned ? -v[1] : v[1]);
            panel.positions.z.push_back(v[2]);
            panel.values.push_back(static_cast<double>(k));
        }
        for (const auto& t : mesh->triangles) surface->triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
        surface->vertexCount += static_cast<int>(mesh->vertices.size());
    }
    return panel;
}

}  // namespace

render::Scene ExplodedMoldScene(const sim::PartSolids& solids, const std::string& title, const sim::PartSolids* firstStage) {
    const double w = sim::MeshBounds(solids.shellA)[3], step = 2.7 * w;
    std::shared_ptr<sim::Surface> surface;
    render::Scene scene;
    std::vector<PlacedSolid> placed{{&solids.actuator, 0, false}, {&solids.core, -step, false}, {&solids.shellA, step, false}, {&solids.shellB, 2 * step, true}};
    const bool fittings = !solids.fittingBottom.triangles.empty();
    if (fittings) placed.insert(placed.end(), {{&solids.fittingBottom, -2 * step, false}, {&solids.fittingTop, -2 * step, false}});
    if (firstStage)  // beyond shell B: the first stage's shells and its layer
        placed.insert(placed.end(), {{&firstStage->shellA, 3 * step, false}, {&firstStage->shellB, 4 * step, true}, {&firstStage->actuator, 5 * step, false}});
    scene.panels = {SolidsPanel(placed, surface)};
    scene.surface = surface;
    scene.title = title;
    auto size = [](const sim::TriangleMesh& mesh) {
        const auto b = sim::MeshBounds(mesh);
        return fmt::format("{:.0f} x {:.0f} x {:.0f} mm", b[3] - b[0], b[4] - b[1], b[5] - b[2]);
    };
    // Okabe and Ito's colour-blind-safe palette: the silicone orange, the core blue, the shells green
    // and yellow, the fittings purple.
    scene.categories = {{"actuator (silicone)\n" + size(solids.actuator), {0.90f, 0.62f, 0.0f}},
                        {"core\n" + size(solids.core), {0.0f, 0.45f, 0.70f}},
                        {"shell A (sprue, pins)\n" + size(solids.shellA), {0.0f, 0.62f, 0.45f}},
                        {"shell B (holes)\n" + size(solids.shellB), {0.94f, 0.89f, 0.26f}}};
    if (fittings)
        scene.categories.insert(scene.categories.end(), {{"fitting, bottom (port)\n" + size(solids.fittingBottom), {0.80f, 0.47f, 0.65f}},
                                                         {"fitting, top\n" + size(solids.fittingTop), {0.80f, 0.47f, 0.65f}}});
    if (firstStage) {
        // The categories follow the placed solids' order (the fittings, when there are, come first).
        scene.categories.insert(scene.categories.end(), {{"stage 1 shell A\n" + size(firstStage->shellA), {0.34f, 0.71f, 0.91f}},
                                                         {"stage 1 shell B\n" + size(firstStage->shellB), {0.84f, 0.37f, 0.0f}},
                                                         {"stage 1 layer (silicone)\n" + size(firstStage->actuator), {0.95f, 0.80f, 0.45f}}});
    }
    scene.colorBy = render::ColorBy::Values;
    scene.colorLabel = "parts (x, y, z)";
    const auto block = sim::MeshBounds(solids.shellA);
    scene.lines = {std::string(fittings ? "fittings, core, actuator, shell A, shell B" : "core, actuator, shell A, shell B") +
                       (firstStage ? ", then the first stage's shells and layer" : "") + " (split faces to you); x, y, z sizes",
                   fmt::format("pour: upright, from below into shell A's sprue (red arrow, {:.1f} mm)", solids.sprueGapMm),
                   "vents: four, in the top end wall"};
    if (solids.markDepthMm > 0) scene.lines.push_back("up: where the arrow engraved on shell A's back points");
    // The pour's direction: up into the sprue's mouth on shell A's bottom face.
    const float x = float(step + solids.sprueMouthMm[0]), y = float(solids.sprueMouthMm[1]), z = float(block[2]);
    const float length = float(0.18 * (block[5] - block[2])), head = std::min(float(0.3 * w), 0.3f * length);
    auto mark = [&](float ax, float az, float bx, float bz) {
        render::Segment s{{ax, y, az}, {bx, y, bz}};
        s.mark = true;
        scene.panels[0].segments.push_back(s);
    };
    mark(x, z - length, x, z - 1);
    mark(x, z - 1, x - head, z - 1 - 1.6f * head);
    mark(x, z - 1, x + head, z - 1 - 1.6f * head);
    return scene;
}

render::Scene WindingGuidesScene(const sim::PartSolids& layer, const std::vector<sim::FibreWinding>& winding, const std::string& title) {
    std::shared_ptr<sim::Surface> surface;
    render::Scene scene;
    scene.panels = {SolidsPanel({{&layer.actuator, 0, false}}, surface)};
    scene.surface = surface;
    scene.title = title;
    std::string families;
    for (size_t f = 0; f < winding.size(); ++f) {
        const sim::FibreWinding& w = winding[f];
        families += fmt::format("{}{} {}: {} threads, {:.2f} turns, {:.0f} mm each", f ? ";  " : "", w.family, w.hand, w.threads.size(), w.turns, w.pathMm);
        for (const sim::ThreadPath& thread : w.threads)
            for (size_t k = 0; k + 1 < thread.pointsMm.size(); ++k) {
                const auto& a = thread.pointsMm[k];
                const auto& b = thread.pointsMm[k + 1];
                render::Segment s{{float(a[0]), float(a[1]), float(a[2])}, {float(b[0]), float(b[1]), float(b[2])}};
                s.value = float(f);
                scene.panels[0].segments.push_back(s);
            }
    }
    scene.lines = {"the first stage's layer on the core, its guide grooves along the threads", families};
    // The layer in the silicone's colour, the threads in the families' (first purple, second yellow).
    for (auto& v : scene.panels[0].values) v = 0;
    scene.colorBy = render::ColorBy::Values;
    scene.categories = {{"layer (silicone)", {0.90f, 0.62f, 0.0f}}};
    for (size_t f = 0; f < winding.size(); ++f) {
        const render::Rgb c = render::ViridisColor(winding.size() > 1 ? double(f) / (winding.size() - 1) : 0.0);
        scene.categories.push_back({winding[f].family + " thread", {0.85f * c.r, 0.85f * c.g, 0.85f * c.b}});  // the segments' shade
    }
    scene.colorMin = 0;
    scene.colorMax = std::max<double>(1, winding.size() - 1);
    return scene;
}

render::Scene CutawayScene(const sim::PartSolids& solids, const std::string& title) {
    std::shared_ptr<sim::Surface> surface;
    render::Scene scene;
    // The half at y >= 0: its cut faces the camera, which looks from the y < 0 side.
    scene.panels = {SolidsPanel({{&solids.actuatorCut, 0, false}}, surface)};
    scene.surface = surface;
    scene.title = title;
    const auto bounds = sim::MeshBounds(solids.actuator);
    scene.lines = {fmt::format("cut along the axis: {:.3g} mm long, {:.3g} mm across, {:.4g} mm^3", bounds[5] - bounds[2],
                               bounds[3] - bounds[0], sim::MeshVolume(solids.actuator))};
    scene.colorBy = render::ColorBy::Shading;
    return scene;
}

render::Scene TurntableScene(const std::string& title, const sim::SimResult& r, const sim::EvalJob& job, double angleDegrees, Colouring colouring) {
    render::Scene scene;
    scene.surface = SharedSurface(job);
    scene.title = title;
    scene.lines = ResultLines(r, job);
    scene.panels = {ColouredPanel(scene, r.final, r, job, colouring, fmt::format("turned {:.0f} degrees", angleDegrees), angleDegrees)};
    return scene;
}

render::Scene LoadStepScene(const std::string& title, const sim::SimResult& r, const sim::EvalJob& job, int step, Colouring colouring) {
    const sim::ShellOutputs& o = r.shell;
    render::Scene scene;
    scene.surface = SharedSurface(job);
    scene.title = title;
    const double pressure = step < static_cast<int>(o.curvePressureKpa.size()) ? o.curvePressureKpa[step] : NAN;
    const double contraction = step < static_cast<int>(o.curveContractionPercent.size()) ? o.curveContractionPercent[step] : NAN;
    scene.lines = {fmt::format("load step {} of {}:  {:.3g} kPa,  contraction {:.2f} %", step + 1, o.steps.size(), pressure, contraction)};
    scene.panels = {ColouredPanel(scene, o.steps.at(step), r, job, colouring, fmt::format("{:.3g} kPa", pressure))};
    return scene;
}

std::unique_ptr<render::MeshRenderer> MakeRenderer(const render::RenderDef& def) {
    std::string error;
    auto renderer = render::MeshRenderer::Create(def, &error);
    if (!renderer) throw UsageError("cannot render: " + error);
    return renderer;
}

std::unique_ptr<render::MeshRenderer> MakeRenderer(int width, int height, int supersample, double textScale) {
    render::RenderDef def = render::DefaultRenderDef();
    def.width = width;
    def.height = height;
    def.supersample = supersample;
    def.textScale = textScale;
    return MakeRenderer(def);
}

void WritePng(const std::string& path, const render::Image& image, int compressionLevel) {
    const auto bytes = render::EncodePng(image, compressionLevel);
    WriteFileAtomically(path, std::string(bytes.begin(), bytes.end()));
}

FrameWriter::~FrameWriter() {
    if (pending_.valid()) pending_.wait();
}

void FrameWriter::Write(std::string path, render::Image image) {
    Wait();
    pending_ = std::async(std::launch::async, [path = std::move(path), image = std::move(image), level = pngLevel_] { WritePng(path, image, level); });
}

void FrameWriter::Wait() {
    if (pending_.valid()) pending_.get();
}

std::vector<std::string> WriteDesignFigures(render::MeshRenderer& renderer, const fs::path& folder, const DesignFigures& f, int figureLevel,
                                            int frameLevel) {
    std::vector<std::string> written;
    const std::pair<const char*, const sim::SimResult*> loads[] = {{"inflation", f.inflated}, {"stretch", f.stretched}};
    // Under vacuum the pictures say "vacuum" where others say "inflation" (the files keep the name
    // inflation.png, which reports and experiment files use).
    const bool vacuum = sim::UnderVacuum(f.job.def);
    // One design's figures share a camera: its "before" mesh is the same size in each.
    std::vector<const sim::Positions*> framed;
    for (const auto& [load, result] : loads)
        if (result) {
            framed.push_back(&result->initial);
            framed.push_back(&result->final);
        }
    for (const auto& [load, result] : loads) {
        if (!result) continue;
        const std::string name = f.prefix + load + ".png";
        const std::string title = f.title + "  -  " + (vacuum && result == f.inflated ? "vacuum" : load);
        render::Scene scene = BeforeAfterScene(title, *result, f.job, f.colouring);
        if (f.inflated && f.stretched) scene.framing = render::FrameMeshes(framed);
        WritePng((folder / name).string(), renderer.Render(scene), figureLevel);
        written.push_back(name);
    }
    if (f.job.model != sim::ModelKind::Thesis && f.inflated && !f.inflated->shell.curvePressureKpa.empty()) {
        const std::string name = f.prefix + "pressure_curve.png";
        WritePng((folder / name).string(), PressureCurveImage(f.title, *f.inflated, f.job.Shell().load.kind == sim::ShellLoad::Blocked), figureLevel);
        written.push_back(name);
    }
    if (f.turntableFrames > 0 && f.inflated) {
        const std::string sub = f.prefix + "turntable";
        std::error_code ec;
        fs::create_directories(folder / sub, ec);
        if (!fs::is_directory(folder / sub, ec)) throw UsageError("cannot create folder " + Quote((folder / sub).string()));
        FrameWriter writer(frameLevel);
        for (int k = 0; k < f.turntableFrames; ++k)
            writer.Write((folder / sub / fmt::format("frame_{:04}.png", k)).string(),
                         renderer.Render(TurntableScene(f.title + (vacuum ? "  -  under vacuum" : "  -  inflated"), *f.inflated, f.job, 360.0 * k / f.turntableFrames, f.colouring)));
        writer.Wait();
        written.push_back(sub + "/frame_%04d.png x " + std::to_string(f.turntableFrames));
    }
    return written;
}

std::string EscapeWarning(const sim::SimResult& r) {
    const sim::Positions& a = r.initial;
    const sim::Positions& b = r.final;
    if (a.Size() == 0 || b.Size() != a.Size()) return "";
    double zMin = INFINITY, zMax = -INFINITY, radius = 0, moved = 0;
    for (int i = 0; i < a.Size(); ++i) {
        zMin = std::min(zMin, a.z[i]);
        zMax = std::max(zMax, a.z[i]);
        radius = std::max(radius, std::hypot(a.x[i], a.y[i]));
        const double d = std::sqrt((b.x[i] - a.x[i]) * (b.x[i] - a.x[i]) + (b.y[i] - a.y[i]) * (b.y[i] - a.y[i]) + (b.z[i] - a.z[i]) * (b.z[i] - a.z[i]));
        if (std::isfinite(d)) moved = std::max(moved, d);
    }
    const double size = std::max(zMax - zMin, 2 * radius);
    if (!(moved > size)) return "";
    return fmt::format("moved {:.3g} on a {:.3g}-unit mesh", moved, size);
}

void WriteContactSheet(const fs::path& path, const std::string& title, const std::vector<SheetEntry>& entries, const sim::EvalJob& job,
                       std::unique_ptr<render::MeshRenderer>& renderer, const SheetAxes& axes) {
    if (entries.empty()) return;
    // Actuators are about ten times taller than wide: many narrow columns, cells about 1:2.
    const int columns = axes.columns > 0 ? axes.columns : std::max(1, static_cast<int>(std::ceil(std::sqrt(entries.size() * 3.0))));
    const int rows = static_cast<int>((entries.size() + columns - 1) / columns);
    const bool labelled = !axes.columnLabels.empty() || !axes.rowLabels.empty();
    render::Scene scene;
    scene.surface = SharedSurface(job);
    scene.title = title;
    scene.columns = columns;
    scene.columnLabels = axes.columnLabels;
    scene.rowLabels = axes.rowLabels;
    scene.columnTitle = axes.columnTitle;
    scene.rowTitle = axes.rowTitle;
    scene.colorBy = render::ColorBy::Displacement;
    if (job.model != sim::ModelKind::Thesis) scene.colorLabel = "displacement\n(mm)";
    std::vector<const sim::Positions*> kept;
    std::vector<std::vector<double>> keptValues;
    int escaped = 0;
    for (const auto& entry : entries) {
        const bool escapes = !EscapeWarning(*entry.result).empty();
        escaped += escapes;
        scene.panels.push_back({entry.result->final, entry.result->initial, (escapes ? "! " : "") + entry.caption, 0, {}, {}});
        if (entry.result->status != sim::Status::Ok || escapes) continue;
        kept.push_back(&entry.result->final);
        kept.push_back(&entry.result->initial);
        keptValues.push_back(render::VertexValues(render::ColorBy::Displacement, *scene.surface, scene.panels.back()));
    }
    // Cells shaped like what they hold (the framing cylinder seen from the side), so that meshes fill
    // them and sit just above their captions.
    double cellAspect = 0.5;  // height : width of the drawing area, before the caption
    if (!kept.empty()) {
        scene.framing = render::FrameMeshes(kept);
        scene.colorMax = render::RobustColorMax(keptValues);
        cellAspect = std::clamp((scene.framing->zMax - scene.framing->zMin) / (2.2 * scene.framing->radius), 0.6, 2.4);
    }
    const int cellWidth = 130, cellHeight = static_cast<int>(cellWidth * cellAspect) + 40;
    const int width = std::clamp(columns * cellWidth + 150 + (labelled ? 110 : 0), 800, 2800);
    const int height = std::clamp(rows * cellHeight + 130 + (labelled ? 50 : 0) + (escaped ? 20 : 0), 450, 2600);
    // Body text 0.8 x 19 px = 15 px: captions readable at 100 %; rendered at twice the size and
    // filtered down like the main figures.
    if (!renderer || !renderer->Resize(width, height)) renderer = MakeRenderer(width, height, 2, 0.8);
    if (escaped)
        scene.lines.push_back(fmt::format("! {} of {} meshes moved farther than their own size: not a physical state; camera and colour scale "
                                          "(98th percentile) are the other meshes'",
                                          escaped, entries.size()));
    WritePng(path.string(), renderer->Render(scene), 1);
}

Thumbnails::Thumbnails(fs::path folder) : folder_(std::move(folder)) {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (!fs::is_directory(folder_, ec)) throw UsageError("cannot create folder " + Quote(folder_.string()));
    render::RenderDef def = render::DefaultRenderDef();
    def.width = 300;
    def.height = 200;
    def.supersample = 1;
    def.textScale = 0.6;  // 11 px: a label, not a caption
    renderer_ = MakeRenderer(def);
}

std::string Thumbnails::Name(std::uint64_t id) { return fmt::format("evaluation_{:06}.png", id); }

void Thumbnails::Append(const ArchiveRecord& record) {
    render::Scene scene;
    scene.surface = SharedSurface(record.job);
    scene.title = fmt::format("#{}  {}", record.id, FitnessCaption(record.result));  // which evaluation, and how it did
    scene.panels = {{record.result.initial, {}, "", 0, {}, {}}, {record.result.final, record.result.initial, "", 0, {}, {}}};
    WritePng((folder_ / Name(record.id)).string(), renderer_->Render(scene), 1);
}

void Thumbnails::RollBack(std::uint64_t keep, const std::vector<ArchiveRecord>&) {
    std::error_code ec;
    for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
        unsigned long long id = 0;
        if (std::sscanf(it->path().filename().string().c_str(), "evaluation_%llu.png", &id) == 1 && id >= keep) fs::remove(it->path(), ec);
    }
}

}  // namespace app
