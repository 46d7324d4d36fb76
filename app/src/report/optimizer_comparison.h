// Optimizers side by side on one problem: each contender (a GA or optimizer experiment) run with
// the same seeds 1..N to the same evaluation budget, each run a complete results folder of its
// own; then the best-so-far against evaluations, the median of the seeds as a line and their
// range shaded, in DIR/comparison.png, with DIR/comparison.csv and a report section.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "evaluation/evaluator.h"
#include "experiments/experiment.h"
#include "formats/results_folder.h"

namespace app {

struct ComparisonDef {
    int seeds = 5;             // runs per contender, seeds 1..seeds
    long long budget = 300;    // evaluations per run (each stops at the first generation that reaches it)
    std::string linkPrefix;    // what the report's links start with: "" in DIR/report.md, "optimizers/" one level up
};

struct ContenderResult {
    std::string label;                 // the experiment's id and algorithm
    std::vector<double> finalBest;     // per seed: the best at the end of the run
    std::vector<long long> evaluations;  // per seed: evaluations the run used
    std::vector<std::vector<std::pair<double, double>>> curves;  // per seed: (evaluations, best so far)
};

struct ComparisonResult {
    std::vector<ContenderResult> contenders;
    std::vector<std::string> figures;  // relative to the folder
    std::string markdown;              // a report section
    double seconds = 0;
};

// Every contender must be one-objective, on the same model and judged by the same fitness (the GA's
// is the thesis fitness under the thesis model and contraction under the others). Throws
// UsageError naming the first that is not.
void CheckContenders(const std::vector<Experiment>& contenders);

// The contender as run for seed k: one run, seed k, stopping at the budget.
Experiment ContenderRun(const Experiment& contender, int seed, long long budget);

// Runs what is missing (a run with a summary.json is done; one with a run.json is resumed) and draws.
ComparisonResult CompareOptimizers(const std::vector<Experiment>& contenders, const ComparisonDef& def, const std::filesystem::path& dir,
                                   Evaluator& evaluator, ResultsFolder* folder, bool resume, bool progress);

}  // namespace app
