// Runs one experiment into a results folder and says what came of it: files, timings, and our
// numbers beside the thesis's. RunExperiment is a dispatcher; each kind has its own file
// (run_sweep.cpp, run_list.cpp; the GA and the optimizers share search_loop.cpp). Shared by sweep, evolve and reproduce.
#pragma once

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "support/errors.h"
#include "evaluation/evaluator.h"
#include "experiments/experiment.h"
#include "formats/files.h"
#include "evaluation/recorder.h"
#include "pictures/figures.h"
#include "formats/results_folder.h"

namespace app {

struct ComparisonRow {
    std::string quantity;  // e.g. "best fitness", "best amplitude", "run 2 best fitness"
    double ours = NAN;
    double thesis = NAN;   // NaN when the thesis gives no number
    // Why ours differs, computed from the run's own numbers (thesis_check.h's sentences), and whether
    // that accounts for the difference.
    std::string why{};
    bool explained = false;
};

struct ExperimentOutcome {
    std::filesystem::path dir;
    double seconds = 0;
    long long simulations = 0;          // this session's
    long long evaluations = 0;          // in the archive, earlier sessions of a resumed run included
    std::vector<std::string> figures;   // files in dir worth showing, in reading order
    std::vector<ComparisonRow> rows;
    std::optional<sim::EvalJob> bestJob;  // the best design found (sweeps and GA runs), with its fitness
    double bestFitness = NAN;
    double bestBlockingForceN = NAN;  // membrane and shell: the best design's held force (NaN when it has none)
    std::vector<std::string> details;   // lines such as the best genome of each run
    std::string meshCheckJson;          // with RunOptions::meshCheck: the best design at twice the mesh, as JSON
    std::string tables;                 // markdown tables beside the rows (the thesis's designs against ours)
    std::string summaryJson;            // what the command prints
};

struct RunOptions {
    Evaluator* evaluator = nullptr;      // where every simulation runs
    bool resume = false;                 // continue from the folder's archive and checkpoints
    bool progress = true;                // progress lines on stderr
    ResultsFolder* folder = nullptr;     // told of the first complete result (--overwrite)
    bool meshCheck = false;              // physical models: the best design again at twice the mesh (mesh_check.h)
};

// Throws UsageError on bad input (an edited experiment on resume, an unwritable folder, no GL).
ExperimentOutcome RunExperiment(const Experiment& experiment, const std::filesystem::path& out, const RunOptions& options);

// What the kinds share while they run.
struct RunContext {
    const Experiment& e;
    std::filesystem::path dir;
    const RunOptions& options;
    Recorder& recorder;
    ExperimentOutcome& outcome;
};

// A GA or optimizer run's folder, DIR/run_K (1-based).
std::filesystem::path RunFolder(const RunContext& c, int run);
// A generation's contact sheet inside its run's folder: sheets/generation_NNN.png.
std::string SheetName(int generation);

void RunSweep(RunContext& c);
void RunList(RunContext& c);
void RunSearch(RunContext& c);  // the GA and the optimizers: search_loop.cpp

// The best design's figures (its inflation result is given). Under the thesis model also the stretch
// test, evaluated and archived as a figure evaluation; under the membrane and shell models the
// contraction-pressure curve. A turntable when the experiment asks.
void WriteBestFigures(RunContext& c, const std::filesystem::path& folder, const sim::EvalJob& job, const sim::SimResult& inflated,
                      const std::string& title, int turntableFrames, bool listInOutcome);

}  // namespace app
