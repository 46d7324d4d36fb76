// `actuator sweep` and `actuator evolve`: the thesis's searches, in-process and on all cores.
//
// [SECTION] Shared: options, output folder, progress
// [SECTION] sweep
// [SECTION] evolve
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <unordered_map>

#include "checkpoint.h"
#include "cli_options.h"
#include "commands.h"
#include "experiment.h"
#include "figures.h"
#include "json_writer.h"
#include "mesh_io.h"
#include "render/plot.h"
#include "sim/batch.h"

namespace app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------------------
// [SECTION] Shared
// ---------------------------------------------------------------------------------------------

int ParseThreads(const ParsedArgs& args) {
    return args.Has("threads") ? ParseInt(args.Get("threads"), "--threads", 1, 1024) : sim::HardwareThreads();
}

fs::path PrepareOutput(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir, ec)) throw UsageError("--out: cannot create folder '" + dir + "'");
    CheckOutputPath((fs::path(dir) / "results.csv").string(), "--out");
    return dir;
}

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
    explicit Progress(std::string what) : what_(std::move(what)), start_(Clock::now()), tty_(isatty(STDERR_FILENO)) {}
    void Update(int done, int total, int evaluations, const std::string& detail) {
        const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
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
    bool tty_;
    int lastDecile_ = -1;
};

std::string Csv(double value) {
    if (!std::isfinite(value)) return "";
    return FormatNumber("%.17g", value);
}

std::string AxisLabel(sim::SweepParameter parameter) {
    switch (parameter) {
        case sim::SweepParameter::Amplitude: return "amplitude A";
        case sim::SweepParameter::Cycles: return "cycles n (phase 0 to n pi)";
        case sim::SweepParameter::PhaseEnd: return "phase end (radians)";
    }
    return "";
}

// The best shape's inflation and stretch figures, as in the thesis's "best mesh" figures.
void WriteBestFigures(const fs::path& out, const sim::Shape& shape, const Experiment& e, const std::string& caption) {
    std::string error;
    auto renderer = render::MeshRenderer::Create(render::DefaultRenderDef(), &error);
    if (!renderer) throw UsageError("cannot render: " + error);
    for (const auto& [name, load] : {std::pair{"best_inflation.png", sim::Load::Inflate}, std::pair{"best_stretch.png", sim::Load::Stretch}}) {
        sim::SimParams params = e.params;
        params.load = load;
        const auto result = sim::Evaluate(shape, e.mesh, params);
        const std::string title = caption + "  -  " + (load == sim::Load::Inflate ? "inflation" : "stretch");
        WritePng((out / name).string(), renderer->Render(BeforeAfterScene(title, result, e.mesh)), 6);
    }
}

