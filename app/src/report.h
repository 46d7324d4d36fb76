// report.md for `actuator reproduce`: one section per thesis experiment with its figures and a
// table of our numbers beside the thesis's, explained where they differ markedly.
#pragma once

#include <string>
#include <vector>

#include "experiment_runner.h"

namespace app {

struct ReportEntry {
    Experiment experiment;
    ExperimentOutcome outcome;
    std::string folder;  // relative to the report
};

std::string ReportMarkdown(const std::vector<ReportEntry>& entries, bool quick, double seconds, const std::string& evaluator);

// A difference worth explaining: more than 10% of the thesis's value and more than 0.05 apart.
bool MarkedlyDifferent(double ours, double thesis);

}  // namespace app
