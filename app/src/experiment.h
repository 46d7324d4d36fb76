// Experiment files: one JSON file describes a thesis experiment (shape family, grid or genome,
// load, iterations, optimizer settings, seed, what to render). Parsed strictly: an unknown key, a
// wrong type or an out-of-range value is refused with the file, the key and the reason.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "sim/search.h"
#include "sim/solver.h"

namespace app {

enum class TurntablePlan { None, Best, All };

struct RenderPlan {
    bool figures = true;                          // landscape / evolution figure and the best shape's images
    TurntablePlan turntable = TurntablePlan::None;  // Best: the best shape; All: every grid point, or
                                                    // every member of each GA run's final population
    int turntableFrames = 36;
};

enum class ExperimentKind {
    Sweep,     // a 1-D or 2-D grid of sine parameters (thesis chapter 4)
    Evolve,    // the genetic algorithm (chapter 5)
    Evaluate,  // a list of given shapes, e.g. the stretch tests of chapter 6
};

struct LabelledShape {
    std::string label;
    sim::Shape shape;
    double thesisFitness = NAN;  // the thesis's number for it, when it reports one
};

// What the thesis reports for an experiment, to set our numbers beside (all optional).
struct ThesisResult {
    double bestFitness = NAN;                    // sweeps: the landscape's best
    std::vector<std::pair<std::string, double>> best;  // sweeps: where it was, e.g. {"amplitude", 4.1}
    struct Point {
        std::vector<std::pair<std::string, double>> at;  // sweep parameters, e.g. amplitude 4, cycles 4
        double fitness = NAN;
    };
    std::vector<Point> points;                   // sweeps: named meshes of a table (Table 4.4)
    std::vector<double> runBest;                 // GA: best fitness of each run
};

struct Experiment {
    std::string path;           // where it was read from
    std::string text;           // the file as read (copied into the output folder)
    std::string id;             // e.g. "4.1"
    std::string title;          // e.g. "Variable amplitude search"
    std::string thesis;         // where the thesis reports it, e.g. "Table 4.1, Figure 4.1"
    std::string note;           // choices made where the thesis is silent, and why
    ThesisResult thesisResult;
    std::string explanation;    // why our numbers may differ from the thesis's (shown when they do)
    sim::MeshDef mesh;
    sim::SimParams params;
    std::uint64_t seed = 1;
    ExperimentKind kind = ExperimentKind::Sweep;
    sim::SweepDef sweep;
    std::vector<LabelledShape> shapes;  // Evaluate
    sim::GaDef ga;
    int runs = 1;               // independent GA runs, seeds derived from `seed`
    RenderPlan render;
};

// Reads and validates. Throws UsageError("FILE: KEY: reason").
Experiment LoadExperiment(const std::string& path);
Experiment ParseExperiment(const std::string& text, const std::string& path);

}  // namespace app
