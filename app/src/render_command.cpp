// `actuator render`: pictures of one shape. Simulates inflation and stretch (in parallel), then
// writes inflation.png and stretch.png (before and after, one camera, one scale), and on request a
// turntable of the inflated mesh, a time-lapse of the inflation, and MP4s of both through ffmpeg.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>

#include "commands.h"
#include "archive.h"
#include "figures.h"
#include "mesh_io.h"
#include "render/mesh_renderer.h"
#include "shape_options.h"

namespace app {
namespace {

namespace fs = std::filesystem;

std::vector<OptionSpec> RenderOnlySpecs() {
    return {
        {"out", "DIR", "", "folder for the images (created if missing); required"},
        {"from", "ARCHIVE", "", "render evaluation --index of an archive (evaluations.capnp) without simulating; no shape options"},
        {"index", "K", "", "with --from: which evaluation (see actuator inspect)"},
        {"size", "WxH", "1024x768", "image size in pixels"},
        {"turntable", "N", "", "also write N frames of the inflated mesh turning a full circle to DIR/turntable/", "60"},
        {"timelapse", "N", "", "also write N frames of the inflation, one every iterations/N, to DIR/timelapse/"},
        {"video", "", "", "also encode the frame sequences as MP4 with ffmpeg (skipped with a note if ffmpeg is missing)"},
        {"background", "white|transparent", "white", "image background"},
        {"color-by", "displacement|strain|none", "displacement", "surface colour: distance moved, spring strain, or plain"},
        {"wireframe", "", "", "draw the springs over the surface"},
        {"no-overlay", "", "", "leave out the title, numbers, captions and colour bar"},
        {"supersample", "N", "2", "render at N times the size and average down (anti-aliasing; 1 = off)"},
        {"elevation", "DEG", "16", "camera height above the mid-plane, degrees"},
        {"azimuth", "DEG", "30", "camera direction around the actuator's axis, degrees"},
        {"png-level", "0-9", "6 for figures, 1 for frame sequences", "zlib compression level of the PNG files"},
        {"help", "", "", "show this help"},
    };
}

std::vector<OptionSpec> AllSpecs() {
    auto specs = ShapeOptionSpecs();
    for (auto& s : SimulationOptionSpecs())
        if (s.name != "load") specs.push_back(s);  // render shows both loads
    for (auto& s : RenderOnlySpecs()) specs.push_back(s);
    return specs;
}

// Frames go to disk on another thread while the next one renders; at most one write in flight.
class FrameWriter {
public:
    explicit FrameWriter(int pngLevel) : pngLevel_(pngLevel) {}
    ~FrameWriter() { Wait(); }
    void Write(std::string path, render::Image image) {
        Wait();
        pending_ = std::async(std::launch::async, [path = std::move(path), image = std::move(image), level = pngLevel_] {
            WriteFileAtomically(path, BytesOf(render::EncodePng(image, level)));
        });
    }
    void Wait() {
        if (pending_.valid()) pending_.get();  // rethrows a write error here
    }
    static std::string BytesOf(const std::vector<std::uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

private:
    int pngLevel_;
    std::future<void> pending_;
};

std::string ShellQuote(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

void EncodeVideo(const fs::path& frames, const fs::path& output) {
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
        std::cerr << "note: ffmpeg is not installed, so " << output.string() << " was not made (apt-get install ffmpeg)\n";
        return;
    }
    const std::string command = "ffmpeg -y -loglevel error -framerate 30 -i " + ShellQuote((frames / "frame_%04d.png").string()) +
                                " -c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' " + ShellQuote(output.string());
    if (std::system(command.c_str()) != 0) std::cerr << "note: ffmpeg failed to make " << output.string() << "\n";
}

void Progress(const char* what, int done, int total) {
    if (!isatty(STDERR_FILENO)) return;
    std::fprintf(stderr, "\r%s: frame %d/%d", what, done, total);
    if (done == total) std::fprintf(stderr, "\n");
}

// An archived evaluation drawn again from its stored meshes: no simulation.
int RenderFromArchive(const ParsedArgs& args) {
    for (const auto& spec : ShapeOptionSpecs())
        if (args.Has(spec.name)) throw UsageError("--from ARCHIVE takes the shape from the archive; drop --" + spec.name);
    for (const auto& spec : SimulationOptionSpecs())
        if (args.Has(spec.name)) throw UsageError("--from ARCHIVE takes the settings from the archive; drop --" + spec.name);
    if (!args.Has("index")) throw UsageError("--from ARCHIVE needs --index K (list them with actuator inspect)");
    if (!args.Has("out")) throw UsageError("--out DIR is required (where the images go)");
    const long long index = ParseInt(args.Get("index"), "--index", 0, 2'000'000'000);
    const ArchiveContents contents = ReadArchive(args.Get("from"));
    if (contents.evaluations.empty() && contents.truncated)
        throw UsageError("'" + args.Get("from") + "' is not an evaluation archive (" + contents.problem + ")");
    if (index >= static_cast<long long>(contents.evaluations.size()))
        throw UsageError("--index " + std::to_string(index) + ": the archive holds " + std::to_string(contents.evaluations.size()) + " evaluations");
    const ArchivedEvaluation& e = contents.evaluations[static_cast<size_t>(index)];
    if (e.initial.Size() != sim::VertexCount(e.mesh) || e.final.Size() != e.initial.Size())
        throw UsageError("evaluation " + std::to_string(index) + " has no usable meshes");

    const fs::path out = args.Get("out");
    std::error_code ec;
    fs::create_directories(out, ec);
    if (!fs::is_directory(out, ec)) throw UsageError("--out: cannot create folder '" + out.string() + "'");
    render::RenderDef def = render::DefaultRenderDef();
    std::string error;
    auto renderer = render::MeshRenderer::Create(def, &error);
    if (!renderer) throw UsageError("cannot render: " + error);
    const sim::SimResult result = ResultOf(e);
    std::string title = "archive " + (e.experiment.empty() ? std::string("") : e.experiment + " ") + "#" + std::to_string(index) + ": " +
                        ShapeTitle(e.shape) + (e.label.empty() ? "" : "  (" + e.label + ")") + "  -  " + sim::LoadName(e.params.load);
    const fs::path path = out / ("evaluation_" + std::to_string(index) + ".png");
    WritePng(path.string(), renderer->Render(BeforeAfterScene(title, result, e.mesh)), 6);
    JsonWriter json;
    json.BeginObject().Key("index").Integer(index).Key("status").String(sim::StatusName(e.status)).Key("fitness").Number(e.fitness);
    json.Key("files").BeginArray().String(path.string()).EndArray().Key("simulated").Bool(false).EndObject();
    std::cout << json.Text() << "\n";
    return 0;
}

}  // namespace

std::string RenderHelp() {
    return "usage: actuator render [shape options] [simulation options] --out DIR [picture options]\n\n"
           "Simulates one shape under inflation and under the stretch load and writes pictures of it:\n"
           "  DIR/inflation.png   before and after inflation, side by side, same camera and scale\n"
           "  DIR/stretch.png     the same for the stretch load\n"
           "  DIR/turntable/frame_0000.png ...  (--turntable) the inflated mesh turning a full circle\n"
           "  DIR/timelapse/frame_0000.png ...  (--timelapse) the mesh while it inflates\n"
           "  DIR/turntable.mp4, DIR/timelapse.mp4  (--video, with ffmpeg)\n"
           "and prints a JSON summary. Exit code 0 on success, 2 on bad input.\n\n"
           "Shape options:\n" + FormatOptions(ShapeOptionSpecs()) +
           "\nSimulation options (both loads):\n" + [] {
               auto specs = SimulationOptionSpecs();
               std::erase_if(specs, [](const OptionSpec& s) { return s.name == "load"; });
               return FormatOptions(specs);
           }() + "\nPicture options:\n" + FormatOptions(RenderOnlySpecs()) +
           "\nExamples:\n  actuator render --shape sine --amplitude 4.1 --out figures/sine --turntable 60 --video\n"
           "  actuator render --from runs/5.2/evaluations.capnp --index 17 --out figures/   (no simulation)\n";
}

int RunRender(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, AllSpecs(), 0);
    if (args.Has("help")) {
        std::cout << RenderHelp();
        return 0;
    }
    if (args.Has("from")) return RenderFromArchive(args);
    if (args.Has("index")) throw UsageError("--index goes with --from ARCHIVE");
    const EvaluationRequest request = ParseEvaluationRequest(args);
    if (!args.Has("out")) throw UsageError("--out DIR is required (where the images go)");

