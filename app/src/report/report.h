// report.md: one section per experiment with its figures and a table of our numbers beside the
// thesis's, explained where they differ markedly. `reproduce` writes one for every thesis
// experiment; `sweep` and `evolve` one for their experiment (folder ".").
#pragma once

#include <string>
#include <vector>

#include "experiments/experiment_runner.h"

namespace app {

struct ReportEntry {
    Experiment experiment;
    ExperimentOutcome outcome;
    std::string folder;  // relative to the report
};

// `chapter`, when given, is inserted before the first experiment that re-runs another under a
// physical model ("compare"): reproduce's part 2. `closing` ends the report (reproduce's part 3,
// anchored "optimizers").
std::string ReportMarkdown(const std::vector<ReportEntry>& entries, bool quick, double seconds, const std::string& evaluator,
                           const std::string& chapter = "", const std::string& closing = "");

// One sentence on the experiment's model and its settings (units included).
std::string ModelDescription(const Experiment& e);

// A row that differs from the thesis: outside its item's tolerance (thesis_check.h's rule, the one
// the item table uses), or the default tolerance when no item names it.
bool RowDiffers(const Experiment& e, const ComparisonRow& row);

}  // namespace app
