// Runs one experiment file's work into a folder and says what came of it: files, timings, and our
// numbers beside the thesis's. Shared by `sweep`, `evolve` and `reproduce`.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "experiment.h"

namespace app {

struct ComparisonRow {
    std::string quantity;  // e.g. "best fitness", "best amplitude", "run 2 best fitness"
    double ours = NAN;
    double thesis = NAN;   // NaN when the thesis gives no number
};

struct ExperimentOutcome {
    std::filesystem::path dir;
    double seconds = 0;
    long long simulations = 0;
    std::vector<std::string> figures;     // files in dir worth showing, in reading order
    std::vector<ComparisonRow> rows;
    std::vector<std::string> details;     // lines such as the best genome of each run
    std::string summaryJson;              // what the command prints
};

class WorkerPool;

struct RunOptions {
    int threads = 0;              // 0: all cores
    bool resume = false;          // evolve: continue from the run folders' checkpoints
    bool progress = true;         // progress lines on stderr
    WorkerPool* workers = nullptr;  // evaluation servers; null: this machine's cores
};

// Throws UsageError on bad input (unwritable folder, no GL context).
ExperimentOutcome RunExperiment(const Experiment& experiment, const std::filesystem::path& out, const RunOptions& options);

// The experiment shrunk for a smoke test: at most 3 values per sweep axis, one GA run of 2
// generations of 6, 2000 iterations. Same files and figures, in seconds.
Experiment QuickVersion(const Experiment& experiment);

std::string ExperimentTitle(const Experiment& e);

}  // namespace app
