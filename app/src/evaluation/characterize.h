// A muscle's characteristic curves (docs/models/shell.md section 12), as `actuator characterize` and
// `actuator.characterize` give them: at each pressure the isobaric force against contraction, from
// none to the free stroke; the isometric force against pressure; the free stroke against pressure;
// the work of one stroke and per gram of the wall's silicone.
#pragma once

#include <vector>

#include "formats/archive.h"
#include "formats/json_out.h"
#include "formats/table.h"
#include "sim/model.h"
#include "sim/shell.h"

namespace app {

struct CharacteristicCurves {
    std::vector<double> pressuresKpa;
    int pointsPerCurve = 0;                                // each isobaric curve's, the free state included
    std::vector<sim::SimResult> free;                      // per pressure: the free inflation
    std::vector<std::vector<double>> contractionPercent;   // per pressure: the isobaric curve, closed by the free state
    std::vector<std::vector<double>> forceN;               // per pressure, beside contractionPercent (NaN: a point that failed)
    std::vector<std::vector<sim::IsobaricPoint>> points;   // per pressure: the held strokes as solved, closed by the free state (no force)
    std::vector<double> workPerStrokeMj;                   // per pressure: the force integrated over the stroke, N mm = mJ (NaN: none)
    sim::SimResult isometric;                              // the top held at its rest place, to the highest pressure
    double siliconeMassG = NAN;                            // the wall's, at the material's density (NaN: no density)
};

// Empty when the pressures can be the curves' (1 to 20, each above 0 kPa, increasing, each once);
// otherwise what is wrong. And empty when `job` can be characterized: a membrane or shell job whose
// load is the muscle alone (characterize sets the pressure and the stroke at each point).
std::string PressuresError(const std::vector<double>& pressuresKpa);
// The setting at fault is named by its key and value ("model", "thesis"), so the command line can
// name its option and Python its argument.
struct CharacterizeRefusal {
    std::string key, value, reason;  // reason empty: none
    std::string Text(const std::string& name) const { return name + (value.empty() ? "" : " " + value) + ": " + reason; }
};
CharacterizeRefusal CharacterizeJobError(const sim::EvalJob& job);

// `base` is a membrane or shell job (its load is replaced); `pressuresKpa` increasing; `points` per
// isobaric curve (2 or more); `threads` 0 for every core. The same whatever the threads.
CharacteristicCurves Characterize(const sim::EvalJob& base, const std::vector<double>& pressuresKpa, int points, int threads);

// Per pressure the free stroke, the force at no contraction, the work of one stroke (mJ) and per
// gram of silicone (mJ/g); the isometric force (N), the silicone's mass (g), the design and model.
Json CharacteristicSummary(const sim::EvalJob& base, const CharacteristicCurves& curves);

// Every evaluation behind the curves, as records of DIR/evaluations.capnp (role characteristic, in
// this order): per pressure its free inflation, then its held strokes from the smallest up; last the
// isometric test. Each job is the one `simulate --from` re-runs: a held stroke as the blocked test at
// that contraction.
std::vector<ArchiveRecord> CharacteristicRecords(const sim::EvalJob& base, const CharacteristicCurves& curves);

// curve (isobaric, isometric or free_stroke), pressure_kpa, contraction_percent, force_n, twist_deg, status.
Table CharacteristicTable(const CharacteristicCurves& curves);

// The ideal McKibben muscle's force at each isobaric point (Tondu and Lopez), for a braided cylinder
// only (empty otherwise): F = pi r0^2 p (3 (1 - eps)^2 / tan^2 a0 - 1 / sin^2 a0).
std::vector<std::vector<double>> IdealMuscleForces(const sim::EvalJob& base, const CharacteristicCurves& curves);

}  // namespace app
