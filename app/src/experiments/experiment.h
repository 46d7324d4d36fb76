// Experiment files: one JSON file describes an experiment (the model, a grid, a list of shapes or a
// genetic algorithm, the seed, what to draw, and what the thesis reported). Parsed strictly: an
// unknown key (with the nearest valid one named), a wrong type or an out-of-range value is refused
// with the file, the key and the reason. `--set key.path=value` overrides any key before parsing and
// is checked like the file.
#pragma once

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/batch.h"
#include "sim/model.h"
#include "sim/optimize.h"
#include "sim/search.h"
#include "sim/solver.h"

namespace app {

enum class TurntablePlan { None, Best, All };

struct RenderPlan {
    bool figures = true;                            // landscape / evolution figure and the best design's images
    bool thumbnails = true;                         // a small before/after picture of every evaluation
    TurntablePlan turntable = TurntablePlan::None;  // Best: the best design; All: every grid point, or
                                                    // every member of each GA run's final population
    int turntableFrames = 36;
};

enum class ExperimentKind {
    Sweep,     // a 1-D or 2-D grid of sine parameters (thesis chapter 4)
    Evolve,    // the genetic algorithm (chapter 5)
    Evaluate,  // a list of given shapes, e.g. the stretch tests of chapter 6
    Optimize,  // a pagmo optimizer over a fixed-length genome (the "optimizer" block)
};

struct LabelledShape {
    std::string label;
    sim::Shape shape;
    double thesisFitness = NAN;  // the thesis's number for it, when it reports one
    std::string source;          // that number's table row as the thesis's text extraction has it
};

// What the thesis reports for an experiment, to set our numbers beside (all optional).
struct ThesisResult {
    double bestFitness = NAN;                                 // sweeps: the landscape's best
    std::vector<std::pair<sim::SweepParameter, double>> best;  // sweeps: where it was
    struct Point {
        std::vector<std::pair<sim::SweepParameter, double>> at;  // e.g. amplitude 4, cycles 4
        double fitness = NAN;
        std::string source;  // the table row as the thesis's text extraction has it
    };
    std::vector<Point> points;    // sweeps: named meshes of a table (Table 4.4)
    std::vector<double> runBest;  // GA: best fitness of each run
    // GA: the designs a table prints (Tables 5.2, 5.4, 5.6, 5.8), evaluated in the run and set beside
    // the thesis's number for them and our run's best.
    struct Specimen {
        LabelledShape design;  // label e.g. "Table 5.4 run 1"; thesisFitness the table's fitness
        int run = 0;           // the table's run (mesh) number
        int length = 0;        // the table's genome length column: checked against the genes
    };
    std::vector<Specimen> specimens;
    double meanBest = NAN;        // GA: the mean best fitness the thesis's text states
    std::string meanBestSource;   // and where
    // Sweeps: what the thesis's analysis says of the landscape's shape in words (sections 4.1-4.3),
    // each checked on ours as a row of its own. Over a 2-D sweep of amplitude and cycles.
    struct LandscapeClaim {
        enum class Kind {
            Peaks,          // "peaks of the landscape": the 1-D landscape has `count` local maxima
            RisesWith,      // "cycle counts whose fitness rises with amplitude": at every amplitude step
            CyclesOrder,    // "cycle counts in the thesis's order": the best fitness of each cycle count, ranked
            NegativeCycles  // "cycle counts negative as the thesis says": exactly `cycles` go below zero somewhere
        } kind = Kind::Peaks;
        int count = 0;                                   // Peaks
        std::vector<std::vector<double>> ranks;          // CyclesOrder: best first; one rank's members are not ordered among themselves
        std::vector<std::pair<double, double>> nearly;   // CyclesOrder: pairs the thesis calls nearly equal ("nearly similar")
        std::vector<double> cycles;                      // NegativeCycles
        std::string source;                              // the thesis's words
    };
    std::vector<LandscapeClaim> claims;
    double minutes = NAN;               // sweeps: the thesis's time for the whole sweep
    double secondsPerSimulation = NAN;  // and for one simulation (section 4.1: 6 s on a 2016 MacBook, one thread)
};

// Control points over all splines (0 for other shapes): the thesis's "genome length".
size_t ControlPointCount(const sim::Shape& shape);

// One claim of a thesis table or figure, set beside one of our numbers (a ComparisonRow's quantity)
// in the comparison table at the top of the report. A settings table has `settings` instead.
struct ThesisItem {
    std::string item;      // "Figure 4.1", "Table 5.4"
    std::string quantity;  // our row it is compared with, e.g. "best fitness"
    std::string claim;     // what the thesis says, in words; default: the quantity
    double thesis = NAN;   // default: the row's thesis value
    double tolerance = NAN;  // reproduced when within it; default max(0.02, 5 % of the thesis's value)
    bool atLeast = false;  // the thesis gives a lower bound ("surpassed 3.7"): reproduced when ours is at least it
    std::string figure;    // our picture of it, relative to the experiment's folder
    // Other thesis figures that show the same numbers (Figure 4.2 restates Figure 4.1's peak): one
    // claim, counted once, with their pictures linked beside it.
    struct Also {
        std::string item, figure;
    };
    std::vector<Also> also;
    std::string reading;   // an assumption the thesis's number rests on as read here (Table 5.8's equal split)
    std::string settings;  // a table of settings: what it prescribes (followed; choices where silent are in the note)
};

struct Experiment {
    std::string path;         // where it was read from
    std::string id;           // e.g. "4.1"
    std::string title;        // e.g. "Variable amplitude search"
    std::string thesis;       // where the thesis reports it, e.g. "Table 4.1, Figure 4.1"
    std::string note;         // choices made where the thesis is silent, and why
    std::string explanation;  // why our numbers may differ from the thesis's (shown when they do)
    std::string compare;      // the id of the thesis-model experiment this one re-runs under another model
    ThesisResult thesisResult;
    std::vector<ThesisItem> thesisItems;  // the thesis tables and figures this experiment reproduces
    sim::ModelKind model = sim::kDefaultModel;  // the "model" block's name
    // The model's def: the "model" block (membrane and shell), or the thesis's "sim" and "mesh" blocks.
    sim::ModelDef def = sim::ModelOf(sim::kDefaultModel).defaultDef();
    std::uint64_t seed = 1;
    ExperimentKind kind = ExperimentKind::Sweep;
    sim::SweepDef sweep;
    std::vector<LabelledShape> shapes;  // Evaluate
    sim::GaDef ga;                  // Evolve; under Optimize its genome describes the optimizer's genes
    sim::OptimizerDef optimizer;    // Optimize
    int runs = 1;  // independent GA or optimizer runs, seeds derived from `seed`
    RenderPlan render;
    nlohmann::ordered_json document;  // the file with every --set applied: what DIR/experiment.json holds
};

// What the experiment's plots say and mark (titles, axis labels, the thesis's points, objectives).
struct PlotContext;
PlotContext PlotContextOf(const Experiment& e);

// A --set KEY.PATH=VALUE. VALUE is JSON when it parses as JSON, else a string ("pi/2" is a string
// that number fields read as an expression).
struct Override {
    std::string path;
    std::string value;
};
// "evolve.generations=5" -> {"evolve.generations", "5"}. Throws UsageError.
Override ParseOverride(const std::string& text);

// Reads and validates. Throws UsageError("FILE: 'KEY': reason").
Experiment LoadExperiment(const std::string& path, const std::vector<Override>& overrides = {});
Experiment ParseExperiment(const std::string& text, const std::string& path, const std::vector<Override>& overrides = {});

// The experiment as saved into a results folder, and a short hash of it (FNV-1a over the canonical
// text), stored in checkpoints so that a resume refuses an edited experiment.
std::string ExperimentText(const Experiment& e);
std::string ExperimentHash(const Experiment& e);
// What differs between two saved experiments, as "key: old -> new" (at most a few).
std::string ExperimentDifference(const nlohmann::ordered_json& before, const nlohmann::ordered_json& after);

std::string ExperimentTitle(const Experiment& e);  // "4.1  Variable amplitude search"

// The job that evaluates `shape` under the experiment's model.
sim::EvalJob JobOf(const Experiment& e, const sim::Shape& shape);
// The job a GA genome describes under the experiment's model: its shape and, with fibre genes, its
// fibres; and the genome of an archived GA job (the inverse).
sim::EvalJob JobOfGenome(const Experiment& e, const sim::Genome& genome);
sim::Genome GenomeOfJob(const Experiment& e, const sim::EvalJob& job);
// The mesh a design's per-vertex offsets (free-xy genomes) live on: the thesis helix, or the
// membrane and shell models' rings.
sim::MeshDef DesignMesh(const Experiment& e);  // "4.1  Variable amplitude search"

// The experiment shrunk for a smoke test: at most 3 values per sweep axis, one GA run of 2
// generations of 6, 2000 iterations (thesis model) or a 12 x 16 ring mesh in 2 load steps (the
// others). Same files and figures, in seconds.
Experiment QuickVersion(const Experiment& experiment);

}  // namespace app

template <>
struct sim::EnumNames<app::TurntablePlan> {
    static constexpr std::array<std::pair<app::TurntablePlan, const char*>, 3> table{
        {{app::TurntablePlan::None, "none"}, {app::TurntablePlan::Best, "best"}, {app::TurntablePlan::All, "all"}}};
};
template <>
struct sim::EnumNames<app::ExperimentKind> {
    static constexpr std::array<std::pair<app::ExperimentKind, const char*>, 4> table{{{app::ExperimentKind::Sweep, "sweep"},
                                                                                       {app::ExperimentKind::Evolve, "evolve"},
                                                                                       {app::ExperimentKind::Evaluate, "evaluate"},
                                                                                       {app::ExperimentKind::Optimize, "optimizer"}}};
};
