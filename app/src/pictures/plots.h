// The figures of numbers an experiment writes: a sweep's fitness landscape (a line plot for one
// axis, a heat map for two) and a GA's evolution (best, mean and worst per generation, per run).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "render/image.h"
#include "sim/batch.h"
#include "sim/material_fit.h"
#include "sim/optimize.h"
#include "sim/search.h"

namespace app {

// What an experiment's plots say and mark, made from the experiment (experiments/PlotContextOf), so
// that pictures need nothing of experiment files.
struct PlotContext {
    std::string title;         // the experiment's, e.g. "4.1  Variable amplitude search"
    std::string fitnessLabel;  // the fitness axis: its meaning and unit
    std::string valueLabel;    // a heat map's colour bar, e.g. "contraction (%)"
    std::string seriesLabel;   // a one-axis landscape's line, e.g. "fitness after 10000 iterations"
    std::vector<sim::SweepAxis> axes;  // a sweep's axes
    struct Mark {
        std::vector<std::pair<sim::SweepParameter, double>> at;
        double value = NAN;
    };
    std::vector<Mark> thesisPoints;          // the thesis's own designs and fitness (Table 4.4, Figure 4.1's peak)
    std::vector<sim::Objective> objectives;  // an optimizer's (Pareto front, hypervolume)
};

// `fitness` in grid order (NaN for failed points); `best` the best point's index or -1.
render::Image LandscapeImage(const PlotContext& e, const std::vector<double>& fitness, int best, const std::string& bestText);

struct RunCurve {
    std::string title;  // e.g. "run 2"
    std::vector<sim::LogbookRow> logbook;
    // Draws the rows' best so far beside the generation's best: for optimizers that may lose their
    // best (CMA-ES). The GA's elitism keeps its best, so its best line already is the best so far.
    bool showBestSoFar = false;
    double reference = NAN;           // the thesis's best for this run, drawn as a line; NaN: none
    std::string referenceLabel{};     // e.g. "thesis, Table 5.4: 1.13"; ThesisBestLegend
};
render::Image EvolutionImage(const PlotContext& e, const std::vector<RunCurve>& runs);

// An optimizer's two-objective Pareto front (natural units and directions): every valid design
// faint, the front's designs numbered 1, 2, ... in the order of pareto_front.csv.
struct ParetoPoint {
    double x, y;
};
render::Image ParetoImage(const PlotContext& e, const std::vector<ParetoPoint>& all, const std::vector<ParetoPoint>& front);
// The hypervolume of each run against its generation.
render::Image HypervolumeImage(const PlotContext& e, const std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>>& runs);

// A membrane or shell result's contraction-pressure curve at its load steps (with the top held, a
// blocked test's: the force on it against pressure), the target pressure and the limit point (the
// pressure maximum) marked when met.
render::Image PressureCurveImage(const std::string& title, const sim::SimResult& result, bool topHeld);

// A muscle's characteristic curves (actuator characterize): the isobaric force against contraction,
// one line per pressure (contraction[k], force[k] at pressures[k], NaN where a point failed); the
// isometric force against pressure (the blocked result's load steps); the free stroke against
// pressure (the free result's load steps). `ideal`, when not empty, is the ideal muscle's force at
// the same points (braided cylinders), drawn faint beside each curve.
struct CharacteristicImages {
    render::Image forceContraction, forcePressure, strokePressure;
};
CharacteristicImages CharacteristicCurveImages(const std::string& title, const std::vector<double>& pressures,
                                               const std::vector<std::vector<double>>& contraction, const std::vector<std::vector<double>>& force,
                                               const std::vector<std::vector<double>>& ideal, const sim::SimResult& isometric,
                                               const sim::SimResult& freeStroke);

// A silicone's uniaxial tensile curve (actuator material show and fit): the measured points (faint
// markers, per specimen), each law's engineering stress against strain (a data-sheet law dashed),
// and the range a fit used shaded.
struct TensileFigure {
    std::string title, subtitle;                 // subtitle: the residual and the range, under the title
    std::vector<sim::TensilePoint> measured;     // may be empty
    std::string measuredLabel;
    struct Law {
        std::string label;
        sim::MaterialDef material;
        bool dashed = false;
    };
    std::vector<Law> laws;
    double fitMaxStrain = 0;  // engineering strain; 0: no fit range drawn
    double maxStrain = 3;     // the x axis's end, engineering strain
};
render::Image TensileCurveImage(const TensileFigure& figure);

// How a sweep axis is named on plots, e.g. "amplitude A".
std::string AxisLabel(sim::SweepParameter parameter);

// The legend of the thesis's reference lines: one legend serves every run's panel, so with several
// runs it names each run's number in run order ("thesis's best of that run: 1.13, 1.09, 1.14").
std::string ThesisBestLegend(const std::vector<double>& runBest, size_t runs);

}  // namespace app
