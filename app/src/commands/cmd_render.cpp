// `actuator render`: pictures of one design. Evaluates it under inflation and under the stretch
// load (both on the evaluator, in parallel), then writes inflation.png and stretch.png (before and
// after, one camera, one scale), and on request a turntable of the inflated mesh, a time-lapse of
// the inflation, and MP4s of both through ffmpeg. With --from ARCHIVE it draws a stored evaluation
// without simulating.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>

#include "formats/archive.h"
#include "options/cli.h"
#include "commands/registry.h"
#include "evaluation/evaluator.h"
#include "pictures/figures.h"
#include "formats/files.h"
#include "fields/result_fields.h"
#include "formats/json_out.h"
#include "support/progress.h"
#include "render/backend.h"
#include "options/model_options.h"
#include "options/part_options.h"
#include "options/shape_options.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// Time-lapse snapshots are kept in memory to fix one camera and colour scale over all frames.
constexpr double kMaxSnapshotBytes = 2.0 * (1ull << 30);

std::string ShellQuote(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

bool HaveFfmpeg() { return std::system("command -v ffmpeg > /dev/null 2>&1") == 0; }

// The frames as an MP4, written beside it under a temporary name and renamed when whole: a failed
// encoding (a full disk) leaves no part of a video. False when there is none.
bool EncodeVideo(const fs::path& frames, const fs::path& output) {
    const fs::path partial = output.parent_path() / (".act" + std::to_string(getpid()) + "-video.tmp");
    const std::string command = "ffmpeg -y -loglevel error -framerate 30 -i " + ShellQuote((frames / "frame_%04d.png").string()) +
                                " -c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -f mp4 " + ShellQuote(partial.string());
    std::error_code ec;
    if (std::system(command.c_str()) != 0 || std::rename(partial.c_str(), output.c_str()) != 0) {
        fs::remove(partial, ec);
        std::cerr << "note: ffmpeg failed to make " << output.string() << "\n";
        return false;
    }
    return true;
}

// A folder for frames: refused early when something that is not a folder is in the way.
void CheckFolder(const fs::path& folder, const std::string& what) {
    std::error_code ec;
    if (fs::exists(fs::symlink_status(folder, ec)) && !fs::is_directory(fs::symlink_status(folder, ec)))
        throw UsageError(what + ": " + Quote(folder.string()) + " is in the way and is not a folder");
}

struct PictureOptions {
    std::string out;
    std::string size;  // WxH; the default is the RenderDef's
    int turntable = 0;
    int timelapse = 0;
    bool video = false;
    int pngLevel = 6;
    std::string backend;
    render::RenderDef def = render::DefaultRenderDef();
};


// The thesis model's inflation watched: the first state, every `interval` iterations, the last.
template <class Sequence>
void WriteThesisTimelapse(const sim::EvalJob& job, const std::string& title, Colouring colouring, const PictureOptions& p, Sequence&& sequence) {
    std::vector<std::pair<int, sim::Positions>> snapshots;
    sim::SimObserver observer;
    sim::SimParams watched = job.Thesis().params;
    watched.load = sim::Load::Inflate;
    observer.interval = std::max(1, watched.iterations / (p.timelapse - 1));
    observer.onSnapshot = [&](int iteration, const sim::Positions& positions) {
        if (static_cast<int>(snapshots.size()) < p.timelapse - 1) snapshots.emplace_back(iteration, positions);
        return true;
    };
    const sim::SimResult watchedResult = sim::Simulate(sim::BuildInitialPositions(job.shape, job.Thesis().mesh), job.Thesis().mesh, watched, &observer);
    snapshots.emplace_back(watchedResult.iterationsRun, watchedResult.final);
    std::vector<render::Scene> scenes;
    for (const auto& [iteration, positions] : snapshots) {
        sim::SimResult at = watchedResult;
        at.final = positions;
        render::Scene scene = TurntableScene(title + "  -  inflating", at, job, 0, colouring);
        const double fitness = sim::Fitness(watchedResult.initial, positions, job.Thesis().mesh);
        scene.lines = {fmt::format("iteration {} of {},  fitness {:.4f},  contraction {:.2f} %", iteration, watched.iterations, fitness,
                                   100 * fitness / job.Thesis().mesh.turns)};
        scene.panels.front().caption = "iteration " + std::to_string(iteration);
        scenes.push_back(std::move(scene));
    }
    ShareFramingAndScale(scenes);
    sequence("timelapse", static_cast<int>(scenes.size()), [&](int k) { return scenes[k]; });
}

}  // namespace

