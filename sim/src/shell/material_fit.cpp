// The uniaxial response, the stability and the fitting of the hyperelastic laws (sim/material_fit.h).
#include "sim/material_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <set>

namespace sim {
namespace {

// dW/dI1 and dW/dI2 of the law at (I1, I2), kPa.
struct InvariantSlopes {
    double w1 = 0, w2 = 0;
};
InvariantSlopes Slopes(const MaterialDef& m, double i1) {
    const double s = i1 - 3;
    switch (m.law) {
        case MaterialLaw::NeoHookean: return {0.5 * m.muKpa, 0};
        case MaterialLaw::MooneyRivlin: return {m.c10Kpa, m.c01Kpa};
        case MaterialLaw::Yeoh: return {m.c10Kpa + 2 * m.c20Kpa * s + 3 * m.c30Kpa * s * s, 0};
    }
    return {};
}

// The true stress of each homogeneous test at in-plane stretch l (incompressible, plane stress).
double UniaxialTrue(const MaterialDef& m, double l) {
    const InvariantSlopes d = Slopes(m, l * l + 2 / l);
    return 2 * (l * l - 1 / l) * (d.w1 + d.w2 / l);
}
double EquibiaxialTrue(const MaterialDef& m, double l) {
    const InvariantSlopes d = Slopes(m, 2 * l * l + 1 / (l * l * l * l));
    return 2 * (l * l - 1 / (l * l * l * l)) * (d.w1 + l * l * d.w2);
}
double PlanarTrue(const MaterialDef& m, double l) {
    const InvariantSlopes d = Slopes(m, l * l + 1 + 1 / (l * l));
    return 2 * (l * l - 1 / (l * l)) * (d.w1 + d.w2);
}

// The constants a law fits, in the order of its basis.
int ConstantCount(const MaterialFitDef& def) {
    switch (def.law) {
        case MaterialLaw::NeoHookean: return 1;
        case MaterialLaw::MooneyRivlin: return 2;
        case MaterialLaw::Yeoh: return def.terms;
    }
    return 1;
}

// Engineering stress per unit of each constant at stretch l: the laws are linear in their constants.
void Basis(const MaterialFitDef& def, double l, double* row) {
    const double a = 2 * (l - 1 / (l * l));
    const double s = l * l + 2 / l - 3;
    switch (def.law) {
        case MaterialLaw::NeoHookean: row[0] = 0.5 * a; break;
        case MaterialLaw::MooneyRivlin: row[0] = a, row[1] = a / l; break;
        case MaterialLaw::Yeoh:
            for (int i = 0; i < def.terms; ++i) row[i] = a * (i + 1) * std::pow(s, i);
            break;
    }
}

}  // namespace

double UniaxialStressKpa(const MaterialDef& m, double stretch) { return UniaxialTrue(m, stretch) / stretch; }

StabilityCheck DruckerStability(const MaterialDef& m, double maxStretch) {
    // Sampled in log strain, fine enough to find a Yeoh law's turning point within 0.1 % of stretch.
    constexpr int kSamples = 2000;
    const struct {
        const char* name;
        double (*trueStress)(const MaterialDef&, double);
    } tests[] = {{"uniaxial", UniaxialTrue}, {"equibiaxial", EquibiaxialTrue}, {"planar", PlanarTrue}};
    StabilityCheck first;
    if (!(maxStretch > 1)) return first;
    const double top = std::log(maxStretch);
    for (const auto& test : tests) {
        double previous = 0;
        for (int k = 1; k <= kSamples; ++k) {
            const double l = std::exp(top * k / kSamples);
            const double stress = test.trueStress(m, l);
            if (!(stress > previous)) {
                if (first.stable || l < first.failingStretch) first = {false, test.name, l};
                break;
            }
            previous = stress;
        }
    }
    return first;
}

double StableStretch(const MaterialDef& m, double upTo) {
    const StabilityCheck check = DruckerStability(m, upTo);
    return check.stable ? upTo : check.failingStretch;
}

MaterialFit FitMaterial(const std::vector<TensilePoint>& points, const MaterialFitDef& def, const MaterialDef& base) {
    MaterialFit fit;
    if (def.law == MaterialLaw::Yeoh && (def.terms < 1 || def.terms > 3)) return fit.error = "a Yeoh law has 1 to 3 terms", fit;
    if (!(def.maxStrain > 0)) return fit.error = "the strain range must be positive", fit;
    std::vector<TensilePoint> used;
    for (const TensilePoint& p : points)
        if (p.strain > 0 && p.strain <= def.maxStrain) used.push_back(p);
    const int n = ConstantCount(def);
    if (static_cast<int>(used.size()) < n + 1) {
        fit.error = "the curve has " + std::to_string(used.size()) + " points with strain in (0, " + std::to_string(def.maxStrain) + "]; a fit of " +
                    std::to_string(n) + " constants needs at least " + std::to_string(n + 1);
        return fit;
    }
    Eigen::MatrixXd a(used.size(), n);
    Eigen::VectorXd b(used.size());
    for (size_t i = 0; i < used.size(); ++i) {
        double row[3] = {0, 0, 0};
        Basis(def, 1 + used[i].strain, row);
        for (int j = 0; j < n; ++j) a(i, j) = row[j];
        b[i] = used[i].stressKpa;
    }
    // Column scaling: a Yeoh C30's column is (I1 - 3)^2 times C10's, 100 times larger at 200 % strain.
    const Eigen::VectorXd scale = a.colwise().norm().transpose().cwiseMax(1e-300);
    const Eigen::VectorXd c = (a * scale.cwiseInverse().asDiagonal()).colPivHouseholderQr().solve(b).cwiseQuotient(scale);

    fit.material = base;
    fit.material.preset = MaterialPreset::Custom;
    fit.material.law = def.law;
    fit.material.muKpa = fit.material.c10Kpa = fit.material.c01Kpa = fit.material.c20Kpa = fit.material.c30Kpa = 0;
    switch (def.law) {
        case MaterialLaw::NeoHookean: fit.material.muKpa = c[0]; break;
        case MaterialLaw::MooneyRivlin: fit.material.c10Kpa = c[0], fit.material.c01Kpa = c[1]; break;
        case MaterialLaw::Yeoh:
            fit.material.c10Kpa = c[0];
            if (n > 1) fit.material.c20Kpa = c[1];
            if (n > 2) fit.material.c30Kpa = c[2];
            break;
    }
    const Eigen::VectorXd residual = a * c - b;
    fit.points = static_cast<int>(used.size());
    std::set<int> specimens;
    for (const TensilePoint& p : used) specimens.insert(p.specimen), fit.maxStrainFitted = std::max(fit.maxStrainFitted, p.strain);
    fit.specimens = static_cast<int>(specimens.size());
    fit.rmsKpa = std::sqrt(residual.squaredNorm() / fit.points);
    fit.maxErrorKpa = residual.cwiseAbs().maxCoeff();
    fit.relativeRms = fit.rmsKpa / std::sqrt(b.squaredNorm() / fit.points);
    fit.stability = DruckerStability(fit.material, 1 + fit.maxStrainFitted);
    return fit;
}

}  // namespace sim
