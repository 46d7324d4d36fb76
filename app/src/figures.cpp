#include "figures.h"

#include <cmath>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <numbers>

#include "errors.h"
#include "files.h"
#include "render/backend.h"
#include "sim/surface.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// "2.642", or "pi-0.5" style when the value is a simple multiple of pi plus a small offset.
std::string Phase(double value) {
    for (int n = 0; n <= 16; ++n)
        for (double offset : {0.0, 0.5, -0.5}) {
            if (std::fabs(value - (n * std::numbers::pi + offset)) > 1e-9) continue;
            if (n == 0) return fmt::format("{:g}", offset);
            const std::string pis = n == 1 ? "pi" : std::to_string(n) + "pi";
            return offset == 0 ? pis : pis + (offset > 0 ? "+0.5" : "-0.5");
        }
    return fmt::format("{:.4g}", value);
}

}  // namespace

std::string ShapeTitle(const sim::Shape& shape) {
    std::string title = sim::ShapeName(shape);
    auto sine = [&](double amplitude, double a, double b) {
        title += fmt::format("  A = {:.4g}, phase {} to {}", amplitude, Phase(a), Phase(b));
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

std::string ResultLine(const sim::SimResult& r, const sim::MeshDef& mesh) {
    std::string line = std::string("status ") + sim::Name(r.status) + ",  ";
    if (r.status == sim::Status::Ok) line += fmt::format("fitness {:.4f},  contraction {:.2f} %,  ", r.fitness, r.contractionPercent);
    return line + fmt::format("{} iterations,  {} x {} mesh", r.iterationsRun, mesh.resolution, mesh.turns);
}

std::string FitnessCaption(const sim::SimResult& r) { return r.status == sim::Status::Ok ? fmt::format("{:.3f}", r.fitness) : sim::Name(r.status); }

std::shared_ptr<const sim::Surface> SurfaceOf(const sim::MeshDef& mesh) {
    // Surfaces are shared: a sweep draws thousands of meshes of one size.
    static std::mutex mutex;
    static std::map<std::pair<int, int>, std::shared_ptr<const sim::Surface>> cache;
    std::lock_guard lock(mutex);
    auto& surface = cache[{mesh.resolution, mesh.turns}];
    if (!surface) surface = std::make_shared<const sim::Surface>(sim::HelixSurface(mesh));
    return surface;
}

render::Scene BeforeAfterScene(const std::string& title, const sim::SimResult& r, const sim::MeshDef& mesh) {
    render::Scene scene;
    scene.surface = SurfaceOf(mesh);
    scene.title = title;
    scene.lines = {ResultLine(r, mesh)};
    scene.panels = {{r.initial, {}, "before", 0, {}, {}}, {r.final, r.initial, "after " + std::to_string(r.iterationsRun) + " iterations", 0, {}, {}}};
    return scene;
}

render::Scene TurntableScene(const std::string& title, const sim::SimResult& r, const sim::MeshDef& mesh, double angleDegrees) {
    render::Scene scene;
    scene.surface = SurfaceOf(mesh);
    scene.title = title;
    scene.lines = {ResultLine(r, mesh)};
    scene.panels = {{r.final, r.initial, fmt::format("turned {:.0f} degrees", angleDegrees), angleDegrees, {}, {}}};
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
    for (const auto& [load, result] : loads) {
        if (!result) continue;
        const std::string name = f.prefix + load + ".png";
        WritePng((folder / name).string(), renderer.Render(BeforeAfterScene(f.title + "  -  " + load, *result, f.mesh)), figureLevel);
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
                         renderer.Render(TurntableScene(f.title + "  -  inflated", *f.inflated, f.mesh, 360.0 * k / f.turntableFrames)));
        writer.Wait();
        written.push_back(sub + "/frame_%04d.png x " + std::to_string(f.turntableFrames));
    }
    return written;
}

void WriteContactSheet(const fs::path& path, const std::string& title, const std::vector<SheetEntry>& entries, const sim::MeshDef& mesh,
                       std::unique_ptr<render::MeshRenderer>& renderer) {
    if (entries.empty()) return;
    // Actuators are about ten times taller than wide: many narrow columns, cells about 1:2.
    const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(entries.size() * 3.0))));
    const int rows = static_cast<int>((entries.size() + columns - 1) / columns);
    const int width = std::clamp(columns * 125 + 110, 800, 2600), height = std::clamp(rows * 250 + 110, 450, 2400);
    if (!renderer || renderer->Def().width != width || renderer->Def().height != height) renderer = MakeRenderer(width, height, 1, 0.72);
    render::Scene scene;
    scene.surface = SurfaceOf(mesh);
    scene.title = title;
    scene.columns = columns;
    std::vector<const sim::Positions*> all;
    for (const auto& entry : entries) {
        scene.panels.push_back({entry.result->final, entry.result->initial, entry.caption, 0, {}, {}});
        if (entry.result->status == sim::Status::Ok) all.push_back(&entry.result->final);
    }
    if (!all.empty()) scene.framing = render::FrameMeshes(all);
    WritePng(path.string(), renderer->Render(scene), 1);
}

ThumbnailWriter::ThumbnailWriter(fs::path folder) : folder_(std::move(folder)) {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (!fs::is_directory(folder_, ec)) throw UsageError("cannot create folder " + Quote(folder_.string()));
    render::RenderDef def = render::DefaultRenderDef();
    def.width = 240;
    def.height = 180;
    def.supersample = 1;
    def.overlay = false;
    renderer_ = MakeRenderer(def);
}

std::string ThumbnailWriter::Name(std::uint64_t id) { return fmt::format("evaluation_{:06}.png", id); }

void ThumbnailWriter::Write(std::uint64_t id, const sim::SimResult& result, const sim::MeshDef& mesh) {
    render::Scene scene;
    scene.surface = SurfaceOf(mesh);
    scene.panels = {{result.initial, {}, "", 0, {}, {}}, {result.final, result.initial, "", 0, {}, {}}};
    WritePng((folder_ / Name(id)).string(), renderer_->Render(scene), 1);
}

}  // namespace app