std::string ExperimentTitle(const Experiment& e) {
    std::string title = e.id.empty() ? fs::path(e.path).stem().string() : e.id;
    if (!e.title.empty()) title += "  " + e.title;
    return title;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// [SECTION] sweep
// ---------------------------------------------------------------------------------------------
namespace {

std::vector<OptionSpec> SweepSpecs() {
    return {
        {"out", "DIR", "", "output folder (created if missing); required"},
        {"threads", "N", "all cores", "evaluation threads; results do not depend on it"},
        {"help", "", "", "show this help"},
    };
}

// An experiment that lists its shapes: each is evaluated under the experiment's load and drawn.
int RunEvaluateList(const Experiment& e, const ParsedArgs& args) {
    const int threads = ParseThreads(args);
    const fs::path out = PrepareOutput(args.Get("out"));
    WriteFileAtomically((out / "experiment.json").string(), e.text);
    std::vector<sim::EvalJob> jobs;
    for (const auto& s : e.shapes) jobs.push_back({s.shape, e.mesh, e.params});
    const auto started = Clock::now();
    Progress progress("evaluate " + ExperimentTitle(e));
    const auto results = sim::EvaluateBatch(jobs, threads, [&](int done, int total) { progress.Update(done, total, done, "shapes"); });
    const double seconds = std::chrono::duration<double>(Clock::now() - started).count();

    std::string csv = "index,label,fitness,contraction_percent,status,iterations,thesis_fitness\n";
    for (size_t j = 0; j < results.size(); ++j)
        csv += std::to_string(j) + ",\"" + e.shapes[j].label + "\"," + Csv(results[j].fitness) + "," + Csv(results[j].contractionPercent) + "," +
               sim::StatusName(results[j].status) + "," + std::to_string(results[j].iterationsRun) + "," + Csv(e.shapes[j].thesisFitness) + "\n";
    WriteFileAtomically((out / "results.csv").string(), csv);
    if (e.render.figures) {
        std::string error;
        auto renderer = render::MeshRenderer::Create(render::DefaultRenderDef(), &error);
        if (!renderer) throw UsageError("cannot render: " + error);
        const char* load = e.params.load == sim::Load::Stretch ? "stretch" : "inflation";
        for (size_t j = 0; j < results.size(); ++j)
            WritePng((out / ("shape_" + std::to_string(j + 1) + ".png")).string(),
                     renderer->Render(BeforeAfterScene(e.shapes[j].label + "  -  " + load, results[j], e.mesh)), 6);
    }
    JsonWriter json;
    json.BeginObject().Key("experiment").String(e.path).Key("shapes").BeginArray();
    for (size_t j = 0; j < results.size(); ++j)
        json.BeginObject().Key("label").String(e.shapes[j].label).Key("status").String(sim::StatusName(results[j].status))
            .Key("fitness").Number(results[j].fitness).Key("thesis_fitness").Number(e.shapes[j].thesisFitness).EndObject();
    json.EndArray().Key("seconds").Number(seconds).Key("threads").Integer(threads).EndObject();
    WriteFileAtomically((out / "summary.json").string(), json.Text() + "\n");
    std::cout << json.Text() << "\n";
    return 0;
}

}  // namespace

std::string SweepHelp() {
    return "usage: actuator sweep EXPERIMENT.json --out DIR [--threads N]\n\n"
           "Evaluates every point of an experiment's 1-D or 2-D grid (see assets/experiments/), or every shape\n"
           "of an experiment that lists them ('evaluate'; then DIR/shape_K.png per shape), and writes\n"
           "  DIR/results.csv       one row per grid point: parameters, fitness, contraction, status\n"
           "  DIR/landscape.png     the fitness landscape: a line plot (1-D) or a heatmap (2-D), best marked\n"
           "  DIR/best_inflation.png, DIR/best_stretch.png   the best shape before and after\n"
           "  DIR/summary.json      the best point and timings (also printed)\n\nOptions:\n" +
           FormatOptions(SweepSpecs());
}

int RunSweep(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, SweepSpecs(), 1);
    if (args.Has("help")) {
        std::cout << SweepHelp();
        return 0;
    }
    if (args.positionals.size() != 1) throw UsageError("expected one experiment file: actuator sweep EXPERIMENT.json --out DIR");
    if (!args.Has("out")) throw UsageError("--out DIR is required");
    if (!args.Has("out")) throw UsageError("--out DIR is required");
    const Experiment e = LoadExperiment(args.positionals[0]);
    if (e.kind == ExperimentKind::Evolve) throw UsageError(e.path + " describes a genetic algorithm: run it with 'actuator evolve'");
    if (e.kind == ExperimentKind::Evaluate) return RunEvaluateList(e, args);
    const int threads = ParseThreads(args);
    const fs::path out = PrepareOutput(args.Get("out"));
    WriteFileAtomically((out / "experiment.json").string(), e.text);

    const auto shapes = sim::SweepShapes(e.sweep);
    std::vector<sim::EvalJob> jobs;
    for (const auto& shape : shapes) jobs.push_back({shape, e.mesh, e.params});
    const auto started = Clock::now();
    Progress progress("sweep " + ExperimentTitle(e));
    const auto results = sim::EvaluateBatch(jobs, threads, [&](int done, int total) { progress.Update(done, total, done, "grid points"); });
    const double seconds = std::chrono::duration<double>(Clock::now() - started).count();

    // results.csv, in grid order (the last axis varies fastest).
    const auto& axes = e.sweep.axes;
    std::string csv = "index";
    for (const auto& axis : axes) csv += std::string(",") + sim::SweepParameterName(axis.parameter);
    csv += ",fitness,contraction_percent,status,iterations\n";
    int best = -1;
    const size_t inner = axes.size() == 2 ? axes[1].values.size() : 1;
    auto axisValue = [&](size_t index, size_t axis) {
        return axes.size() == 1 ? axes[0].values[index] : (axis == 0 ? axes[0].values[index / inner] : axes[1].values[index % inner]);
    };
    for (size_t j = 0; j < results.size(); ++j) {
        csv += std::to_string(j);
        for (size_t a = 0; a < axes.size(); ++a) csv += "," + Csv(axisValue(j, a));
        csv += "," + Csv(results[j].fitness) + "," + Csv(results[j].contractionPercent) + "," + sim::StatusName(results[j].status) + "," +
               std::to_string(results[j].iterationsRun) + "\n";
        if (results[j].status == sim::Status::Ok && (best < 0 || results[j].fitness > results[best].fitness)) best = static_cast<int>(j);
    }
    WriteFileAtomically((out / "results.csv").string(), csv);

    std::string bestText = "no grid point evaluated successfully";
    if (best >= 0) {
        bestText = "best: ";
        for (size_t a = 0; a < axes.size(); ++a) bestText += std::string(a ? ", " : "") + sim::SweepParameterName(axes[a].parameter) + " " + FormatNumber("%.4g", axisValue(best, a));
        bestText += ",  fitness " + FormatNumber("%.4f", results[best].fitness);
    }
    if (e.render.figures) {
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
                heatmap.highlightLabel = bestText + "  (grey: failed)";
            }
            image = plots->RenderHeatmap(title, heatmap);
        }
        WritePng((out / "landscape.png").string(), image, 6);
        if (best >= 0) WriteBestFigures(out, shapes[best], e, ShapeTitle(shapes[best]));
    }

    JsonWriter json;
    json.BeginObject().Key("experiment").String(e.path).Key("points").Integer(static_cast<long long>(results.size()));
    if (best >= 0) {
        json.Key("best").BeginObject().Key("index").Integer(best);
        for (size_t a = 0; a < axes.size(); ++a) json.Key(sim::SweepParameterName(axes[a].parameter)).Number(axisValue(best, a));
        json.Key("fitness").Number(results[best].fitness).Key("contraction_percent").Number(results[best].contractionPercent).EndObject();
    } else {
        json.Key("best").Null();
    }
    int failed = 0;
    for (const auto& r : results) failed += r.status != sim::Status::Ok;
    json.Key("failed").Integer(failed).Key("seconds").Number(seconds).Key("evaluations_per_second").Number(results.size() / seconds);
    json.Key("threads").Integer(threads).EndObject();
    WriteFileAtomically((out / "summary.json").string(), json.Text() + "\n");
    std::cout << json.Text() << "\n";
    return 0;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] evolve
