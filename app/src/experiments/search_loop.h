// One search loop for the GA and every pagmo algorithm (search_loop.cpp). The loop owns what every
// search has: the run folders, the resume cut, per-generation outputs (contact sheet, tables,
// checkpoint, progress), the best of the runs and the end figures. An engine sits behind two small
// adapters: a SearchEngine per experiment (its runs, its comparison rows, its own end figures) and a
// SearchRun per run (step, logbook, population, tables, checkpoint or replay). A new engine is one
// adapter file and one row of SearchEngines().
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/design_cache.h"
#include "experiments/experiment_runner.h"

namespace app {

// A contact sheet's member: the design's key in its run's cache and the caption under it.
struct SheetMember {
    std::string key;
    std::string caption;
};

// The best design of a run, in the engine's first objective (natural units and direction).
struct RunBest {
    double value = NAN;
    std::string key;   // in the run's cache
    sim::EvalJob job;  // the design
};

class SearchRun {
public:
    virtual ~SearchRun() = default;
    // Resume: reads and checks this run's checkpoint, and returns the archive length it describes.
    virtual std::uint64_t Resume(const std::string& text, const std::string& path) = 0;
    // Whether the run had ended before this session (a resume then only redraws).
    virtual bool Ended() const = 0;
    // Runs to the end, from the start or from the checkpoint read; calls `generationDone` after
    // every generation this session adds (0 = the initial population). Wall time is the engine's.
    virtual void Run(const std::function<void()>& generationDone) = 0;

    virtual const std::vector<sim::LogbookRow>& Logbook() const = 0;
    virtual std::vector<SheetMember> Population() const = 0;
    // logbook.csv and the engine's other tables, then the checkpoint (last: a checkpoint always
    // describes files that are already complete).
    virtual void WriteFiles(const std::filesystem::path& dir, std::uint64_t archiveCount) = 0;
    virtual std::optional<RunBest> Best() const = 0;
    virtual DesignCache& Cache() = 0;
};

class SearchEngine {
public:
    virtual ~SearchEngine() = default;
    // "evolve", or the pagmo algorithm's name: progress lines.
    virtual std::string Name() const = 0;
    // A run as sheet titles name it: "run 2", "cmaes run 2".
    virtual std::string RunLabel(int run) const = 0;
    // The engine's run K (1-based). The engine may keep a view of it for Judge and EndFigures; the
    // loop owns it and keeps it alive until the end.
    virtual std::unique_ptr<SearchRun> MakeRun(int run) = 0;
    virtual bool Maximise() const = 0;        // the first objective's direction
    virtual bool MultiObjective() const = 0;  // no evolution plot; fronts instead
    // Elitism keeps the best in every generation: no separate best-so-far line.
    virtual bool KeepsItsBest() const = 0;
    // The budget the progress line counts: generations, population, evaluations (0: none).
    virtual int Generations() const = 0;
    virtual int Population() const = 0;
    virtual long long EvaluationBudget() const = 0;
    // The outcome's rows and details from the finished runs (the thesis's designs beside the GA's).
    virtual void Judge() = 0;
    // Figures only this engine draws, after evolution.png (the thesis's designs beside each run's
    // best; Pareto fronts). `bestRun` is 0-based, -1 when no run found a valid design.
    virtual void EndFigures(int bestRun) = 0;
    // The best design's figure title (the loop adds its fibres).
    virtual std::string BestTitle(int run, const sim::EvalJob& job) const = 0;
};

// The engines, one row each: which experiments it runs and how it is made.
struct SearchEngineRow {
    ExperimentKind kind;
    std::unique_ptr<SearchEngine> (*make)(RunContext& c);
};
const std::vector<SearchEngineRow>& SearchEngines();

// Runs the experiment's search through its engine's row.
void RunSearch(RunContext& c);

// The engines' rows' makers (ga_engine.cpp, pagmo_engine.cpp).
std::unique_ptr<SearchEngine> MakeGaEngine(RunContext& c);
std::unique_ptr<SearchEngine> MakePagmoEngine(RunContext& c);

}  // namespace app