    render::RenderDef def = render::DefaultRenderDef();
    if (args.Has("size")) {
        const std::string size = args.Get("size");
        const auto x = size.find('x');
        if (x == std::string::npos) throw UsageError("--size: expected WxH like 1024x768, got '" + size + "'");
        def.width = ParseInt(size.substr(0, x), "--size width", 64, 8192);
        def.height = ParseInt(size.substr(x + 1), "--size height", 64, 8192);
    }
    if (args.Has("supersample")) def.supersample = ParseInt(args.Get("supersample"), "--supersample", 1, 4);
    if (static_cast<long long>(def.width) * def.height * def.supersample * def.supersample > 64ll << 20)
        throw UsageError("--size x --supersample: more than 64 megapixels to render; lower one of them");
    if (args.Has("background"))
        def.background = ParseChoice(args.Get("background"), "--background", {"white", "transparent"}) == "white"
                             ? render::Background::White : render::Background::Transparent;
    if (args.Has("color-by")) {
        const auto mode = ParseChoice(args.Get("color-by"), "--color-by", {"displacement", "strain", "none"});
        def.colorBy = mode == "displacement" ? render::ColorBy::Displacement : mode == "strain" ? render::ColorBy::Strain : render::ColorBy::Shading;
    }
    def.wireframe = args.Has("wireframe");
    def.overlay = !args.Has("no-overlay");
    if (args.Has("elevation")) def.elevationDegrees = ParseNumber(args.Get("elevation"), "--elevation");
    if (args.Has("azimuth")) def.azimuthDegrees = ParseNumber(args.Get("azimuth"), "--azimuth");
    if (std::fabs(def.elevationDegrees) > 89) throw UsageError("--elevation: must be between -89 and 89 degrees");
    const int turntable = args.Has("turntable") ? ParseInt(args.Get("turntable"), "--turntable", 1, 100000) : 0;
    const int timelapse = args.Has("timelapse") ? ParseInt(args.Get("timelapse"), "--timelapse", 1, 100000) : 0;
    if (timelapse > std::max(1, request.params.iterations))
        throw UsageError("--timelapse: more frames (" + std::to_string(timelapse) + ") than iterations (" +
                         std::to_string(request.params.iterations) + ")");
    const int figureLevel = args.Has("png-level") ? ParseInt(args.Get("png-level"), "--png-level", 0, 9) : 6;
    const int frameLevel = args.Has("png-level") ? figureLevel : 1;