// ---------------------------------------------------------------------------------------------
namespace {

std::vector<OptionSpec> EvolveSpecs() {
    return {
        {"out", "DIR", "", "output folder (created if missing); required unless --resume"},
        {"resume", "DIR", "", "continue an interrupted evolve in DIR from its checkpoints"},
        {"threads", "N", "all cores", "evaluation threads; results do not depend on it"},
        {"help", "", "", "show this help"},
    };
}

// Evaluates genomes on the thread pool, remembering results so that an identical genome is not
// simulated twice within a run. The cache changes speed only: the simulation is deterministic.
class CachedEvaluator {
public:
    CachedEvaluator(const Experiment& e, int threads) : e_(e), threads_(threads) {}

    std::vector<std::pair<double, sim::Status>> operator()(const std::vector<const sim::Genome*>& genomes) {
        std::vector<std::pair<double, sim::Status>> out(genomes.size());
        std::vector<sim::EvalJob> jobs;
        std::vector<size_t> slots;
        std::vector<std::string> keys;
        for (size_t j = 0; j < genomes.size(); ++j) {
            std::string key = sim::GenomeText(*genomes[j]);
            if (auto hit = cache_.find(key); hit != cache_.end()) {
                out[j] = hit->second;
                ++hits_;
                continue;
            }
            jobs.push_back({sim::ShapeOfGenome(*genomes[j], e_.ga.genome, e_.mesh), e_.mesh, e_.params});
            slots.push_back(j);
            keys.push_back(std::move(key));
        }
        const auto results = sim::EvaluateBatch(jobs, threads_);
        for (size_t k = 0; k < results.size(); ++k) {
            out[slots[k]] = {results[k].fitness, results[k].status};
            cache_.emplace(keys[k], out[slots[k]]);
        }
        simulated_ += static_cast<long long>(results.size());
        return out;
    }
    long long Simulated() const { return simulated_; }
    long long Hits() const { return hits_; }

private:
    const Experiment& e_;
    int threads_;
    std::unordered_map<std::string, std::pair<double, sim::Status>> cache_;
    long long simulated_ = 0, hits_ = 0;
};

void WriteRunFiles(const fs::path& dir, const RunCheckpoint& checkpoint) {
    WriteFileAtomically((dir / "logbook.csv").string(), LogbookCsv(checkpoint.state));
    WriteFileAtomically((dir / "best_per_generation.csv").string(), BestPerGenerationCsv(checkpoint.state));
    WriteFileAtomically((dir / "halloffame.csv").string(), HallOfFameCsv(checkpoint.state));
    // Last: a checkpoint always describes files that are already complete.
    WriteFileAtomically((dir / "checkpoint.json").string(), FormatCheckpoint(checkpoint));
}

std::string ReadFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

std::string EvolveHelp() {
    return "usage: actuator evolve EXPERIMENT.json --out DIR [--threads N]\n"
           "       actuator evolve --resume DIR [--threads N]\n\n"
           "Runs an experiment's genetic algorithm (see assets/experiments/): tournament selection, elitism,\n"
           "the thesis's mutation, optional two-point crossover, as many independent runs as the file asks,\n"
           "each with a seed derived from the experiment's seed. Same seed, same bytes, whatever --threads.\n"
           "Writes, per run, DIR/run_K/{logbook.csv, best_per_generation.csv, halloffame.csv, checkpoint.json}\n"
           "(rewritten after every generation), and DIR/evolution.png, DIR/best_inflation.png,\n"
           "DIR/best_stretch.png and DIR/summary.json at the end. An interrupted run continues with --resume.\n\n"
           "Options:\n" + FormatOptions(EvolveSpecs());
}

int RunEvolve(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, EvolveSpecs(), 1);
    if (args.Has("help")) {
        std::cout << EvolveHelp();
        return 0;
    }
    const bool resume = args.Has("resume");
    if (resume && (args.Has("out") || !args.positionals.empty()))
        throw UsageError("--resume DIR takes the experiment and output folder from DIR; give no file or --out with it");
    if (!resume && args.positionals.size() != 1) throw UsageError("expected one experiment file: actuator evolve EXPERIMENT.json --out DIR");
    if (!resume && !args.Has("out")) throw UsageError("--out DIR is required");
    const fs::path out = resume ? fs::path(args.Get("resume")) : PrepareOutput(args.Get("out"));
    if (resume && !fs::exists(out / "experiment.json"))
        throw UsageError("--resume: '" + out.string() + "' holds no experiment.json; is it an evolve output folder?");
    const Experiment e = resume ? ParseExperiment(ReadFile(out / "experiment.json"), (out / "experiment.json").string())
                                : LoadExperiment(args.positionals[0]);
    if (e.kind != ExperimentKind::Evolve) throw UsageError(e.path + " describes no genetic algorithm: run it with 'actuator sweep'");
    if (!resume) WriteFileAtomically((out / "experiment.json").string(), e.text);
    const int threads = ParseThreads(args);

