// Silicone presets and the checks of a shell model's definition.
#include <cmath>
#include <cstdio>

#include "sim/shell.h"

namespace sim {
namespace {

// A supplier's typical values. The neo-Hookean shear modulus is the 100 % modulus divided by 1.75:
// the nominal uniaxial stress of a neo-Hookean solid at stretch 2 is mu (2 - 1/4) = 1.75 mu.
MaterialDef Preset(MaterialPreset preset, double modulus100Kpa, double tensileKpa, double elongation, double density) {
    MaterialDef m;
    m.preset = preset;
    m.law = MaterialLaw::NeoHookean;
    m.muKpa = modulus100Kpa / 1.75;
    m.tensileStrengthKpa = tensileKpa;
    m.elongationAtBreak = elongation;
    m.densityKgPerM3 = density;
    return m;
}

constexpr double kPsi = 6.894757;  // kPa

}  // namespace

MaterialDef MaterialPresetDef(MaterialPreset preset) {
    switch (preset) {
        // Smooth-On technical bulletins (Ecoflex series, Dragon Skin series): 100 % modulus, tensile
        // strength, elongation at break, specific gravity.
        case MaterialPreset::Ecoflex0030: return Preset(preset, 10 * kPsi, 200 * kPsi, 9.0, 1070);
        case MaterialPreset::Ecoflex0050: return Preset(preset, 12 * kPsi, 315 * kPsi, 9.8, 1070);
        case MaterialPreset::DragonSkin10: return Preset(preset, 22 * kPsi, 475 * kPsi, 10.0, 1070);
        case MaterialPreset::DragonSkin20: return Preset(preset, 49 * kPsi, 550 * kPsi, 6.2, 1080);
        case MaterialPreset::DragonSkin30: return Preset(preset, 86 * kPsi, 500 * kPsi, 3.64, 1080);
        case MaterialPreset::Elastosil4601: {
            // Wacker's data sheet (tensile strength 6.5 MPa, elongation 700 %, density 1.13 g/cm^3) and
            // the Yeoh fit of Polygerinos et al. 2015 (C10 = 0.11 MPa, C20 = 0.02 MPa).
            MaterialDef m = Preset(preset, 0, 6500, 7.0, 1130);
            m.law = MaterialLaw::Yeoh;
            m.muKpa = 0;
            m.c10Kpa = 110;
            m.c20Kpa = 20;
            return m;
        }
        case MaterialPreset::Custom: break;
    }
    return MaterialDef{};
}

double ShearModulusKpa(const MaterialDef& m) {
    switch (m.law) {
        case MaterialLaw::NeoHookean: return m.muKpa;
        case MaterialLaw::MooneyRivlin: return 2 * (m.c10Kpa + m.c01Kpa);
        case MaterialLaw::Yeoh: return 2 * m.c10Kpa;
    }
    return m.muKpa;
}

double StretchLimit(const MaterialDef& m) {
    // Half the one-pull elongation: silicone fatigues and tears long before its break elongation.
    return m.stretchLimit > 0 ? m.stretchLimit : 1 + m.elongationAtBreak / 2;
}

ShellDef DefaultShellDef() { return ShellDef{}; }

std::string ShellDefError(const ShellDef& d) {
    const GeometryDef& g = d.geometry;
    auto positive = [](double v) { return std::isfinite(v) && v > 0; };
    if (!positive(g.radiusMm)) return "radius must be a positive number of millimetres";
    if (!positive(g.lengthMm)) return "length must be a positive number of millimetres";
    if (!positive(g.thicknessMm)) return "wall thickness must be a positive number of millimetres";
    if (g.thicknessMm >= g.radiusMm) return "the wall (" + std::to_string(g.thicknessMm) + " mm) must be thinner than the radius (" + std::to_string(g.radiusMm) + " mm)";
    if (g.ringVertices < 6) return "a ring needs at least 6 vertices";
    if (g.clampRings < 1) return "each clamp holds at least one ring";
    const int rings = RingCount(g);
    if (rings < 2 * g.clampRings + 2) return "the tube needs at least two free rings between its clamps (" + std::to_string(2 * g.clampRings + 2) + " rings)";
    const MaterialDef& m = d.material;
    const double modulus = ShearModulusKpa(m);
    if (!positive(modulus)) return "the material's shear modulus must be positive (set mu, or C10 and C01)";
    for (double c : {m.muKpa, m.c10Kpa, m.c01Kpa, m.c20Kpa, m.c30Kpa})
        if (!std::isfinite(c) || c < 0) return "material constants must be finite and not negative";
    if (!std::isfinite(m.tensileStrengthKpa) || m.tensileStrengthKpa < 0 || !std::isfinite(m.elongationAtBreak) || m.elongationAtBreak < 0)
        return "tensile strength and elongation must be finite and not negative";
    if (!std::isfinite(m.stretchLimit) || (m.stretchLimit != 0 && m.stretchLimit <= 1)) return "the stretch limit must be above 1";
    const LoadDef& l = d.load;
    if (!std::isfinite(l.pressureKpa)) return "the pressure must be a finite number";
    if (!std::isfinite(l.forceN)) return "the force must be a finite number";
    if (!positive(l.volumeRatio)) return "the volume ratio must be positive";
    if (l.steps < 1 || l.steps > 1000) return "load steps must be between 1 and 1000";
    if (!(std::isfinite(l.strokePercent) && l.strokePercent > -100 && l.strokePercent < 100))
        return "the held contraction must be a percentage of the length between -100 and 100";
    if (!std::isfinite(l.strokeMm)) return "the held stroke must be a finite number of mm";
    if (l.isobaricPoints == 1 || l.isobaricPoints < 0 || l.isobaricPoints > 100)
        return "the isobaric curve needs 2 to 100 points (from no contraction to the free stroke), or 0 for none";
    if (l.strokeMm != 0 && l.strokePercent != 0) return "give the held stroke once: stroke_percent or stroke_mm";
    if (!(std::fabs(l.strokeMm) < d.geometry.lengthMm)) return "the held stroke must be shorter than the tube";
    if (!std::isfinite(d.ends.torqueNMm)) return "the torque must be a finite number";
    if (d.ends.twist == TwistEnd::Loaded && d.geometry.ends != EndCondition::Clamped) return "a torque needs clamped ends (sliding ends cannot turn)";
    const FibreDef& f = d.fibres;
    auto angleOk = [](double a) { return std::isfinite(a) && a >= -90 && a <= 90; };
    if (!angleOk(f.angleDeg)) return "the fibre angle must be a number of degrees from -90 to 90";
    if (!std::isfinite(f.stiffnessNPerMm) || f.stiffnessNPerMm < 0) return "the fibre stiffness must be finite and not negative";
    if (!f.bands.empty() && !f.sectorAnglesDeg.empty()) return "fibre angles come by bands or by sectors, not both";
    if (!f.bands.empty()) {
        // Bands in order, each from where the last ended, together from 0 to 1.
        double covered = 0;
        for (const FibreBand& band : f.bands) {
            if (!angleOk(band.angleDeg)) return "a fibre band's angle must be a number of degrees from -90 to 90";
            if (!(band.from >= 0 && band.to <= 1 && band.from < band.to)) return "a fibre band runs from 'from' to 'to', fractions of the length with 0 <= from < to <= 1";
            if (std::fabs(band.from - covered) > 1e-9)
                return "the fibre bands must cover the length from 0 to 1 in order, each starting where the last ended (a gap or overlap at " +
                       std::to_string(covered) + ")";
            covered = band.to;
        }
        if (std::fabs(covered - 1) > 1e-9) return "the fibre bands must cover the length up to 1 (they end at " + std::to_string(covered) + ")";
    }
    if (f.sectorAnglesDeg.size() == 3 || f.sectorAnglesDeg.size() > 4) return "fibre sectors come as 1, 2 or 4 angles, as the thesis's sectors";
    for (double a : f.sectorAnglesDeg)
        if (!angleOk(a)) return "a fibre sector's angle must be a number of degrees from -90 to 90";
    if (!positive(d.solver.tolerance)) return "the tolerance must be positive";
    if (d.solver.maxIterations < 1) return "Newton needs at least one iteration";
    // Last: the estimate reads the whole definition.
    if (const double bytes = EvaluationBytesEstimate(d); !(bytes <= kMaxEvaluationBytes)) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "the mesh (%d vertices a ring x %d rings) would need about %.1f GB per evaluation, more than the %.1f GB limit (about 270,000 "
                      "vertices, 520 x 520)",
                      g.ringVertices, RingCount(g), bytes / 1e9, kMaxEvaluationBytes / 1e9);
        return text;
    }
    return "";
}

}  // namespace sim
