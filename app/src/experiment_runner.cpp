// [SECTION] Shared: progress, figures, contact sheets
// [SECTION] Sweeps
// [SECTION] Lists of shapes
// [SECTION] Genetic algorithm
// [SECTION] Entry points
#include "experiment_runner.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "archive.h"
#include "checkpoint.h"
#include "cli_options.h"
#include "figures.h"
#include "json_writer.h"
#include "mesh_io.h"
#include "remote.h"
#include "render/mesh_renderer.h"
#include "render/plot.h"
#include "sim/batch.h"

namespace app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------------------
// [SECTION] Shared
// ---------------------------------------------------------------------------------------------

double Seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

std::string Duration(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "?";
    const long s = std::lround(seconds);
    char text[32];
    std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
    return text;
}

// One line on stderr, rewritten in place on a terminal; in a log, about every 10% of the work.
class Progress {
public:
    Progress(std::string what, bool enabled) : what_(std::move(what)), start_(Clock::now()), tty_(isatty(STDERR_FILENO)), enabled_(enabled) {}
    void Update(int done, int total, long long evaluations, const std::string& detail) {
        if (!enabled_) return;
        const double seconds = Seconds(start_);
        const double rate = seconds > 0 ? evaluations / seconds : 0;
        const double left = done > 0 ? seconds * (total - done) / done : NAN;
        const int decile = total > 0 ? 10 * done / total : 10;
        if (!tty_ && decile == lastDecile_ && done != total) return;
        lastDecile_ = decile;
        std::fprintf(stderr, "%s%s: %d/%d, %.1f evaluations/s, %s, %s left%s", tty_ ? "\r\033[K" : "", what_.c_str(), done, total, rate,
                     detail.c_str(), Duration(left).c_str(), tty_ && done != total ? "" : "\n");
        std::fflush(stderr);
    }

private:
    std::string what_;
    Clock::time_point start_;
    bool tty_, enabled_;
    int lastDecile_ = -1;
};

std::string Csv(double value) { return std::isfinite(value) ? FormatNumber("%.17g", value) : ""; }

std::string AxisLabel(sim::SweepParameter parameter) {
    switch (parameter) {
        case sim::SweepParameter::Amplitude: return "amplitude A";
        case sim::SweepParameter::Cycles: return "cycles n (phase 0 to n pi)";
        case sim::SweepParameter::PhaseEnd: return "phase end (radians)";
    }
    return "";
}

std::unique_ptr<render::MeshRenderer> MakeRenderer(int width, int height, int supersample = 2, double textScale = 0) {
    render::RenderDef def = render::DefaultRenderDef();
    def.width = width;
    def.height = height;
    def.supersample = supersample;
    def.textScale = textScale;
    std::string error;
    auto renderer = render::MeshRenderer::Create(def, &error);
    if (!renderer) throw UsageError("cannot render: " + error);
    return renderer;
}

// The best shape's inflation and stretch figures (thesis Figures 4.2, 4.4, 4.6, 5.2, ...), and its
// turntable when the experiment asks for one.
void WriteBestFigures(const fs::path& out, const sim::Shape& shape, const Experiment& e, const std::string& caption,
                      ExperimentOutcome& outcome) {
    auto renderer = MakeRenderer(1024, 768);
    sim::SimResult inflated;
    for (const auto& [name, load] : {std::pair{"best_inflation.png", sim::Load::Inflate}, std::pair{"best_stretch.png", sim::Load::Stretch}}) {
        sim::SimParams params = e.params;
        params.load = load;
        const auto result = sim::Evaluate(shape, e.mesh, params);
        if (load == sim::Load::Inflate) inflated = result;
        const std::string title = caption + "  -  " + (load == sim::Load::Inflate ? "inflation" : "stretch");
        WritePng((out / name).string(), renderer->Render(BeforeAfterScene(title, result, e.mesh)), 6);
        outcome.figures.push_back(name);
    }
    if (e.render.turntable == TurntablePlan::None) return;
    const fs::path folder = out / "turntable_best";
    fs::create_directories(folder);
    for (int k = 0; k < e.render.turntableFrames; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d.png", k);
        WritePng((folder / name).string(), renderer->Render(TurntableScene(caption, inflated, e.mesh, 360.0 * k / e.render.turntableFrames)), 1);
    }
}