    const auto started = Clock::now();
    long long simulated = 0;
    std::vector<RunCheckpoint> runs;
    for (int r = 0; r < e.runs; ++r) {
        const fs::path dir = out / ("run_" + std::to_string(r + 1));
        fs::create_directories(dir);
        CachedEvaluator evaluate(e, threads);
        const sim::GenomeEvaluator evaluator = [&](const std::vector<const sim::Genome*>& genomes) { return evaluate(genomes); };
        RunCheckpoint checkpoint;
        if (resume && fs::exists(dir / "checkpoint.json")) {
            checkpoint = ParseCheckpoint(ReadFile(dir / "checkpoint.json"), (dir / "checkpoint.json").string());
        } else {
            checkpoint.seed = sim::DeriveSeed(e.seed, static_cast<std::uint64_t>(r));
            checkpoint.state = sim::StartEvolution(e.ga, e.mesh, checkpoint.seed, evaluator);
            WriteRunFiles(dir, checkpoint);
        }
        Progress progress("evolve " + ExperimentTitle(e) + " run " + std::to_string(r + 1) + "/" + std::to_string(e.runs));
        while (checkpoint.state.generation < e.ga.generations) {
            if (!sim::EvolveOneGeneration(e.ga, e.mesh, checkpoint.state, evaluator)) {
                std::cerr << "run " << r + 1 << ": every individual of generation " << checkpoint.state.generation
                          << " failed (nan or diverged); the run stops here\n";
                break;
            }
            WriteRunFiles(dir, checkpoint);
            const auto& row = checkpoint.state.logbook.back();
            progress.Update(checkpoint.state.generation, e.ga.generations, static_cast<int>(evaluate.Simulated()),
                            "best " + FormatNumber("%.4f", row.best) + ", generation");
        }
        simulated += evaluate.Simulated();
        runs.push_back(std::move(checkpoint));
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - started).count();

