// What every model returns from an evaluation: a status (never an exception), the fitness and
// contraction every search compares, the meshes before and after, and the physical models' outputs.
// The outputs are listed by name and unit once, in model.h (VisitOutputs).
#pragma once

#include <cmath>
#include <vector>

#include "sim/mesh.h"
#include "sim/status.h"

namespace sim {

// What an evaluation of a shell model says beyond the common result fields (docs/models/shell.md section 10).
struct ShellOutputs {
    std::vector<double> curvePressureKpa;          // the load steps' pressures
    std::vector<double> curveContractionPercent;   // contraction at each (positive = shorter)
    std::vector<double> curveVolumeMm3;            // enclosed volume at each
    std::vector<double> curveForceN;               // axial force on the top clamp at each: the held stroke's
                                                   // reaction (blocked test; + pulls on the supports), else the load on it
    std::vector<double> curveTwistDeg;             // the top clamp's turn at each
    std::vector<double> isobaricContractionPercent;  // inflate with isobaric points: the held strokes, none to the free stroke
    std::vector<double> isobaricForceN;            // the force at each (NaN: a point that failed; 0 at the free stroke)
    double workPerStrokeMj = NAN;                  // the isobaric force integrated over the stroke, mJ
    double workPerGramMjPerG = NAN;                // the same per gram of the wall's silicone (NaN: no density)
    double siliconeG = NAN;                        // the wall's silicone at rest, g (NaN: no density)
    double restMaxRadiusMm = NAN;                  // the rest wall's largest distance from the axis, mm
    double targetPressureKpa = NAN;                // the pressure the contraction is reported at
    double limitPressureKpa = NAN;                 // the pressure maximum, when met
    double collapsePressureKpa = NAN;              // vacuum: where the wall collapsed (snapped inward), bracketed within the smallest step
    double blockingForceN = NAN;                   // top clamp held at its rest place; + pulls on the supports
    double strokeForceN = NAN;                     // blocked: the top held at its stroke (the isobaric test's force), likewise
    double heldBowMm = NAN;                        // the held state's bow: its rings' centres' largest distance from the axis,
                                                   // mm (0: straight); the blocking force's state, or a blocked test's end state
    double axialStiffnessNPerMm = NAN;             // dF/du at the free equilibrium
    double restVolumeMm3 = NAN, volumeMm3 = NAN;   // enclosed, caps included
    double maxStretch = NAN;                       // largest principal stretch of the wall
    double maxStressKpa = NAN;                     // largest principal true (Cauchy) stress
    double stretchLimit = NAN, tensileStrengthKpa = NAN;  // the material's, to compare with
    double displacementMm = NAN;                   // top clamp's axial displacement u
    double twistDeg = NAN;                         // top clamp's turn about the axis, + right-handed about +z (clamped ends)
    double twistPerLengthDegPerMm = NAN;           // twistDeg over the length
    double torqueNMm = NAN;                        // about +z on the top clamp: the fixture's that holds it (twist held),
                                                   // or the one applied (twist loaded); NaN when it turns freely
    double tipLateralMm = NAN;                     // tip free: the top cap centre's distance from the axis (clamped ends)
    double tipTiltDeg = NAN;                       // tip free: the angle between the top cap's axis and the tube's
    double tipForceN = NAN;                        // tip held: the lateral force that keeps the top cap on the axis
    double tipMomentNMm = NAN;                     // tip held: the bending moment that keeps it square to the axis
    double maxFibreStrain = NAN, meanFibreStrain = NAN;  // fibre stretch - 1 at the target (fibres only)
    double fibreAngleDeg = NAN;                    // the fibres' mean angle to the axis in the middle third
    int contactPairs = 0;                          // contact on: point-triangle and edge-edge pairs within the barrier's reach at the target
    double minGapMm = NAN;                         // contact on: the walls' smallest gap, mid-surface distance - h (inf: no wall near another)
    double contactForceN = NAN;                    // contact on: the sum of the active pairs' normal forces
    int newtonIterations = 0;
    int factorizations = 0;
    std::vector<Positions> steps;                  // positions at each load step (for pictures)
};

struct SimResult {
    Status status = Status::Ok;
    double fitness = 0.0;             // mesh units; NaN unless status is Ok
    double contractionPercent = 0.0;  // 100 * fitness / turns; NaN unless status is Ok
    int iterationsRun = 0;            // thesis: where the run stopped (== params.iterations when Ok);
                                      // membrane and shell: Newton iterations, all load steps
    double elapsedMs = 0.0;           // wall time of the relaxation alone
    Positions initial;                // the shaped rest mesh
    Positions final;                  // positions after the last iteration run
    ShellOutputs shell;               // membrane and shell models only
};

}  // namespace sim