// Every mesh of a sweep or a generation in one picture: inflated, one camera and colour scale,
// fitness under each. Failed evaluations show their last finite state, captioned with the status.
struct SheetEntry {
    const sim::SimResult* result;
    std::string caption;
};

// `renderer` is kept between calls and made anew only when the sheet's size changes: a GA run
// draws a sheet of the same size every generation, and a renderer costs ~17 ms to create.
void WriteContactSheet(const fs::path& path, const std::string& title, const std::vector<SheetEntry>& entries, const sim::MeshDef& mesh,
                       std::unique_ptr<render::MeshRenderer>& renderer) {
    if (entries.empty()) return;
    // Actuators are about ten times taller than wide: many narrow columns, cells about 1:2.
    const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(entries.size() * 3.0))));
    const int rows = static_cast<int>((entries.size() + columns - 1) / columns);
    const int width = std::clamp(columns * 125 + 110, 800, 2600), height = std::clamp(rows * 250 + 110, 450, 2400);
    if (!renderer || renderer->Def().width != width || renderer->Def().height != height)
        renderer = MakeRenderer(width, height, 1, /*textScale=*/0.72);
    render::Scene scene;
    scene.mesh = mesh;
    scene.title = title;
    scene.columns = columns;
    std::vector<const sim::Positions*> all;
    for (const auto& entry : entries) {
        scene.panels.push_back({entry.result->final, entry.result->initial, entry.caption, 0});
        if (entry.result->status == sim::Status::Ok) all.push_back(&entry.result->final);
    }
    if (!all.empty()) scene.framing = render::FrameMeshes(all);
    WritePng(path.string(), renderer->Render(scene), 1);
}

// A small before/after picture of one evaluated mesh, for browsing every evaluation of a search.
class ThumbnailWriter {
public:
    ThumbnailWriter(fs::path folder, const sim::MeshDef& mesh) : folder_(std::move(folder)), mesh_(mesh) {
        fs::create_directories(folder_);
        render::RenderDef def = render::DefaultRenderDef();
        def.width = 240;
        def.height = 180;
        def.supersample = 1;
        def.overlay = false;
        std::string error;
        renderer_ = render::MeshRenderer::Create(def, &error);
        if (!renderer_) throw UsageError("cannot render: " + error);
    }
    void Write(const std::string& name, const sim::SimResult& result) {
        render::Scene scene;
        scene.mesh = mesh_;
        scene.panels = {{result.initial, {}, "", 0}, {result.final, result.initial, "", 0}};
        WritePng((folder_ / name).string(), renderer_->Render(scene), 1);
    }

private:
    fs::path folder_;
    sim::MeshDef mesh_;
    std::unique_ptr<render::MeshRenderer> renderer_;
};

std::string FitnessCaption(const sim::SimResult& r) {
    return r.status == sim::Status::Ok ? FormatNumber("%.3f", r.fitness) : std::string(sim::StatusName(r.status));
}

// On the evaluation servers when there are any, else on this machine's cores: same results.
std::vector<sim::SimResult> EvaluateJobs(const RunOptions& options, const std::vector<sim::EvalJob>& jobs, const sim::BatchProgress& progress = {}) {
    if (options.workers) return options.workers->Evaluate(jobs, progress);
    return sim::EvaluateBatch(jobs, options.threads, progress);
}