static int RunRender(int argc, char** argv, int first) {
    Cli cli("render", "Pictures of one design. Under --model thesis: evaluated under inflation and under the stretch load, written as "
                      "DIR/inflation.png and DIR/stretch.png (before and after, side by side, one camera and scale). Under --model membrane or "
                      "shell: DIR/inflation.png at the target pressure, coloured by principal stretch (or stress) with the material's limit "
                      "on the colour bar, and DIR/pressure_curve.png, the contraction-pressure curve. On request DIR/turntable/frame_NNNN.png "
                      "(the inflated mesh turning), DIR/timelapse/frame_NNNN.png (the inflation: iterations of the thesis model, load steps "
                      "of the others) and MP4s of both. Prints a JSON summary.");
    ShapeOptions shape;
    ModelOptions model;
    std::string from;
    int index = 0;
    PictureOptions p;
    Colouring colouring = Colouring::Auto;
    bool saveVtu = false;
    p.size = fmt::format("{}x{}", p.def.width, p.def.height);
    AddShapeOptions(cli, shape);
    AddModelOptions(cli, model);
    cli.Group("Design from an archive");
    cli.Text("--from", from, "draw a stored evaluation (DIR/evaluations.capnp) with --index, without simulating; no shape or model options")
        ->type_name("ARCHIVE");
    cli.Integer("--index", index, "with --from: the evaluation id (see actuator inspect)", 0, 1ll << 40)->default_str("");
    PartOptions partOptions;
    std::string solid;
    cli.Group("Exported solids (no simulation)");
    cli.Text("--solid", solid, "draw the solids `export` writes instead: cutaway (the wall cut along its axis, DIR/cutaway.png) or mold "
                               "(the parts side by side, DIR/mold.png); with the part and mold options below")
        ->type_name("cutaway|mold");
    AddPartOptions(cli, partOptions);
    cli.Group("Picture options");
    cli.Text("--out", p.out, "folder for the images (created if missing); required")->type_name("DIR");
    cli.Text("--size", p.size, "image size in pixels")->type_name("WxH");
    std::string turntable, timelapse;
    cli.Text("--turntable", turntable, "also write N frames of the inflated mesh turning a full circle to DIR/turntable/ (60 when N is left out)")
        ->expected(0, 1)
        ->type_name("[N]")
        ->default_str("60");
    cli.Text("--timelapse", timelapse,
             "also write the inflation to DIR/timelapse/: thesis model, N frames (the first, evenly spaced iterations, the last; 30 when N is "
             "left out); membrane and shell, one frame per load step (N, when given, sets the number of load steps)")
        ->expected(0, 1)
        ->type_name("[N]")
        ->default_str("30");
    cli.Flag("--save-vtu", saveVtu, "also write the inflated wall with its fields as DIR/inflated.vtu (thesis: and DIR/stretched.vtu; --from: "
                                    "DIR/evaluation_NNNNNN.vtu), as simulate --save-vtu does");
    cli.Flag("--video", p.video, "also encode the frame sequences as MP4 with ffmpeg (skipped with a note if ffmpeg is missing)");
    cli.Enum("--background", p.def.background, "image background");
    cli.Enum("--color-by", colouring,
             "surface colour: auto (displacement for the thesis model, stretch for the others), displacement, spring or edge strain, "
             "largest principal stretch or true stress (membrane and shell), gap: how near each wall is to another beyond a wall thickness "
             "(--contact on: where walls touch), or none");
    cli.Flag("--wireframe", p.def.wireframe, "draw the edges (springs) over the surface");
    bool noOverlay = false;
    cli.Flag("--no-overlay", noOverlay, "leave out the title, numbers, captions and colour bar");
    cli.Integer("--supersample", p.def.supersample, "render at N times the size and average down (anti-aliasing; 1 = off)", 1, 4);
    cli.Number("--elevation", p.def.elevationDegrees, "camera height above the mid-plane, degrees", -89, 89);
    cli.Number("--azimuth", p.def.azimuthDegrees, "camera direction around the actuator's axis, degrees");
    cli.Integer("--png-level", p.pngLevel, "zlib compression level of the PNG files (frame sequences use 1 unless given)", 0, 9);
    cli.Text("--gl-backend", p.backend, "OpenGL backend module: osmesa or egl (default: $ACTUATOR_GL_BACKEND, else osmesa)")->type_name("NAME");
    cli.Examples(
        "  actuator render --model thesis --shape sine --amplitude 4.1 --out figures/sine --turntable 60 --video\n"
        "  actuator render --shape sine --amplitude 1.3 --pressure-kpa 4 --timelapse 8 --out figures/shell\n"
        "  actuator render --shape cylinder --fibres braid --fibre-angle-deg 30 --color-by stress --out figures/braid\n"
        "  actuator render --from runs/5.2/evaluations.capnp --index 17 --out figures/ --turntable 36   (no simulation)\n"
        "  actuator render --model thesis --shape sine --amplitude 1.3 --phase 0.5,pi-0.5 --solid cutaway --wall-mm 1.5 --out figures/\n");
    if (!cli.Parse(argc, argv, first)) return 0;
    if (cli.Given("--turntable")) p.turntable = static_cast<int>(ParseInteger(turntable.empty() ? "60" : turntable, "--turntable", 1, 100000));
    if (cli.Given("--timelapse")) p.timelapse = static_cast<int>(ParseInteger(timelapse.empty() ? "30" : timelapse, "--timelapse", 2, 100000));
    p.def.overlay = !noOverlay;
    if (!cli.Given("--out")) throw UsageError("--out DIR is required (where the images go)");
    {
        const auto x = p.size.find('x');
        if (x == std::string::npos) throw UsageError("--size: expected WxH like 1024x768, got " + Quote(p.size));
        p.def.width = static_cast<int>(ParseInteger(p.size.substr(0, x), "--size width", 64, 8192));
        p.def.height = static_cast<int>(ParseInteger(p.size.substr(x + 1), "--size height", 64, 8192));
    }
    if (static_cast<long long>(p.def.width) * p.def.height * p.def.supersample * p.def.supersample > 64ll << 20)
        throw UsageError("--size x --supersample: more than 64 megapixels to render; lower one of them");
    if (cli.Given("--gl-backend")) {
        std::string error;
        if (!render::SetBackend(p.backend, &error)) throw UsageError("--gl-backend: " + error);
    }
    const int frameLevel = cli.Given("--png-level") ? p.pngLevel : 1;
    if (cli.Given("--video") && !p.turntable && !p.timelapse) throw UsageError("--video needs --turntable or --timelapse (the frames it encodes)");

    // The design: from the options, or stored in an archive.
    sim::EvalJob job;
    std::optional<ArchiveRecord> stored;
    if (cli.Given("--from")) {
        for (const auto& name : ShapeOptionNames()) cli.RefuseIfGiven(name, "does not go with --from: the design comes from the archive");
        cli.RefuseIfGiven("--timelapse", "needs a simulation; --from draws the stored meshes (re-simulate with actuator simulate --from)");
        cli.RefuseIfGiven("--model", "does not go with --from: the model comes from the archive");
        RefuseModelOptions(cli, model, "does not go with --from: the settings come from the archive");
        if (!cli.Given("--index")) throw UsageError("--from ARCHIVE needs --index K (list them with actuator inspect)");
        stored = ReadArchiveRecord(from, static_cast<std::uint64_t>(index));
        job = stored->job;
        const int vertices = SharedSurface(job)->vertexCount;
        if (stored->result.initial.Size() != vertices || stored->result.final.Size() != vertices)
            throw UsageError("evaluation " + std::to_string(index) + " of " + Quote(from) + " has no usable meshes");
    } else {
        cli.RefuseIfGiven("--index", "goes with --from ARCHIVE");
        job = BuildJob(cli, shape, model, cli.Given("--solid") ? ModelUse::RestShape : ModelUse::BothLoads);
        if (job.model == sim::ModelKind::Thesis)
            cli.RefuseIfGiven("--load", "does not apply to --model thesis here: render shows both of its loads (inflation and stretch)");
    }
    const bool thesis = job.model == sim::ModelKind::Thesis;
    if (const std::string error = ColouringError(colouring, job); !error.empty()) throw UsageError("--color-by: " + error);
    if (thesis && p.timelapse > std::max(1, job.Thesis().params.iterations) + 1)
        throw UsageError(fmt::format("--timelapse: {} frames but only {} iterations", p.timelapse, job.Thesis().params.iterations));
    if (!thesis && p.timelapse && !stored) {
        // One frame per load step: N sets the steps, unless --steps says otherwise.
        if (cli.Given("--steps") && cli.Given("--timelapse") && !timelapse.empty() && p.timelapse != job.Shell().load.steps)
            throw UsageError(fmt::format("--timelapse {} and --steps {}: under --model {} the time-lapse has one frame per load step; give one of them",
                                         p.timelapse, job.Shell().load.steps, sim::Name(job.model)));
        if (!cli.Given("--steps") && !timelapse.empty()) job.Shell().load.steps = p.timelapse;
        p.timelapse = job.Shell().load.steps;
    }
    if (cli.Given("--solid")) {
        if (solid != "cutaway" && solid != "mold") throw UsageError("--solid: unknown value " + Quote(solid) + " (choose cutaway or mold)");
        for (const char* option : {"--turntable", "--timelapse", "--video", "--save-vtu"})
            cli.RefuseIfGiven(option, "does not go with --solid (a picture of the exported solids, nothing is simulated)");
        cli.RefuseIfGiven("--wireframe", "draws the simulation mesh's edges; the solids are drawn without them");
        if (solid == "cutaway")
            for (const auto& names : {MoldOptionNames(), std::vector<std::string>{"--fittings", "--port-mm"}})
                for (const auto& name : names) cli.RefuseIfGiven(name, "applies to --solid mold (the cut-away shows the wall alone)");
        const sim::PartDef part = PartDefOf(cli, partOptions, job);
        const sim::PartSolids solids = BuildSolids(job, part, partOptions.mold, partOptions.fittings);
        const fs::path out = p.out;
        CreatedFolders folders;
        folders.Create(out, "--out");
        const std::string file = (out / (solid + ".png")).string();
        CheckOutputPath(file, "--out");
        RefuseOutputThatIsInput(file, "--out", {shape.meshFile, shape.offsets, from});
        const std::string title = fmt::format("{}  -  wall {:g} mm", ShapeTitle(job.shape), part.thicknessMm);
        WritePng(file, MakeRenderer(p.def)->Render(solid == "mold" ? ExplodedMoldScene(solids, "mold for " + title) : CutawayScene(solids, title)), p.pngLevel);
        std::cout << Json{{"image", file}, {"silicone_volume_mm3", sim::MeshVolume(solids.actuator)}}.dump() << "\n";
        return 0;
    }
    for (const auto& names : {PartOptionNames(), MoldOptionNames()})
        for (const auto& name : names) cli.RefuseIfGiven(name, "applies to --solid (the pictures of the solids export makes)");
    const double snapshotBytes = double(p.timelapse) * SharedSurface(job)->vertexCount * 3 * sizeof(double);
    if (snapshotBytes > kMaxSnapshotBytes)
        throw UsageError(fmt::format("--timelapse: {} frames of {} vertices would hold {:.1f} GB of snapshots, more than {:.0f} GB; use fewer frames or a "
                                     "smaller mesh",
                                     p.timelapse, SharedSurface(job)->vertexCount, snapshotBytes / 1e9, kMaxSnapshotBytes / 1e9));

    // Every output checked before any work: nothing is half-written on bad input.
    const fs::path out = p.out;
    std::error_code ec;
    CreatedFolders folders;  // before the batch: removed, when left empty, after its temporaries
    folders.Create(out, "--out");
    const std::vector<std::string> inputs{shape.meshFile, shape.offsets, from};
    std::vector<std::string> files;
    if (stored) files.push_back(fmt::format("evaluation_{:06}.png", index));
    else if (thesis) files.insert(files.end(), {"inflation.png", "stretch.png"});
    else files.insert(files.end(), {"inflation.png", "pressure_curve.png"});
    if (p.turntable) CheckFolder(out / "turntable", "--turntable");
    if (p.timelapse) CheckFolder(out / "timelapse", "--timelapse");
    if (saveVtu) {
        if (stored) files.push_back(fmt::format("evaluation_{:06}.vtu", index));
        else if (thesis) files.insert(files.end(), {"inflated.vtu", "stretched.vtu"});
        else files.push_back("inflated.vtu");
    }
    if (p.video && p.turntable) files.push_back("turntable.mp4");
    if (p.video && p.timelapse) files.push_back("timelapse.mp4");
    for (const auto& name : files) {
        CheckOutputPath((out / name).string(), "--out");
        RefuseOutputThatIsInput((out / name).string(), "--out", inputs);
    }
    const bool video = p.video && HaveFfmpeg();
    if (p.video && !video) std::cerr << "note: ffmpeg is not installed, so no MP4 is made (apt-get install ffmpeg)\n";

    auto renderer = MakeRenderer(p.def);
    const auto started = std::chrono::steady_clock::now();
    sim::SimResult inflated, stretched;
    if (stored) {
        inflated = stored->result;
    } else if (thesis) {
        sim::EvalJob inflate = job, stretch = job;
        inflate.Thesis().params.load = sim::Load::Inflate;
        stretch.Thesis().params.load = sim::Load::Stretch;
        auto results = MakeLocalEvaluator(2)->EvaluateAll({inflate, stretch});
        inflated = std::move(results[0]);
        stretched = std::move(results[1]);
    } else {
        inflated = MakeLocalEvaluator(1)->EvaluateAll({job}).front();
    }
    const double simulateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();

    std::vector<std::string> written;
    const auto renderStarted = std::chrono::steady_clock::now();
    // Every picture or none (a full disk leaves no part of the set); the videos are made from the
    // frames once they are in place.
    OutputBatch batch;
    std::vector<std::pair<fs::path, fs::path>> videos;  // (frames, mp4)
    const std::string loadName = std::string(sim::ModelOf(job).loadName(job)) + (sim::UnderVacuum(job.def) ? " (vacuum)" : "");
    const std::string title = stored ? fmt::format("archive {}#{}: {}{}  -  {}", stored->experiment.empty() ? "" : stored->experiment + " ", index,
                                                   ShapeTitle(job.shape), stored->label.empty() ? "" : "  (" + stored->label + ")", loadName)
                                     : JobTitle(job);
    if (stored) {
        const fs::path path = out / files.front();
        WritePng(path.string(), renderer->Render(BeforeAfterScene(title, inflated, job, colouring)), p.pngLevel);
        written.push_back(path.string());
    } else {
        DesignFigures figures;
        figures.title = title;
        figures.inflated = &inflated;
        figures.stretched = thesis ? &stretched : nullptr;
        figures.job = job;
        figures.colouring = colouring;
        for (const auto& name : WriteDesignFigures(*renderer, out, figures, p.pngLevel, frameLevel)) written.push_back((out / name).string());
    }

    // Sequences: camera and colour scale fixed over all frames, so only the mesh moves.
    auto sequence = [&](const char* folderName, int frames, auto&& sceneOf) {
        const fs::path folder = out / folderName;
        folders.Create(folder, folderName);
        FrameWriter writer(frameLevel);
        Progress progress(folderName, isatty(STDERR_FILENO), "frames");
        for (int k = 0; k < frames; ++k) {
            writer.Write((folder / fmt::format("frame_{:04}.png", k)).string(), renderer->Render(sceneOf(k)));
            progress.Update(k + 1, frames, k + 1, "");
        }
        writer.Wait();
        written.push_back((folder / "frame_%04d.png").string() + " x " + std::to_string(frames));
        if (video) videos.push_back({folder, out / (std::string(folderName) + ".mp4")});
    };
    if (p.turntable > 0)
        sequence("turntable", p.turntable,
                 [&](int k) { return TurntableScene(title + (sim::UnderVacuum(job.def) ? "  -  under vacuum" : "  -  inflated"), inflated, job, 360.0 * k / p.turntable, colouring); });
    if (p.timelapse > 0 && thesis) WriteThesisTimelapse(job, title, colouring, p, sequence);
    if (p.timelapse > 0 && !thesis) {
        // One frame per converged load step; a run that stopped early shows the steps it reached.
        std::vector<render::Scene> scenes;
        for (int k = 0; k < static_cast<int>(inflated.shell.steps.size()); ++k)
            scenes.push_back(LoadStepScene(title + (sim::UnderVacuum(job.def) ? "  -  under vacuum" : "  -  inflating"), inflated, job, k, colouring));
        if (scenes.empty()) std::cerr << "note: no load step converged (" << sim::Name(inflated.status) << "), so no time-lapse is written\n";
        else {
            ShareFramingAndScale(scenes);
            sequence("timelapse", static_cast<int>(scenes.size()), [&](int k) { return scenes[k]; });
        }
    }
    if (saveVtu) {
        const std::string inflatedFile = stored ? fmt::format("evaluation_{:06}.vtu", index) : std::string("inflated.vtu");
        WriteFileAtomically((out / inflatedFile).string(), FormatVtu(ResultFieldMesh(job, inflated)));
        written.push_back((out / inflatedFile).string());
        if (!stored && thesis) {
            sim::EvalJob stretch = job;
            stretch.Thesis().params.load = sim::Load::Stretch;
            WriteFileAtomically((out / "stretched.vtu").string(), FormatVtu(ResultFieldMesh(stretch, stretched)));
            written.push_back((out / "stretched.vtu").string());
        }
    }
    batch.Commit();
    for (const auto& [frames, mp4] : videos)
        if (EncodeVideo(frames, mp4)) written.push_back(mp4.string());
    const double renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - renderStarted).count();

    Json summary;
    summary["inflation"] = ResultNumbersJson(inflated, job);
    if (!stored && thesis)
        summary["stretch"] = Json{{"status", sim::Name(stretched.status)}, {"fitness", NumberJson(stretched.status == sim::Status::Ok ? stretched.fitness : NAN)}};
    summary["model"] = sim::Name(job.model);
    summary["files"] = written;
    summary["simulated"] = !stored;
    summary["simulate_ms"] = simulateMs;
    summary["render_ms"] = renderMs;
    summary["renderer"] = renderer->Description();
    std::cout << summary.dump() << "\n";
    return 0;
}

static const RegisterCommand kRenderCommand{{"render", "pictures of one design: before/after, stretch, turntable, time-lapse", 20, RunRender}};

}  // namespace app
