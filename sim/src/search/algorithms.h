// pagmo's algorithms as rows of one table: what each is (one objective or several), the smallest
// population pagmo accepts, its parameters with their defaults and ranges, and how to make it.
// Adding an algorithm: its value and name in sim::Algorithm (optimize.h) and its row in
// algorithms.cpp; the runner, resume, logbooks, figures and `compare` need nothing else.
#pragma once

#include <pagmo/algorithm.hpp>
#include <string>
#include <vector>

#include "sim/optimize.h"

namespace sim {

struct AlgorithmParameterRow {
    const char* name;  // as experiment files give it ("parameters": {"sigma0": 0.2})
    double defaultValue;
    double min, max;
    bool integer;
    const char* meaning;
};

struct AlgorithmRow {
    Algorithm id;
    bool multiObjective;     // optimises several objectives at once
    int smallestPopulation;  // pagmo throws below it, mid-run
    std::vector<AlgorithmParameterRow> parameters;
    // One generation per evolve() call, with memory, so that stepping equals one long call; pagmo's
    // own tolerances off: the run's stop criteria decide.
    pagmo::algorithm (*make)(const OptimizerDef& def, unsigned seed);
    // What pagmo would refuse mid-run (or misread) in this algorithm's settings, beyond each
    // parameter's range; empty when they can run. Null: nothing more to check.
    std::string (*error)(const OptimizerDef& def) = nullptr;
};

const std::vector<AlgorithmRow>& AlgorithmRows();
const AlgorithmRow& AlgorithmRowOf(Algorithm id);

}  // namespace sim
