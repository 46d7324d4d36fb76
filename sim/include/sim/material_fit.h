// A silicone from its tensile test (docs/guide/materials.md): the uniaxial response of the laws the
// models have, their Drucker stability, and a least-squares fit of a law to measured engineering
// stress. Pure computation: the command line reads the curve and writes the material file.
#pragma once

#include <string>
#include <vector>

#include "sim/shell.h"

namespace sim {

// One measured point of a uniaxial tensile test: engineering strain (0.5 = 50 %) and engineering
// stress (force over the undeformed section) in kPa, from specimen `specimen` (0 when one).
struct TensilePoint {
    double strain = 0;
    double stressKpa = 0;
    int specimen = 0;
};

// The engineering (nominal) stress of an incompressible solid pulled to `stretch` in uniaxial
// tension, kPa: P = 2 (l - l^-2) (dW/dI1 + dW/dI2 / l).
double UniaxialStressKpa(const MaterialDef& material, double stretch);

// Drucker stability in the three homogeneous tests, uniaxial, equibiaxial and planar (pure shear):
// the true stress must rise with the logarithmic strain. Negative higher constants (a Mooney-Rivlin
// C01, a Yeoh C30) can make a law soften and then fail it: the wall would then have no unique
// equilibrium, and the model's results would mean nothing.
struct StabilityCheck {
    bool stable = true;
    std::string mode;           // where it first fails: "uniaxial", "equibiaxial" or "planar"; "" when stable
    double failingStretch = 0;  // the stretch (the loading direction's) where it first fails
};
StabilityCheck DruckerStability(const MaterialDef& material, double maxStretch);

// The largest stretch up to which a material is stable in all three tests (searched to `upTo`;
// `upTo` itself when stable throughout). The solver compares the wall's largest stretch to it.
double StableStretch(const MaterialDef& material, double upTo);

// How a law is fitted to a curve.
struct MaterialFitDef {
    MaterialLaw law = MaterialLaw::Yeoh;
    int terms = 2;          // Yeoh: 1 to 3 constants (C10, C20, C30); the other laws have a fixed count
    double maxStrain = 2;   // points with engineering strain above this are left out (2 = 200 %)
};

struct MaterialFit {
    std::string error;          // why there is no fit ("" when there is)
    MaterialDef material;       // the law and its constants; the rest copied from `base`
    int points = 0;             // points used (strain within the range)
    int specimens = 0;          // distinct specimens among them
    double maxStrainFitted = 0; // the largest strain among the points used
    double rmsKpa = 0;          // root-mean-square residual of the engineering stress, kPa
    double maxErrorKpa = 0;     // largest absolute residual, kPa
    double relativeRms = 0;     // rmsKpa over the root-mean-square measured stress
    StabilityCheck stability;   // Drucker, up to 1 + maxStrainFitted
};

// Least squares on engineering stress (the laws are linear in their constants: a column-scaled QR).
MaterialFit FitMaterial(const std::vector<TensilePoint>& points, const MaterialFitDef& def, const MaterialDef& base);

// Where a preset's constants come from (materials.cpp): the measurement or the data sheet, its test
// conditions, and, for a fitted preset, the range and residual of its fit.
struct MaterialSource {
    std::string source;         // who measured or published what
    std::string conditions;     // the test: standard, specimen, speed, machine, how strain was measured
    double fitMaxStrain = 0;    // the fit's range, engineering strain; 0: constants not fitted here
    double fitRmsKpa = 0;
    double fitRelativeRms = 0;
    MaterialPreset datasheet = MaterialPreset::Custom;  // a fitted preset's data-sheet constants, kept as that preset
};
MaterialSource MaterialPresetSource(MaterialPreset preset);

// A subset of the measured curve a preset was fitted to (a few dozen points, with the database's
// attribution in MaterialPresetSource); empty for presets from data sheets.
std::vector<TensilePoint> MaterialPresetPoints(MaterialPreset preset);

}  // namespace sim
