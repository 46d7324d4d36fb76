// Searches over shapes: exhaustive sweeps over sine parameters (thesis chapter 4) and the thesis's
// genetic algorithm (chapter 5, DEAP's eaSimple semantics plus elitism). Plain data and pure steps:
// evaluation is a callback, so the caller chooses threads, caching and archives, while every random
// draw happens here, in a fixed order, from one checkpointable generator.
#pragma once

#include <cmath>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sim/random.h"
#include "sim/shape.h"
#include "sim/shell.h"
#include "sim/solver.h"

namespace sim {

// [SECTION] Sweeps -------------------------------------------------------------------------------

enum class SweepParameter {
    Amplitude,  // A
    Cycles,     // n: phase runs from phaseStart to phaseStart + n*pi (thesis 4.2, 4.3)
    PhaseEnd,   // b: phase runs from phaseStart to b
    PressureKpa,  // the target gauge pressure of the membrane and shell models: a load, not a shape
                  // parameter (sweeps over jobs: SweepJobs in batch.h)
    FibreAngleDeg,  // the fibres' angle to the meridian (membrane and shell models with fibres)
};

// A sine or abs-sine shape's value of a sweep parameter (NaN for other shapes and for PressureKpa),
// and the shape with that parameter set (other shapes and PressureKpa: returned unchanged).
double SweepParameterValue(const Shape& shape, SweepParameter parameter);
Shape WithSweepParameter(Shape shape, SweepParameter parameter, double value);

struct SweepAxis {
    SweepParameter parameter = SweepParameter::Amplitude;
    std::vector<double> values;
};

// Evenly spaced values from `from` to `to` inclusive (numpy.linspace).
std::vector<double> Linspace(double from, double to, int points);

struct SweepDef {
    Shape base = SineShape{};     // sine or abs-sine; the axes overwrite their parameters
    std::vector<SweepAxis> axes;  // one or two
};

// The grid's shapes, row-major: the last axis varies fastest.
std::vector<Shape> SweepShapes(const SweepDef& def);

// [SECTION] Genetic algorithm --------------------------------------------------------------------

enum class GenomeKind {
    BSpline,  // integer control points, one list per sector spline, each of variable length
    FreeXY,   // a (dx, dy) offset per vertex, 2N floats
};

struct GenomeDef {
    GenomeKind kind = GenomeKind::BSpline;
    SplineRegion region = SplineRegion::Middle;  // B-splines: where the splines apply; free-xy: middle leaves the clamped turns unmoved
    int splines = 1;        // B-spline sectors: 1, 2 or 4
    // Control points (radii in base-radius units) lie on a grid: controlMin, controlMin + controlStep,
    // ..., controlMax (thesis: the integers 0-8). A finer step over a narrower range keeps a search
    // near a muscle's proportions (the shipped physical searches: 0.5-2.5 in steps of 0.25).
    double controlMin = 0;
    double controlMax = 8;
    double controlStep = 1;
    long long ControlLevels() const { return std::llround((controlMax - controlMin) / controlStep); }  // grid points less one
    double ControlValue(long long level) const { return controlMin + static_cast<double>(level) * controlStep; }
    bool OnControlGrid(double c) const;  // within the range and on a grid point
    int lengthMin = 5;      // control points per spline, inclusive bounds (thesis: 5-16)
    int lengthMax = 16;
    double initRange = 0.5; // free-xy: initial offsets uniform in [-initRange, initRange] (thesis 5.5)
    double sigma = 0.2;     // free-xy: standard deviation of the Gaussian mutation, mesh units
    double bound = 1.0;     // free-xy: offsets are clamped to [-bound, bound] (thesis 5.5)
    // Fibre genes (membrane and shell models with fibres), in one extra gene list after the shape's:
    // the angles, then the switches.
    int fibreAngles = 0;         // angle genes: 0 none; 1 one angle; n > 1 one per band of n equal bands
    bool fibreSwitches = false;  // one on/off gene per fibre family (+alpha, and a braid's -alpha)
    double fibreAngleMin = 0;    // angle genes lie in [fibreAngleMin, fibreAngleMax], degrees
    double fibreAngleMax = 90;
    double fibreSigmaDeg = 10;   // Gaussian mutation of an angle gene, degrees
    bool HasFibreGenes() const { return fibreAngles > 0 || fibreSwitches; }
};

// Empty when the control grid is one: a positive step that divides max - min, low end first, at
// most a million points; otherwise what is wrong.
std::string ControlGridError(const GenomeDef& g);

// When a search stops besides its number of generations (each 0 or NaN: never). The reason is
// written in the run's logbook.
struct StopDef {
    long long evaluations = 0;  // once this many designs were evaluated (checked after each generation)
    double seconds = 0;         // after this much wall time (this session's for the GA); not reproducible
    double target = NAN;        // once the best reaches it (one objective)
    int stagnation = 0;         // after this many generations without improvement of the best (several
                                // objectives: of the hypervolume)
};

struct GaDef {
    int population = 30;    // individuals per generation
    int generations = 40;   // generations after the initial population
    int tournament = 3;     // tournament size k
    int elite = 1;          // best individuals copied unchanged into the next generation
    double mutpb = 0.4;     // probability that an individual is mutated (MUTPB)
    double indpb = 0.2;     // probability that a gene is reset, and that a spline grows or shrinks (INDPB)
    double cxpb = 0.0;      // probability that a pair gets two-point crossover (thesis: only for free-xy)
    GenomeDef genome;
    StopDef stop;
};

// B-spline: one list of control points per sector. Free-xy: one list dx0, dy0, dx1, dy1, ...
using Genome = std::vector<std::vector<double>>;

struct Individual {
    Genome genome;
    bool evaluated = false;
    double fitness = 0;          // meaningful only when evaluated and status is Ok
    Status status = Status::Ok;  // a failed individual is never selected and never counts as 0

