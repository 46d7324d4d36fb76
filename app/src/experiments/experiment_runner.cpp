#include "pictures/figures.h"
#include "formats/json_out.h"
#include "experiments/experiment_runner.h"

#include "evaluation/mesh_check.h"

#include <fmt/format.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "support/errors.h"
#include "formats/files.h"

namespace app {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// DIR/run.json: what the folder was started with, so that a resume under an edited experiment is
// refused, naming what changed. It also holds the model's settings as this version resolved them
// (defaults included): a resume by a version whose defaults differ would mix two models' results.
void CheckOrRecordExperiment(const Experiment& e, const fs::path& dir, bool resume) {
    const fs::path path = dir / "run.json";
    const Json model = ModelJson(sim::EvalJob{sim::CylinderShape{}, e.model, e.def});
    if (!resume) {
        WriteFileAtomically((dir / "experiment.json").string(), ExperimentText(e));
        WriteFileAtomically(path.string(),
                            Json{{"experiment_hash", ExperimentHash(e)}, {"experiment", e.document}, {"model", model}}.dump(2) + "\n");
        return;
    }
    std::error_code ec;
    if (!fs::exists(path, ec)) throw UsageError("--resume: " + Quote(dir.string()) + " holds no run.json; it was not made by this version");
    Json run;
    try {
        run = ParseJson(ReadInputFile(path.string()), path.string());
        if (run.at("experiment_hash").get<std::string>() == ExperimentHash(e)) {
            // Folders from before the model was recorded resume as they did (nothing to check).
            if (!run.contains("model") || run.at("model") == model) return;
            const std::string changed = ExperimentDifference(run.at("model"), model);
            throw UsageError("--resume: " + Quote(dir.string()) + " was started by a version of actuator whose " + sim::Name(e.model) +
                             " model's defaults differ from this one's (" + (changed.empty() ? std::string("its settings differ") : changed) +
                             "): its results and new ones would not be of one model; start afresh with --overwrite");
        }
    } catch (const Json::exception&) {
        throw UsageError(Quote(path.string()) + " is damaged; start afresh with --overwrite");
    }
    const std::string changed = ExperimentDifference(run.at("experiment"), e.document);
    throw UsageError("--resume: " + Quote((dir / "experiment.json").string()) + " changed since the run started (" +
                     (changed.empty() ? std::string("its text differs") : changed) + "); put it back, or start afresh with --overwrite");
}

std::string SummaryJson(const Experiment& e, const ExperimentOutcome& o) {
    Json rows = Json::array();
    for (const auto& row : o.rows)
        rows.push_back(Json{{"quantity", row.quantity},
                            {"ours", std::isfinite(row.ours) ? Json(row.ours) : Json(nullptr)},
                            {"thesis", std::isfinite(row.thesis) ? Json(row.thesis) : Json(nullptr)}});
    Json summary{{"experiment", ExperimentTitle(e)},
                 {"results", rows},
                 {"details", o.details},
                 {"figures", o.figures},
                 {"simulations", o.simulations},
                 {"seconds", o.seconds},
                 {"evaluations_per_second", o.seconds > 0 ? o.simulations / o.seconds : 0.0}};
    if (!o.meshCheckJson.empty()) summary["mesh_check"] = Json::parse(o.meshCheckJson);
    return summary.dump();
}

}  // namespace