    const fs::path out = args.Get("out");
    std::error_code ec;
    fs::create_directories(out, ec);
    if (!fs::is_directory(out, ec)) throw UsageError("--out: cannot create folder '" + out.string() + "'");
    CheckOutputPath((out / "inflation.png").string(), "--out");

    std::string error;
    auto renderer = render::MeshRenderer::Create(def, &error);
    if (!renderer) throw UsageError("cannot render: " + error);

    // Both loads at once (the solver is thread-safe); the time-lapse watches the inflation.
    const auto started = std::chrono::steady_clock::now();
    sim::SimParams stretchParams = request.params;
    stretchParams.load = sim::Load::Stretch;
    auto stretchFuture = std::async(std::launch::async, [&] {
        return sim::Simulate(sim::BuildInitialPositions(request.shape, request.mesh), request.mesh, stretchParams);
    });
    sim::SimParams inflateParams = request.params;
    inflateParams.load = sim::Load::Inflate;
    std::vector<std::pair<int, sim::Positions>> snapshots;
    sim::SimObserver observer;
    if (timelapse > 0) {
        observer.interval = std::max(1, request.params.iterations / timelapse);
        observer.onSnapshot = [&](int iteration, const sim::Positions& p) {
            snapshots.emplace_back(iteration, p);
            return true;
        };
    }
    const sim::SimResult inflated =
        sim::Simulate(sim::BuildInitialPositions(request.shape, request.mesh), request.mesh, inflateParams, timelapse ? &observer : nullptr);
    const sim::SimResult stretched = stretchFuture.get();
    const double simulateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();