    bool Valid() const { return evaluated && status == Status::Ok; }
};

// One generation of a search, as the GA and every optimizer log it (each engine's logbook.csv
// writes the columns it has always written from this one row).
struct LogbookRow {
    int generation = 0;
    long long evaluations = 0;       // designs evaluated in this generation (DEAP's nevals)
    long long evaluationsSoFar = 0;  // the run's evaluations up to and including this generation
    // The first objective over the generation's valid members, natural units and direction; stddev
    // with ddof 0; quartiles with linear interpolation (numpy's default).
    double best = NAN, worst = NAN, mean = NAN, stddev = NAN;
    double q1 = NAN, median = NAN, q3 = NAN;
    double bestSoFar = NAN;  // over every design the run has evaluated
    int invalid = 0;         // members whose evaluation failed
    // Several objectives: the hypervolume of every valid design so far and the size of their front.
    double hypervolume = NAN;
    int frontSize = 0;
};

// A GA logbook row's running fields (evaluations so far, best so far) from the row before it (none
// for generation 0): derived, never stored, so that checkpoints stay as they were written.
void ChainGaLogbookRow(LogbookRow& row, const LogbookRow* before);

// The q-quantile (0..1) of values sorted ascending, interpolating linearly between neighbours.
double SortedQuantile(const std::vector<double>& ascending, double q);

struct GaState {
    int generation = 0;  // generations completed; 0 once the initial population is evaluated
    std::string stopReason;  // why the run ended, once it has (GaStopReason, or "stopped", "no valid design")
    Random rng;
    std::vector<Individual> population;
    std::vector<LogbookRow> logbook;
    std::vector<Individual> bestPerGeneration;  // one per logbook row
    std::vector<Individual> hallOfFame;         // best distinct genomes of the run, best first
};

constexpr int kHallOfFameSize = 10;

// Evaluates genomes; returns (fitness, status) for each, in order. May run them in parallel.
using GenomeEvaluator = std::function<std::vector<std::pair<double, Status>>(const std::vector<const Genome*>&)>;

// Empty when the definition is usable; otherwise what is wrong.
std::string GaDefError(const GaDef& def, const MeshDef& mesh);

// The shape a genome describes (its fibre genes, if any, aside).
Shape ShapeOfGenome(const Genome& genome, const GenomeDef& def, const MeshDef& mesh);
// The inverse: the genome a shape of this genome kind was built from (empty for another kind).
Genome GenomeOfShape(const Shape& shape);
// The fibres a genome's fibre genes give over `base` (layout and stiffness from the model), and the
// inverse: the whole genome of a design.
FibreDef FibresOfGenome(const Genome& genome, const GenomeDef& def, FibreDef base);
Genome GenomeOfDesign(const Shape& shape, const FibreDef& fibres, const GenomeDef& def);

// Creates and evaluates the initial population (generation 0).
GaState StartEvolution(const GaDef& def, const MeshDef& mesh, std::uint64_t seed, const GenomeEvaluator& evaluate);

// One generation: keep the elite, select by tournament among valid individuals, cross, mutate,
// evaluate the changed individuals. False (state unchanged) when no individual is valid to select.
bool EvolveOneGeneration(const GaDef& def, const MeshDef& mesh, GaState& state, const GenomeEvaluator& evaluate);

// Why the run should stop after its latest generation ("generations", "evaluations", "target",
// "stagnation"), or "" to go on. Wall time is the caller's.
std::string GaStopReason(const GaDef& def, const GaState& state);

// A genome as text: splines separated by ';', genes by ',' (shortest round-trip digits).
std::string GenomeText(const Genome& genome);

template <>
struct EnumNames<SweepParameter> {
    static constexpr std::array<std::pair<SweepParameter, const char*>, 5> table{{
        {SweepParameter::Amplitude, "amplitude"}, {SweepParameter::Cycles, "cycles"}, {SweepParameter::PhaseEnd, "phase_end"},
        {SweepParameter::PressureKpa, "pressure_kpa"},
        {SweepParameter::FibreAngleDeg, "fibre_angle_deg"}}};
};
template <>
struct EnumNames<GenomeKind> {
    static constexpr std::array<std::pair<GenomeKind, const char*>, 2> table{{{GenomeKind::BSpline, "bspline"}, {GenomeKind::FreeXY, "free-xy"}}};
};

}  // namespace sim