ArchivedEvaluation Record(const Experiment& e, const sim::SimResult& r, const sim::Shape& shape, std::string label, int run = 0,
                          int generation = -1) {
    ArchivedEvaluation a;
    a.experiment = e.id;
    a.run = run;
    a.generation = generation;
    a.label = std::move(label);
    a.shape = shape;
    a.params = e.params;
    a.mesh = e.mesh;
    SetResult(a, r);
    return a;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Sweeps
// ---------------------------------------------------------------------------------------------

double ParameterOf(const sim::Shape& shape, const std::string& name);

// A grid point's parameters, e.g. "amplitude=3.48 cycles=6" (names) or "3.48 6" (values only).
std::string PointLabel(const sim::Shape& shape, const std::vector<sim::SweepAxis>& axes, bool withNames, const char* format) {
    std::string label;
    for (const auto& axis : axes) {
        const char* name = sim::SweepParameterName(axis.parameter);
        label += (label.empty() ? "" : " ") + (withNames ? std::string(name) + "=" : std::string()) + FormatNumber(format, ParameterOf(shape, name));
    }
    return label;
}

double ParameterOf(const sim::Shape& shape, const std::string& name) {
    auto read = [&](const auto& s) {
        if (name == "amplitude") return s.amplitude;
        if (name == "cycles") return (s.phaseEnd - s.phaseStart) / std::numbers::pi;
        return s.phaseEnd;
    };
    if (const auto* s = std::get_if<sim::SineShape>(&shape)) return read(*s);
    if (const auto* a = std::get_if<sim::AbsSineShape>(&shape)) return read(*a);
    return NAN;
}

sim::Shape WithParameters(sim::Shape shape, const std::vector<std::pair<std::string, double>>& at) {
    for (const auto& [name, value] : at) {
        sim::SweepAxis axis;
        axis.parameter = name == "amplitude" ? sim::SweepParameter::Amplitude : name == "cycles" ? sim::SweepParameter::Cycles : sim::SweepParameter::PhaseEnd;
        axis.values = {value};
        shape = sim::SweepShapes(sim::SweepDef{shape, {axis}}).front();
    }
    return shape;
}

void RunSweep(const Experiment& e, const fs::path& out, const RunOptions& options, ArchiveWriter& archive, ExperimentOutcome& outcome) {
    const auto shapes = sim::SweepShapes(e.sweep);
    std::vector<sim::EvalJob> jobs;
    for (const auto& shape : shapes) jobs.push_back({shape, e.mesh, e.params});
    Progress progress("sweep " + ExperimentTitle(e), options.progress);
    double bestSoFar = NAN;
    const auto results = EvaluateJobs(options, jobs, [&](int done, int total, const sim::SimResult& finished) {
        if (finished.status == sim::Status::Ok && !(finished.fitness <= bestSoFar)) bestSoFar = finished.fitness;
        progress.Update(done, total, done, "best so far " + FormatNumber("%.4f", bestSoFar) + ", grid points");
    });
    outcome.simulations += static_cast<long long>(results.size());

    const auto& axes = e.sweep.axes;
    std::string csv = "index";
    for (const auto& axis : axes) csv += std::string(",") + sim::SweepParameterName(axis.parameter);
    csv += ",fitness,contraction_percent,status,iterations\n";
    int best = -1;
    for (size_t j = 0; j < results.size(); ++j) {
        csv += std::to_string(j);
        for (const auto& axis : axes) csv += "," + Csv(ParameterOf(shapes[j], sim::SweepParameterName(axis.parameter)));
        csv += "," + Csv(results[j].fitness) + "," + Csv(results[j].contractionPercent) + "," + sim::StatusName(results[j].status) + "," +
               std::to_string(results[j].iterationsRun) + "\n";
        if (results[j].status == sim::Status::Ok && (best < 0 || results[j].fitness > results[best].fitness)) best = static_cast<int>(j);
    }
    WriteFileAtomically((out / "results.csv").string(), csv);
    for (size_t j = 0; j < results.size(); ++j) archive.Append(Record(e, results[j], shapes[j], PointLabel(shapes[j], axes, true, "%.6g")));

    std::string bestText = "no grid point evaluated successfully";
    if (best >= 0) {
        bestText = "best: ";
        for (size_t a = 0; a < axes.size(); ++a)
            bestText += std::string(a ? ", " : "") + sim::SweepParameterName(axes[a].parameter) + " " +
                        FormatNumber("%.4g", ParameterOf(shapes[best], sim::SweepParameterName(axes[a].parameter)));
        bestText += ",  fitness " + FormatNumber("%.4f", results[best].fitness);
        outcome.rows.push_back({"best fitness", results[best].fitness, e.thesisResult.bestFitness});
        for (const auto& axis : axes) {
            const std::string name = sim::SweepParameterName(axis.parameter);
            double thesis = NAN;
            for (const auto& [key, value] : e.thesisResult.best) if (key == name) thesis = value;
            outcome.rows.push_back({"best " + name, ParameterOf(shapes[best], name), thesis});
        }
    }
    // Meshes the thesis names in a table (e.g. Table 4.4), evaluated as it states them.
    for (const auto& point : e.thesisResult.points) {
        const auto result = sim::Evaluate(WithParameters(e.sweep.base, point.at), e.mesh, e.params);
        ++outcome.simulations;
        std::string name;
        for (const auto& [key, value] : point.at) name += (name.empty() ? "" : ", ") + key + " " + FormatNumber("%g", value);
        outcome.rows.push_back({"fitness at " + name, result.fitness, point.fitness});
    }

    if (!e.render.figures) return;
    std::string error;
    auto plots = render::PlotRenderer::Create(1024, 640, &error);
    if (!plots) throw UsageError("cannot render: " + error);
    const std::string title = ExperimentTitle(e) + "  -  fitness landscape";
    render::Image image;
    if (axes.size() == 1) {
        render::LinePlot plot;
        plot.xLabel = AxisLabel(axes[0].parameter);
        plot.yLabel = "fitness (contraction, mesh units)";
        plot.zeroLine = true;
        render::LineSeries series{"fitness after " + std::to_string(e.params.iterations) + " iterations", axes[0].values, {}, {0.13f, 0.35f, 0.75f}, true};
        for (const auto& r : results) series.y.push_back(r.fitness);
        plot.series.push_back(series);
        if (best >= 0) {
            plot.highlight = std::pair{axes[0].values[best], results[best].fitness};
            plot.highlightLabel = bestText;
        }
        image = plots->RenderLines(title, {plot});
    } else {
        render::Heatmap heatmap;
        heatmap.xLabel = AxisLabel(axes[1].parameter);
        heatmap.yLabel = AxisLabel(axes[0].parameter);
        heatmap.valueLabel = "fitness";
        heatmap.xValues = axes[1].values;
        heatmap.yValues = axes[0].values;
        for (const auto& r : results) heatmap.values.push_back(r.fitness);
        if (best >= 0) {
            heatmap.highlight = static_cast<size_t>(best);
            const bool anyFailed = std::any_of(results.begin(), results.end(), [](const sim::SimResult& r) { return r.status != sim::Status::Ok; });
            heatmap.highlightLabel = bestText + (anyFailed ? "  (grey cells: failed evaluations)" : "");
        }
        image = plots->RenderHeatmap(title, heatmap);
    }
    WritePng((out / "landscape.png").string(), image, 6);
    outcome.figures.push_back("landscape.png");
    std::vector<SheetEntry> entries;
    for (size_t j = 0; j < results.size(); ++j)
        entries.push_back({&results[j], PointLabel(shapes[j], axes, false, "%.3g") + ": " + FitnessCaption(results[j])});
    std::unique_ptr<render::MeshRenderer> sheetRenderer;
    WriteContactSheet(out / "contact_sheet.png", ExperimentTitle(e) + "  -  every grid point, inflated", entries, e.mesh, sheetRenderer);
    ThumbnailWriter thumbnails(out / "thumbnails", e.mesh);
    for (size_t j = 0; j < results.size(); ++j) {
        char name[32];
        std::snprintf(name, sizeof name, "point_%04zu.png", j);
        thumbnails.Write(name, results[j]);
    }
    outcome.figures.push_back("contact_sheet.png");
    if (best >= 0) WriteBestFigures(out, shapes[best], e, ShapeTitle(shapes[best]), outcome);
    if (e.render.turntable == TurntablePlan::All) {
        // Every grid point turning: heavy, so only on request.
        for (size_t j = 0; j < results.size(); ++j) {
            Experiment one = e;
            one.render.turntable = TurntablePlan::Best;
            ExperimentOutcome ignored;
            const fs::path folder = out / ("point_" + std::to_string(j));
            fs::create_directories(folder);
            WriteBestFigures(folder, shapes[j], one, ShapeTitle(shapes[j]), ignored);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Lists of shapes
// ---------------------------------------------------------------------------------------------

void RunList(const Experiment& e, const fs::path& out, const RunOptions& options, ArchiveWriter& archive, ExperimentOutcome& outcome) {
    std::vector<sim::EvalJob> jobs;
    for (const auto& s : e.shapes) jobs.push_back({s.shape, e.mesh, e.params});
    Progress progress("evaluate " + ExperimentTitle(e), options.progress);
    const auto results = EvaluateJobs(options, jobs, [&](int done, int total, const sim::SimResult&) { progress.Update(done, total, done, "shapes"); });
    outcome.simulations += static_cast<long long>(results.size());
    std::string csv = "index,label,fitness,contraction_percent,status,iterations,thesis_fitness\n";
    for (size_t j = 0; j < results.size(); ++j) {
        csv += std::to_string(j) + ",\"" + e.shapes[j].label + "\"," + Csv(results[j].fitness) + "," + Csv(results[j].contractionPercent) + "," +
               sim::StatusName(results[j].status) + "," + std::to_string(results[j].iterationsRun) + "," + Csv(e.shapes[j].thesisFitness) + "\n";
        outcome.rows.push_back({e.shapes[j].label, results[j].fitness, e.shapes[j].thesisFitness});
        archive.Append(Record(e, results[j], e.shapes[j].shape, e.shapes[j].label));
    }
    WriteFileAtomically((out / "results.csv").string(), csv);
    if (!e.render.figures) return;
    auto renderer = MakeRenderer(1024, 768);
    const char* load = e.params.load == sim::Load::Stretch ? "stretch" : "inflation";
    for (size_t j = 0; j < results.size(); ++j) {
        const std::string name = "shape_" + std::to_string(j + 1) + ".png";
        WritePng((out / name).string(), renderer->Render(BeforeAfterScene(e.shapes[j].label + "  -  " + load, results[j], e.mesh)), 6);
        outcome.figures.push_back(name);
    }
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Genetic algorithm
// ---------------------------------------------------------------------------------------------

// Evaluates genomes on the thread pool. Remembers every result so that an identical genome is not
// simulated twice within a run (the cache changes speed only: the simulation is deterministic),
// and keeps the meshes of the current generation for its contact sheet.
class CachedEvaluator {
public:
    CachedEvaluator(const Experiment& e, const RunOptions& options, const fs::path& runDir, int run, ArchiveWriter& archive)
        : e_(e), options_(options), runDir_(runDir), run_(run), archive_(archive) {
        if (e.render.figures) thumbnails_ = std::make_unique<ThumbnailWriter>(runDir / "thumbnails", e.mesh);
    }

    // Generation whose offspring the next call evaluates (for the evaluation log).
    void SetGeneration(int generation) { generation_ = generation; }

    std::vector<std::pair<double, sim::Status>> operator()(const std::vector<const sim::Genome*>& genomes) {
        std::vector<std::pair<double, sim::Status>> out(genomes.size());
        std::vector<sim::EvalJob> jobs;
        std::vector<size_t> slots;
        std::vector<std::string> keys;
        for (size_t j = 0; j < genomes.size(); ++j) {
            std::string key = sim::GenomeText(*genomes[j]);
            if (auto hit = fitness_.find(key); hit != fitness_.end()) {
                out[j] = hit->second;
                continue;
            }
            jobs.push_back({sim::ShapeOfGenome(*genomes[j], e_.ga.genome, e_.mesh), e_.mesh, e_.params});
            slots.push_back(j);
            keys.push_back(std::move(key));
        }
        auto results = EvaluateJobs(options_, jobs);
        for (size_t k = 0; k < results.size(); ++k) {
            out[slots[k]] = {results[k].fitness, results[k].status};
            fitness_.emplace(keys[k], out[slots[k]]);
            // Every simulation is logged and pictured once: evaluations.csv and thumbnails/ belong together.
            const long long number = simulated_ + static_cast<long long>(k) + 1;
            char name[40];
            std::snprintf(name, sizeof name, "evaluation_%05lld.png", number);
            log_ += std::to_string(number) + "," + std::to_string(generation_) + "," + Csv(results[k].fitness) + "," +
                    sim::StatusName(results[k].status) + "," + (thumbnails_ ? std::string(name) : std::string()) + ",\"" + keys[k] + "\"\n";
            if (thumbnails_) thumbnails_->Write(name, results[k]);
            archive_.Append(Record(e_, results[k], jobs[k].shape, "run " + std::to_string(run_) + " evaluation " + std::to_string(number),
                                   run_, generation_));
            meshes_[keys[k]] = std::move(results[k]);
        }
        simulated_ += static_cast<long long>(results.size());
        return out;
    }

    // The simulated meshes of a population, re-simulating any not kept (after a resume); then the
    // kept meshes are trimmed to this population.
    std::vector<const sim::SimResult*> MeshesOf(const std::vector<sim::Individual>& population) {
        std::map<std::string, sim::SimResult> kept;
        std::vector<const sim::SimResult*> out;
        for (const auto& individual : population) {
            const std::string key = sim::GenomeText(individual.genome);
            if (!kept.count(key)) {
                auto found = meshes_.find(key);
                kept[key] = found != meshes_.end() ? std::move(found->second)
                                                   : sim::Evaluate(sim::ShapeOfGenome(individual.genome, e_.ga.genome, e_.mesh), e_.mesh, e_.params);
            }
        }
        meshes_.clear();
        for (auto& [key, result] : kept) meshes_.emplace(key, std::move(result));
        for (const auto& individual : population) out.push_back(&meshes_.at(sim::GenomeText(individual.genome)));
        return out;
    }

    long long Simulated() const { return simulated_; }

    // Appends this session's evaluations to run_K/evaluations.csv. A resumed run starts a new
    // session; evaluations of a generation cut off by the interruption may appear twice.
    void FlushLog() {
        const fs::path path = runDir_ / "evaluations.csv";
        const bool fresh = !fs::exists(path);
        std::ofstream file(path, std::ios::app);
        if (fresh) file << "evaluation,generation,fitness,status,thumbnail,genome\n";
        file << log_;
        log_.clear();
    }

private:
    const Experiment& e_;
    const RunOptions& options_;
    fs::path runDir_;
    int run_;
    ArchiveWriter& archive_;
    std::unique_ptr<ThumbnailWriter> thumbnails_;
    int generation_ = 0;
    std::string log_;
    std::unordered_map<std::string, std::pair<double, sim::Status>> fitness_;
    std::unordered_map<std::string, sim::SimResult> meshes_;
    long long simulated_ = 0;
};

void WriteRunFiles(const fs::path& dir, const RunCheckpoint& checkpoint) {
    WriteFileAtomically((dir / "logbook.csv").string(), LogbookCsv(checkpoint.state));
    WriteFileAtomically((dir / "best_per_generation.csv").string(), BestPerGenerationCsv(checkpoint.state));
    WriteFileAtomically((dir / "halloffame.csv").string(), HallOfFameCsv(checkpoint.state));
    // Last: a checkpoint always describes files that are already complete.
    WriteFileAtomically((dir / "checkpoint.json").string(), FormatCheckpoint(checkpoint));
}


void WriteGenerationSheet(const fs::path& runDir, const Experiment& e, int run, CachedEvaluator& evaluate, const sim::GaState& state,
                          std::unique_ptr<render::MeshRenderer>& renderer) {
    if (!e.render.figures) return;
    fs::create_directories(runDir / "sheets");
    const auto meshes = evaluate.MeshesOf(state.population);
    std::vector<SheetEntry> entries;
    for (const sim::SimResult* mesh : meshes) entries.push_back({mesh, FitnessCaption(*mesh)});
    char name[40];
    std::snprintf(name, sizeof name, "generation_%03d.png", state.generation);
    WriteContactSheet(runDir / "sheets" / name,
                      ExperimentTitle(e) + "  -  run " + std::to_string(run + 1) + ", generation " + std::to_string(state.generation), entries, e.mesh,
                      renderer);
}

void RunEvolution(const Experiment& e, const fs::path& out, const RunOptions& options, ArchiveWriter& archive, ExperimentOutcome& outcome) {
    std::vector<RunCheckpoint> runs;
    for (int r = 0; r < e.runs; ++r) {
        const fs::path dir = out / ("run_" + std::to_string(r + 1));
        fs::create_directories(dir);
        CachedEvaluator evaluate(e, options, dir, r + 1, archive);
        std::unique_ptr<render::MeshRenderer> sheetRenderer;
        const sim::GenomeEvaluator evaluator = [&](const std::vector<const sim::Genome*>& genomes) { return evaluate(genomes); };
        RunCheckpoint checkpoint;
        Progress progress("evolve " + ExperimentTitle(e) + " run " + std::to_string(r + 1) + "/" + std::to_string(e.runs), options.progress);
        if (options.resume && fs::exists(dir / "checkpoint.json")) {
            checkpoint = ParseCheckpoint(ReadTextFile((dir / "checkpoint.json").string()), (dir / "checkpoint.json").string());
        } else {
            checkpoint.seed = sim::DeriveSeed(e.seed, static_cast<std::uint64_t>(r));
            checkpoint.state = sim::StartEvolution(e.ga, e.mesh, checkpoint.seed, evaluator);
            WriteGenerationSheet(dir, e, r, evaluate, checkpoint.state, sheetRenderer);
            WriteRunFiles(dir, checkpoint);
        }
        evaluate.FlushLog();
        while (checkpoint.state.generation < e.ga.generations) {
            evaluate.SetGeneration(checkpoint.state.generation + 1);
            if (!sim::EvolveOneGeneration(e.ga, e.mesh, checkpoint.state, evaluator)) {
                std::cerr << "run " << r + 1 << ": every individual of generation " << checkpoint.state.generation
                          << " failed (nan or diverged); the run stops here\n";
                break;
            }
            WriteGenerationSheet(dir, e, r, evaluate, checkpoint.state, sheetRenderer);
            evaluate.FlushLog();
            WriteRunFiles(dir, checkpoint);
            progress.Update(checkpoint.state.generation, e.ga.generations, evaluate.Simulated(),
                            "best " + FormatNumber("%.4f", checkpoint.state.logbook.back().best) + ", generation");
        }
        outcome.simulations += evaluate.Simulated();
        runs.push_back(std::move(checkpoint));
    }

    int bestRun = -1;
    for (int r = 0; r < e.runs; ++r) {
        const auto& s = runs[r].state;
        const double best = s.hallOfFame.empty() ? NAN : s.hallOfFame.front().fitness;
        outcome.rows.push_back({"run " + std::to_string(r + 1) + " best fitness", best,
                                r < static_cast<int>(e.thesisResult.runBest.size()) ? e.thesisResult.runBest[r] : NAN});
        if (!s.hallOfFame.empty()) {
            outcome.details.push_back("run " + std::to_string(r + 1) + " (seed " + std::to_string(runs[r].seed) + "): best genome " +
                                      (e.ga.genome.kind == sim::GenomeKind::BSpline ? "[" + sim::GenomeText(s.hallOfFame.front().genome) + "]"
                                                                                    : std::string("of ") + std::to_string(s.hallOfFame.front().genome[0].size()) + " offsets"));
            if (bestRun < 0 || best > runs[bestRun].state.hallOfFame.front().fitness) bestRun = r;
        }
    }

    if (e.render.figures) {
        std::string error;
        auto plots = render::PlotRenderer::Create(std::min(2400, 560 * e.runs + 200), 640, &error);
        if (!plots) throw UsageError("cannot render: " + error);
        std::vector<render::LinePlot> panels;
        for (int r = 0; r < e.runs; ++r) {
            render::LinePlot plot;
            plot.title = "run " + std::to_string(r + 1) + " (seed " + std::to_string(runs[r].seed) + ")";
            plot.xLabel = "generation";
            plot.yLabel = "fitness";
            render::LineSeries bestLine{"best", {}, {}, {0.10f, 0.55f, 0.20f}}, worstLine{"worst", {}, {}, {0.80f, 0.20f, 0.15f}},
                meanLine{"mean", {}, {}, {0.13f, 0.35f, 0.75f}};
            render::Band band{"mean +/- std", {}, {}, {}, {0.13f, 0.35f, 0.75f}};
            for (const auto& row : runs[r].state.logbook) {
                const double g = row.generation;
                bestLine.x.push_back(g); bestLine.y.push_back(row.best);
                worstLine.x.push_back(g); worstLine.y.push_back(row.worst);
                meanLine.x.push_back(g); meanLine.y.push_back(row.mean);
                band.x.push_back(g); band.low.push_back(row.mean - row.stddev); band.high.push_back(row.mean + row.stddev);
            }
            plot.bands = {band};
            plot.series = {bestLine, meanLine, worstLine};
            if (!runs[r].state.logbook.empty()) {
                const auto& last = runs[r].state.logbook.back();
                plot.highlight = std::pair{double(last.generation), last.best};
                plot.highlightLabel = "best " + FormatNumber("%.4f", last.best);
            }
            panels.push_back(plot);
        }
        WritePng((out / "evolution.png").string(), plots->RenderLines(ExperimentTitle(e) + "  -  evolution", panels), 6);
        outcome.figures.push_back("evolution.png");
        for (int r = 0; r < e.runs; ++r) {
            char name[64];
            std::snprintf(name, sizeof name, "run_%d/sheets/generation_%03d.png", r + 1, runs[r].state.generation);
            if (fs::exists(out / name)) outcome.figures.push_back(name);
        }
        if (e.render.turntable == TurntablePlan::All) {
            // Every member of each run's final population turning (all evaluations would be thousands).
            for (int r = 0; r < e.runs; ++r) {
                Experiment one = e;
                one.render.turntable = TurntablePlan::Best;
                const auto& population = runs[r].state.population;
                for (size_t k = 0; k < population.size(); ++k) {
                    ExperimentOutcome ignored;
                    const fs::path folder = out / ("run_" + std::to_string(r + 1)) / "final_population" / ("individual_" + std::to_string(k + 1));
                    fs::create_directories(folder);
                    const sim::Shape shape = sim::ShapeOfGenome(population[k].genome, e.ga.genome, e.mesh);
                    WriteBestFigures(folder, shape, one, "run " + std::to_string(r + 1) + ", individual " + std::to_string(k + 1), ignored);
                }
            }
        }
        if (bestRun >= 0) {
            const auto& best = runs[bestRun].state.hallOfFame.front();
            const sim::Shape shape = sim::ShapeOfGenome(best.genome, e.ga.genome, e.mesh);
            WriteBestFigures(out, shape, e,
                             "best of run " + std::to_string(bestRun + 1) + ": " +
                                 (e.ga.genome.kind == sim::GenomeKind::BSpline ? ShapeTitle(shape) : std::string("free-xy offsets")),
                             outcome);
        }
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// [SECTION] Entry points
// ---------------------------------------------------------------------------------------------

std::string ExperimentTitle(const Experiment& e) {
    std::string title = e.id.empty() ? fs::path(e.path).stem().string() : e.id;
    if (!e.title.empty()) title += "  " + e.title;
    return title;
}

Experiment QuickVersion(const Experiment& experiment) {
    Experiment e = experiment;
    e.params.iterations = std::min(e.params.iterations, 2000);
    for (auto& axis : e.sweep.axes)
        if (axis.values.size() > 3) axis.values = {axis.values.front(), axis.values[axis.values.size() / 2], axis.values.back()};
    e.runs = 1;
    e.ga.population = std::min(e.ga.population, 6);
    e.ga.elite = std::min(e.ga.elite, 1);
    e.ga.generations = std::min(e.ga.generations, 2);
    e.thesisResult.points.clear();
    e.render.turntableFrames = std::min(e.render.turntableFrames, 4);
    return e;
}

ExperimentOutcome RunExperiment(const Experiment& e, const fs::path& out, const RunOptions& options) {
    std::error_code ec;
    fs::create_directories(out, ec);
    if (!fs::is_directory(out, ec)) throw UsageError("cannot create folder '" + out.string() + "'");
    CheckOutputPath((out / "summary.json").string(), "output folder");
    if (!options.resume) WriteFileAtomically((out / "experiment.json").string(), e.text);

    ExperimentOutcome outcome;
    outcome.dir = out;
    const auto started = Clock::now();
    // Every simulated shape, with its meshes, for `actuator inspect` and `render --from`.
    ArchiveWriter archive((out / "evaluations.capnp").string());
    switch (e.kind) {
        case ExperimentKind::Sweep: RunSweep(e, out, options, archive, outcome); break;
        case ExperimentKind::Evaluate: RunList(e, out, options, archive, outcome); break;
        case ExperimentKind::Evolve: RunEvolution(e, out, options, archive, outcome); break;
    }
    outcome.seconds = Seconds(started);

    JsonWriter json;
    json.BeginObject().Key("experiment").String(e.path).Key("results").BeginArray();
    for (const auto& row : outcome.rows)
        json.BeginObject().Key("quantity").String(row.quantity).Key("ours").Number(row.ours).Key("thesis").Number(row.thesis).EndObject();
    json.EndArray().Key("details").BeginArray();
    for (const auto& line : outcome.details) json.String(line);
    json.EndArray().Key("figures").BeginArray();
    for (const auto& figure : outcome.figures) json.String(figure);
    json.EndArray().Key("simulations").Integer(outcome.simulations).Key("seconds").Number(outcome.seconds);
    json.Key("evaluations_per_second").Number(outcome.seconds > 0 ? outcome.simulations / outcome.seconds : 0).EndObject();
    outcome.summaryJson = json.Text();
    WriteFileAtomically((out / "summary.json").string(), outcome.summaryJson + "\n");
    return outcome;
}

}  // namespace app
