// Optimizers beside the thesis's GA: CMA-ES, xNES, DE, SaDE, PSO (pagmo's generational pso_gen)
// for one objective, NSGA-II and MOEA/D for several, all from pagmo2, over fixed-length real genomes. Like the GA: plain data, and
// evaluation is a callback, so the caller chooses threads, workers, caching and archives. pagmo is
// an implementation detail of optimize_pagmo.cpp (its headers carry Eigen, which must be built with
// the flags Debian's libpagmo was built with): nothing here includes it.
//
// Each generation is run twice on copies: first with a recording problem that only collects the
// designs the algorithm asks for, which are then evaluated as one batch by the callback (so both
// cores and every worker are busy even for algorithms that evaluate one design at a time), then for
// real, answered from those results. An answer the first pass did not foresee is evaluated on its
// own: the result never depends on the foresight, only the speed does.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sim/batch.h"
#include "sim/names.h"
#include "sim/search.h"

namespace sim {

enum class Algorithm { Cmaes, Xnes, De, Sade, Pso, Nsga2, Moead, Sga };

// True for the algorithms that optimise several objectives at once (NSGA-II, MOEA/D).
bool IsMultiObjective(Algorithm algorithm);

// What a design is judged by. Each has a natural direction (contraction up, stretch down) that an
// experiment may reverse.
enum class ObjectiveKind {
    Contraction,     // percent at the target pressure, + shorter (every model)
    ThesisFitness,   // the thesis model's fitness, mesh units (thesis model)
    StretchFitness,  // the thesis's stretch test (chapter 6): fitness under the pull load instead of
                     // inflation, mesh units, + less elongation (thesis model; a second simulation)
    BlockingForce,   // N, + pulls on the supports (membrane, shell)
    AxialStiffness,  // N/mm at the free equilibrium (membrane, shell)
    MaxStretch,      // largest principal stretch of the wall (membrane, shell)
    VolumeChange,    // percent of the rest volume at the target pressure (membrane, shell)
    LimitMargin,     // how far the pressure maximum lies above the target, as a fraction of it, from a
                     // second inflation to twice the target: 1 when none is met by then (membrane, shell)
    Twist,           // |the top's turn|, deg, at the target: a muscle that pulls straight (membrane, shell; a top that may turn)
    ForceAtStroke,   // N, the isobaric force with the top held at the load's stroke_percent, + pulls on the
                     // supports (membrane, shell; load blocked)
    WorkPerGram,     // mJ/g, the work of one stroke at the target pressure (the isobaric curve's area) per gram
                     // of the wall's silicone (membrane, shell; load inflate with isobaric points, a density)
    ForcePerGram,    // N/g, the blocking force per gram of the wall's silicone (membrane, shell; a density)
};

struct Objective {
    ObjectiveKind kind = ObjectiveKind::Contraction;
    bool maximise = true;
};
bool MaximisedByDefault(ObjectiveKind kind);
// Empty when the model produces this objective; otherwise why not.
std::string ObjectiveError(ObjectiveKind kind, ModelKind model);
// Empty when the study's settings give the objective a meaning; otherwise why not (force_at_stroke
// needs the top held at a stroke, twist a top that may turn).
std::string ObjectiveDefError(ObjectiveKind kind, const ModelDef& def);
// The objective's value in a result (NaN when the result's status is not Ok). StretchFitness and
// LimitMargin read `second`, the design's second evaluation (NaN without one): its stretch test, or
// its inflation to twice the target pressure.
double ObjectiveValue(ObjectiveKind kind, const SimResult& result, const SimResult* second = nullptr);
// Which second evaluation of every design an objective needs.
enum class SecondEvaluation { None, StretchTest, TwiceThePressure };
SecondEvaluation SecondEvaluationOf(const std::vector<Objective>& objectives);
// "contraction, %" and the like, for axes and column headers.
const char* ObjectiveUnit(ObjectiveKind kind);

// Fixed-length real genomes for every shape family. Integer genes (the thesis's B-spline control
// points) and on/off genes (fibre families) are real in the algorithm and rounded in
// DesignOfVector, the one place that reads a vector.
enum class VectorFamily {
    Sine,     // amplitude, phase start, phase end (a gene whose bounds are equal is fixed, not a gene)
    AbsSine,  // the same for |sin|
    BSpline,  // `splines` x `controlPoints` control points, rounded onto the genome's control grid (controlMin to controlMax in controlStep)
    FreeXY,   // a (dx, dy) offset per vertex in [-bound, bound]
};

struct VectorGenomeDef {
    VectorFamily family = VectorFamily::BSpline;
    // B-spline region, sectors, control point range, free-xy bound and the fibre genes: as the GA's.
    GenomeDef genes;
    int controlPoints = 8;  // B-spline: control points per spline (the GA's vary in length; here fixed)
    std::array<double, 2> amplitude{0.5, 10};                  // sine: bounds of A, mesh units
    std::array<double, 2> phaseStart{0.5, 0.5};                // radians (equal: fixed)
    std::array<double, 2> phaseEnd{3.141592653589793 - 0.5, 3.141592653589793 - 0.5};
};

// The genome's bounds, gene by gene; the genes' names ("amplitude", "spline1.c3", "fibre_angle1").
std::pair<std::vector<double>, std::vector<double>> VectorBounds(const VectorGenomeDef& def, const MeshDef& mesh);
std::vector<std::string> VectorGeneNames(const VectorGenomeDef& def, const MeshDef& mesh);

// What a vector describes: the shape, and the fibre genes as a GA genome's extra list (empty when
// the genome has none; FibresOfGenome reads it).
struct VectorDesign {
    Shape shape;
    Genome genome;  // B-spline and free-xy: the GA genome it equals; sine: the fibre list alone
};
VectorDesign DesignOfVector(const VectorGenomeDef& def, const std::vector<double>& x, const MeshDef& mesh);

// An algorithm's parameters: pagmo's, by name, each with its default, range and meaning in one table.
struct AlgorithmParameter {
    Algorithm algorithm;
    const char* name;
    double defaultValue;
    double min, max;
    bool integer;
    const char* meaning;
};
const std::vector<AlgorithmParameter>& AlgorithmParameters();

struct OptimizerDef {
    Algorithm algorithm = Algorithm::Cmaes;
    int population = 16;                        // designs per generation
    int generations = 20;                       // generations after the initial population (the first stop)
    std::map<std::string, double> parameters;   // given values; the rest from AlgorithmParameters()
    std::vector<Objective> objectives{Objective{}};
    VectorGenomeDef genome;
    StopDef stop;
};

// The parameter's value: the given one, else the table's default.
double ParameterValue(const OptimizerDef& def, const char* name);
// Empty when usable; otherwise what is wrong (population too small for the algorithm, objectives
// the model does not produce or too many for the algorithm, reversed bounds), for a user to read.
std::string OptimizerDefError(const OptimizerDef& def, ModelKind model, const MeshDef& mesh);

// [SECTION] A run ---------------------------------------------------------------------------------

// One design's evaluation, as the callback returns it: the objectives' values in their natural
// units (NaN when the status is not Ok).
struct DesignScore {
    std::vector<double> values;
    Status status = Status::Ok;
};
using VectorEvaluator = std::function<std::vector<DesignScore>(const std::vector<std::vector<double>>& xs)>;

struct EvaluatedDesign {
    std::vector<double> x;
    DesignScore score;
    int generation = 0;  // when it was first asked for
};

struct OptimizerRun {
    std::vector<LogbookRow> logbook;
    std::vector<EvaluatedDesign> evaluated;  // every distinct design, in the order first asked
    std::vector<std::vector<double>> population;  // the last generation's members (vectors)
    std::vector<size_t> hallOfFame;  // one objective: indices into `evaluated`, best first (at most 10)
    std::vector<size_t> front;       // several: the non-dominated valid designs, by the first objective
    std::vector<double> referencePoint;  // several: the hypervolume's, minimised form (fixed at generation 0)
    std::string stopReason;              // "generations", "evaluations", "target", "stagnation", "stopped", "no valid design"
    int unforeseen = 0;                  // designs evaluated one by one (the recording pass missed them)
};

// Called after every generation (0 = the initial population) with the run so far; returning false
// stops the run (reason "stopped": wall time, an interrupt).
using GenerationHook = std::function<bool(const OptimizerRun& run)>;

// Runs the optimizer. Same seed, same run: the callback may evaluate in any order on any threads.
OptimizerRun RunOptimizer(const OptimizerDef& def, const MeshDef& mesh, std::uint64_t seed, const VectorEvaluator& evaluate,
                          const GenerationHook& onGeneration);

// Minimised form: maximised objectives negated; failed designs get kFailedPenalty in every one.
constexpr double kFailedPenalty = 1e9;
std::vector<double> MinimisedForm(const OptimizerDef& def, const DesignScore& score);

// Indices of the non-dominated points (minimised form), in input order.
std::vector<size_t> NonDominated(const std::vector<std::vector<double>>& points);

template <>
struct EnumNames<Algorithm> {
    static constexpr std::array<std::pair<Algorithm, const char*>, 8> table{{{Algorithm::Cmaes, "cmaes"},
                                                                             {Algorithm::Xnes, "xnes"},
                                                                             {Algorithm::De, "de"},
                                                                             {Algorithm::Sade, "sade"},
                                                                             {Algorithm::Pso, "pso"},
                                                                             {Algorithm::Nsga2, "nsga2"},
                                                                             {Algorithm::Moead, "moead"},
                                                                             {Algorithm::Sga, "sga"}}};
};
template <>
struct EnumNames<ObjectiveKind> {
    static constexpr std::array<std::pair<ObjectiveKind, const char*>, 12> table{{{ObjectiveKind::Contraction, "contraction"},
                                                                                 {ObjectiveKind::ThesisFitness, "thesis_fitness"},
                                                                                 {ObjectiveKind::StretchFitness, "stretch_fitness"},
                                                                                 {ObjectiveKind::BlockingForce, "blocking_force"},
                                                                                 {ObjectiveKind::AxialStiffness, "axial_stiffness"},
                                                                                 {ObjectiveKind::MaxStretch, "max_stretch"},
                                                                                 {ObjectiveKind::VolumeChange, "volume_change"},
                                                                                 {ObjectiveKind::LimitMargin, "limit_margin"},
                                                                                 {ObjectiveKind::Twist, "twist"},
                                                                                 {ObjectiveKind::ForceAtStroke, "force_at_stroke"},
                                                                                 {ObjectiveKind::WorkPerGram, "work_per_gram"},
                                                                                 {ObjectiveKind::ForcePerGram, "force_per_gram"}}};
};
template <>
struct EnumNames<VectorFamily> {
    static constexpr std::array<std::pair<VectorFamily, const char*>, 4> table{
        {{VectorFamily::Sine, "sine"}, {VectorFamily::AbsSine, "abs-sine"}, {VectorFamily::BSpline, "bspline"}, {VectorFamily::FreeXY, "free-xy"}}};
};

}  // namespace sim