    const std::string title = ShapeTitle(request.shape);
    auto figure = [&](const sim::SimResult& r, const char* load) {
        return renderer->Render(BeforeAfterScene(title + "  -  " + load, r, request.mesh));
    };
    std::vector<std::string> written;
    const auto renderStarted = std::chrono::steady_clock::now();
    for (const auto& [name, result, load] : {std::tuple{"inflation.png", &inflated, "inflation"}, std::tuple{"stretch.png", &stretched, "stretch"}}) {
        const fs::path path = out / name;
        WritePng(path.string(), figure(*result, load), figureLevel);
        written.push_back(path.string());
    }

    // Sequences: camera and colour scale fixed over all frames, so only the mesh moves.
    auto sequence = [&](const char* folderName, int frames, auto&& sceneOf) {
        const fs::path folder = out / folderName;
        fs::create_directories(folder, ec);
        if (!fs::is_directory(folder, ec)) throw UsageError("cannot create folder '" + folder.string() + "'");
        FrameWriter writer(frameLevel);
        for (int k = 0; k < frames; ++k) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04d.png", k);
            writer.Write((folder / name).string(), renderer->Render(sceneOf(k)));
            Progress(folderName, k + 1, frames);
        }
        writer.Wait();
        written.push_back((folder / "frame_%04d.png").string() + " x " + std::to_string(frames));
        if (args.Has("video")) {
            const fs::path video = out / (std::string(folderName) + ".mp4");
            EncodeVideo(folder, video);
            if (fs::exists(video, ec)) written.push_back(video.string());
        }
    };
    if (turntable > 0)
        sequence("turntable", turntable, [&](int k) { return TurntableScene(title + "  -  inflated", inflated, request.mesh, 360.0 * k / turntable); });
    if (timelapse > 0) {
        std::vector<const sim::Positions*> all;
        for (const auto& s : snapshots) all.push_back(&s.second);
        const render::Framing framing = render::FrameMeshes(all);
        double colorMax = 0;
        for (const auto& s : snapshots)
            for (double v : render::VertexValues(def.colorBy, request.mesh, s.second, inflated.initial)) colorMax = std::max(colorMax, v);
        sequence("timelapse", static_cast<int>(snapshots.size()), [&](int k) {
            render::Scene scene;
            scene.mesh = request.mesh;
            scene.title = title + "  -  inflating";
            const sim::Positions& p = snapshots[k].second;
            const double fitness = sim::Fitness(inflated.initial, p, request.mesh);
            scene.lines = {"iteration " + std::to_string(snapshots[k].first) + " of " + std::to_string(inflateParams.iterations) +
                           ",  fitness " + FormatNumber("%.4f", fitness) + ",  contraction " + FormatNumber("%.2f %%", 100 * fitness / request.mesh.turns)};
            scene.panels = {{p, inflated.initial, "iteration " + std::to_string(snapshots[k].first), 0}};
            scene.framing = framing;
            scene.colorMax = colorMax;
            return scene;
        });
    }
    const double renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - renderStarted).count();

    JsonWriter json;
    json.BeginObject();
    json.Key("inflation").BeginObject().Key("status").String(sim::StatusName(inflated.status)).Key("fitness").Number(inflated.fitness).EndObject();
    json.Key("stretch").BeginObject().Key("status").String(sim::StatusName(stretched.status)).Key("fitness").Number(stretched.fitness).EndObject();
    json.Key("files").BeginArray();
    for (const auto& f : written) json.String(f);
    json.EndArray();
    json.Key("simulate_ms").Number(simulateMs).Key("render_ms").Number(renderMs);
    json.Key("renderer").String(renderer->Description());
    json.EndObject();
    std::cout << json.Text() << "\n";
    return 0;
}

}  // namespace app
