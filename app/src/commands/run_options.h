// The options every experiment command shares (sweep, evolve, reproduce): where results go and
// whether they continue or replace an earlier run, --set overrides, and where evaluations run
// (--threads on this machine, --workers on evaluation servers).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "options/cli.h"
#include "evaluation/evaluator.h"
#include "experiments/experiment.h"
#include "formats/results_folder.h"

namespace app {

struct RunCommandOptions {
    std::string out;                 // --out DIR
    std::string resume;              // --resume [DIR]: "" not given; "." given without a folder
    bool overwrite = false;
    int threads = 0;                 // 0: every core
    std::string workers;
    double workerTimeoutSeconds = 300;
    std::vector<std::string> sets;   // --set KEY.PATH=VALUE, repeatable
};

void AddRunOptions(Cli& cli, RunCommandOptions& options);

// The results folder the options name, and its mode. Throws UsageError for --resume with
// --overwrite, a missing --out, or --out and --resume DIR naming different folders.
std::string ResultsDir(const Cli& cli, const RunCommandOptions& options);
FolderMode ResultsMode(const Cli& cli, const RunCommandOptions& options);

std::vector<Override> Overrides(const RunCommandOptions& options);

// The evaluator the options ask for: this machine's threads, or the --workers pool.
std::unique_ptr<Evaluator> MakeEvaluator(const Cli& cli, const RunCommandOptions& options);

}  // namespace app