    // The best individual over all runs.
    int bestRun = -1;
    for (int r = 0; r < e.runs; ++r)
        if (!runs[r].state.hallOfFame.empty() &&
            (bestRun < 0 || runs[r].state.hallOfFame.front().fitness > runs[bestRun].state.hallOfFame.front().fitness))
            bestRun = r;

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
        if (bestRun >= 0) {
            const auto& best = runs[bestRun].state.hallOfFame.front();
            WriteBestFigures(out, sim::ShapeOfGenome(best.genome, e.ga.genome, e.mesh), e,
                             "best of run " + std::to_string(bestRun + 1) + ": " + (e.ga.genome.kind == sim::GenomeKind::BSpline
                                 ? ShapeTitle(sim::ShapeOfGenome(best.genome, e.ga.genome, e.mesh)) : std::string("free-xy")));
        }
    }

    JsonWriter json;
    json.BeginObject().Key("experiment").String(e.path).Key("runs").BeginArray();
    for (int r = 0; r < e.runs; ++r) {
        const auto& s = runs[r].state;
        json.BeginObject().Key("run").Integer(r + 1).Key("seed").String(std::to_string(runs[r].seed)).Key("generations").Integer(s.generation);
        if (!s.hallOfFame.empty())
            json.Key("best_fitness").Number(s.hallOfFame.front().fitness).Key("best_genome").String(sim::GenomeText(s.hallOfFame.front().genome));
        json.EndObject();
    }
    json.EndArray().Key("simulations").Integer(simulated).Key("seconds").Number(seconds);
    json.Key("evaluations_per_second").Number(seconds > 0 ? simulated / seconds : 0).Key("threads").Integer(threads).EndObject();
    WriteFileAtomically((out / "summary.json").string(), json.Text() + "\n");
    std::cout << json.Text() << "\n";
    return 0;
}

}  // namespace app
