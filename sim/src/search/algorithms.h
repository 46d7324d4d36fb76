// pagmo's algorithms as rows of one table: what each is (one objective or several), the smallest
// population pagmo accepts, and its parameters with their defaults and ranges. The table needs no
// pagmo (the commands check a file against it without loading the optimizer module); how to make
// each algorithm is MakeAlgorithm's (optimize_pagmo.cpp, in the module that links pagmo).
// Adding an algorithm: its value and name in sim::Algorithm (optimize.h), its row in algorithms.cpp
// and its case in MakeAlgorithm; the runner, resume, logbooks, figures and `compare` need nothing else.
#pragma once

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
    // What pagmo would refuse mid-run (or misread) in this algorithm's settings, beyond each
    // parameter's range; empty when they can run. Null: nothing more to check.
    std::string (*error)(const OptimizerDef& def) = nullptr;
};

const std::vector<AlgorithmRow>& AlgorithmRows();
const AlgorithmRow& AlgorithmRowOf(Algorithm id);

}  // namespace sim
