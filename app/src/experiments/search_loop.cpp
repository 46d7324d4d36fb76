// The one search loop: every run of the experiment's engine in its folder DIR/run_K, resumed from
// its checkpoint, with a contact sheet, the tables and a checkpoint after every generation; then
// the best of the runs and the end figures. A resume cuts the archive back to the newest
// checkpoint and continues from it: every output then equals an uninterrupted run's.
#include "experiments/search_loop.h"

#include <fmt/format.h>

#include "experiments/checkpoint.h"
#include "formats/files.h"
#include "pictures/plots.h"
#include "support/errors.h"
#include "support/progress.h"

namespace app {
namespace {

namespace fs = std::filesystem;

const std::vector<SearchEngineRow> kEngines{
    {ExperimentKind::Evolve, MakeGaEngine},
    {ExperimentKind::Optimize, MakePagmoEngine},
};

// Resume: each run's checkpoint read and checked by its engine, a gap before the newest refused,
// the archive cut back to the newest, and each resumed run's cache given back what it evaluated.
// Without --resume: no checkpoints, the archive untouched.
void ResumeRuns(RunContext& c, std::vector<std::unique_ptr<SearchRun>>& runs) {
    if (!c.options.resume) return;
    int newest = 0;  // 1-based run of the newest checkpoint; 0: none
    std::uint64_t archiveCount = 0;
    std::vector<bool> resumed(runs.size(), false);
    for (size_t r = 0; r < runs.size(); ++r) {
        const fs::path path = RunFolder(c, static_cast<int>(r + 1)) / "checkpoint.json";
        std::error_code ec;
        if (!fs::exists(path, ec)) continue;
        archiveCount = runs[r]->Resume(ReadInputFile(path.string()), path.string());
        resumed[r] = true;
        newest = static_cast<int>(r + 1);
    }
    for (int r = 1; r < newest; ++r)
        if (!resumed[r - 1]) throw UsageError("--resume: " + Quote(RunFolder(c, r).string()) + " has no checkpoint, yet a later run has one");
    c.recorder.RollBack(newest ? archiveCount : 0);
    for (size_t r = 0; r < runs.size(); ++r)
        if (resumed[r]) runs[r]->Cache().Restore(c.recorder.Existing());
}

void WriteGenerationSheet(RunContext& c, const fs::path& dir, const std::string& title, SearchRun& run, std::unique_ptr<render::MeshRenderer>& renderer) {
    if (!c.e.render.figures) return;
    std::error_code ec;
    fs::create_directories(dir / "sheets", ec);
    const std::vector<SheetMember> members = run.Population();
    std::vector<std::string> keys;
    for (const SheetMember& m : members) keys.push_back(m.key);
    const std::vector<const sim::SimResult*> meshes = run.Cache().MeshesOf(keys);
    std::vector<SheetEntry> entries;
    for (size_t k = 0; k < members.size(); ++k) entries.push_back({meshes[k], members[k].caption});
    WriteContactSheet(dir / SheetName(run.Logbook().back().generation), title, entries, JobOf(c.e, sim::CylinderShape{}), renderer);
}

void ReportProgress(const SearchEngine& engine, const SearchRun& run, Progress& progress, const Recorder& recorder) {
    const sim::LogbookRow& row = run.Logbook().back();
    // By evaluations when an evaluation budget ends the run first (compare's runs).
    const long long budget = engine.EvaluationBudget();
    const bool byBudget = budget > 0 && budget < static_cast<long long>(engine.Generations() + 1) * engine.Population();
    const std::string unit = byBudget ? "evaluations" : "generation";
    progress.Update(byBudget ? std::min(row.evaluationsSoFar, budget) : row.generation, byBudget ? budget : engine.Generations(), recorder.Simulated(),
                    engine.MultiObjective() ? fmt::format("hypervolume {:.4g}, front {}, {}", row.hypervolume, row.frontSize, unit)
                                            : fmt::format("best {:.4f}, {}", row.bestSoFar, unit));
}

void WriteEvolutionFigure(RunContext& c, const SearchEngine& engine, const std::vector<std::unique_ptr<SearchRun>>& runs) {
    const Experiment& e = c.e;
    std::vector<RunCurve> curves;
    for (size_t r = 0; r < runs.size(); ++r) {
        RunCurve curve{fmt::format("run {}", r + 1), runs[r]->Logbook()};
        curve.showBestSoFar = !engine.KeepsItsBest();
        if (r < e.thesisResult.runBest.size()) {
            curve.reference = e.thesisResult.runBest[r];
            curve.referenceLabel = ThesisBestLegend(e.thesisResult.runBest, runs.size());
        }
        curves.push_back(std::move(curve));
    }
    WritePng((c.dir / "evolution.png").string(), EvolutionImage(PlotContextOf(e), curves), 6);
    c.outcome.figures.push_back("evolution.png");
}

}  // namespace

const std::vector<SearchEngineRow>& SearchEngines() { return kEngines; }

void RunSearch(RunContext& c) {
    const Experiment& e = c.e;
    const auto row = std::find_if(kEngines.begin(), kEngines.end(), [&](const SearchEngineRow& r) { return r.kind == e.kind; });
    if (row == kEngines.end()) throw std::logic_error(std::string("no search engine runs a ") + sim::Name(e.kind) + " experiment");
    const std::unique_ptr<SearchEngine> engine = row->make(c);
    std::vector<std::unique_ptr<SearchRun>> runs;
    for (int r = 1; r <= e.runs; ++r) runs.push_back(engine->MakeRun(r));
    ResumeRuns(c, runs);

    std::unique_ptr<render::MeshRenderer> sheetRenderer;
    for (int r = 1; r <= e.runs; ++r) {
        const fs::path dir = RunFolder(c, r);
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (!fs::is_directory(dir, ec)) throw UsageError("cannot create folder " + Quote(dir.string()));
        SearchRun& run = *runs[r - 1];
        Progress progress(fmt::format("{} {} run {}/{}", engine->Name(), ExperimentTitle(e), r, e.runs), c.options.progress);
        const bool endedBefore = run.Ended();
        run.Run([&] {
            WriteGenerationSheet(c, dir, fmt::format("{}  -  {}, generation {}", ExperimentTitle(e), engine->RunLabel(r), run.Logbook().back().generation), run,
                                 sheetRenderer);
            run.WriteFiles(dir, c.recorder.Count());
            ReportProgress(*engine, run, progress, c.recorder);
        });
        // The last files say why the run ended; a run that had ended before a resume keeps its own.
        if (!endedBefore) run.WriteFiles(dir, c.recorder.Count());
    }

    engine->Judge();
    // The best of all runs in the first objective (the first of equals).
    int bestRun = -1;
    std::optional<RunBest> best;
    for (int r = 0; r < e.runs; ++r) {
        std::optional<RunBest> b = runs[r]->Best();
        if (!b) continue;
        if (!best || (engine->Maximise() ? b->value > best->value : b->value < best->value)) {
            best = std::move(b);
            bestRun = r;
        }
    }
    if (best) {
        c.outcome.bestJob = best->job;
        c.outcome.bestFitness = best->value;
        c.outcome.bestBlockingForceN = c.recorder.ReadBack({runs[bestRun]->Cache().Of(best->key).id}).at(0).result.shell.blockingForceN;
    }
    if (!e.render.figures) return;

    if (!engine->MultiObjective()) WriteEvolutionFigure(c, *engine, runs);
    engine->EndFigures(bestRun);
    for (int r = 0; r < e.runs; ++r) {
        const std::string sheet = "run_" + std::to_string(r + 1) + "/" + SheetName(runs[r]->Logbook().back().generation);
        std::error_code ec;
        if (fs::exists(c.dir / sheet, ec)) c.outcome.figures.push_back(sheet);
    }
    if (e.render.turntable == TurntablePlan::All) {
        // Every member of each run's final population turning (all evaluations would be thousands).
        for (int r = 0; r < e.runs; ++r) {
            const std::vector<SheetMember> population = runs[r]->Population();
            for (size_t k = 0; k < population.size(); ++k) {
                const fs::path folder = RunFolder(c, r + 1) / "final_population" / ("individual_" + std::to_string(k + 1));
                std::error_code ec;
                fs::create_directories(folder, ec);
                const ArchiveRecord record = c.recorder.ReadBack({runs[r]->Cache().Of(population[k].key).id}).at(0);
                WriteBestFigures(c, folder, record.job, record.result, fmt::format("run {}, individual {}", r + 1, k + 1), e.render.turntableFrames, false);
            }
        }
    }
    if (best) {
        const ArchiveRecord record = c.recorder.ReadBack({runs[bestRun]->Cache().Of(best->key).id}).at(0);
        std::string title = engine->BestTitle(bestRun + 1, record.job);
        const std::string fibres = FibreTitle(record.job);
        if (!fibres.empty()) title += ",  " + fibres;
        WriteBestFigures(c, c.dir, record.job, record.result, title, e.render.turntable == TurntablePlan::None ? 0 : e.render.turntableFrames, true);
    }
}

}  // namespace app