// The best design again at twice the mesh (clamps the same length): its contraction, how far it
// moved and the rule's verdict, in summary.json and a line of the report.
static void CheckBestMesh(RunContext& c) {
    const sim::EvalJob fine = RefinedJob(*c.outcome.bestJob);
    const sim::SimResult r = c.recorder.EvaluateOne(fine, {Role::Figure, 0, -1, "mesh check of the best design"});
    Json check = MeshCheckJson(c.outcome.bestFitness, fine, r, c.outcome.bestBlockingForceN);
    // The report's line reads the verdict MeshCheckJson reached: a difference only where both meshes gave one.
    std::string line =
        check["difference_points"].is_number()
            ? fmt::format("mesh check of the best design: {:+.3f} % here, {:+.3f} % at twice the mesh ({}), {:.3f} points ({:.1f} %) apart: {}",
                          c.outcome.bestFitness, r.contractionPercent, check["mesh"].get<std::string>(), check["difference_points"].get<double>(),
                          check["relative_difference_percent"].get<double>(),
                          check["converged"].get<bool>() ? "converged by the mesh rule" : "outside the mesh rule, so not yet converged")
            : fmt::format("mesh check of the best design: at twice the mesh it is {}", sim::Name(r.status));
    if (check.contains("blocking_force_n") && check["blocking_force_n"].is_number())
        line += fmt::format("; its held force {:.4g} N here, {:.4g} N at twice the mesh: {}", c.outcome.bestBlockingForceN,
                            check["blocking_force_n"].get<double>(),
                            check["blocking_force_converged"].get<bool>() ? "converged by the force rule" : "outside the force rule");
    c.outcome.details.push_back(line);
    check["best_contraction_percent"] = std::isfinite(c.outcome.bestFitness) ? Json(c.outcome.bestFitness) : Json(nullptr);
    c.outcome.meshCheckJson = check.dump();
}

std::string SheetName(int generation) { return fmt::format("sheets/generation_{:03}.png", generation); }

fs::path RunFolder(const RunContext& c, int run) { return c.dir / ("run_" + std::to_string(run)); }

ExperimentOutcome RunExperiment(const Experiment& e, const fs::path& out, const RunOptions& options) {
    CheckOrRecordExperiment(e, out, options.resume);
    ExperimentOutcome outcome;
    outcome.dir = out;
    const auto started = std::chrono::steady_clock::now();
    Recorder recorder(out, e.id, *options.evaluator, e.render.thumbnails, options.resume, options.folder);
    RunContext context{e, out, options, recorder, outcome};
    switch (e.kind) {
        case ExperimentKind::Sweep: RunSweep(context); break;
        case ExperimentKind::Evaluate: RunList(context); break;
        case ExperimentKind::Evolve:
        case ExperimentKind::Optimize: RunSearch(context); break;
    }
    if (options.meshCheck && outcome.bestJob && sim::ModelOf(*outcome.bestJob).physical) CheckBestMesh(context);
    outcome.simulations = recorder.Simulated();
    outcome.evaluations = static_cast<long long>(recorder.Count());
    outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    outcome.summaryJson = SummaryJson(e, outcome);
    WriteFileAtomically((out / "summary.json").string(), outcome.summaryJson + "\n");
    return outcome;
}

void WriteBestFigures(RunContext& c, const fs::path& folder, const sim::EvalJob& job, const sim::SimResult& inflated, const std::string& title,
                      int turntableFrames, bool listInOutcome) {
    // The thesis's stretch test (chapter 6) belongs to its model; the membrane and shell models show
    // their contraction-pressure curve instead (in the inflated result).
    std::optional<sim::SimResult> stretched;
    if (job.model == sim::ModelKind::Thesis) {
        sim::EvalJob stretch = job;
        stretch.Thesis().params.load = sim::Load::Stretch;
        stretched = c.recorder.EvaluateOne(stretch, {Role::Figure, 0, -1, "stretch test of: " + title});
    }
    auto renderer = MakeRenderer(1024, 768);
    DesignFigures figures;
    figures.title = title;
    figures.inflated = &inflated;
    figures.stretched = stretched ? &*stretched : nullptr;
    figures.job = job;
    figures.turntableFrames = turntableFrames;
    figures.prefix = "best_";
    const auto written = WriteDesignFigures(*renderer, folder, figures);
    if (listInOutcome)
        for (const auto& name : written)
            if (name.find("turntable") == std::string::npos) c.outcome.figures.push_back(name);
}

}  // namespace app
