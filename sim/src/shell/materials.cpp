// Silicone presets and the checks of a shell model's definition.
#include <cmath>
#include <cstdio>
#include <string>

#include "sim/material_fit.h"
#include "sim/shell.h"

namespace sim {
namespace {

constexpr double kPsi = 6.894757;  // kPa

// Smooth-On's technical bulletins (Ecoflex series, Dragon Skin series): 100 % modulus, tensile
// strength, elongation at break, specific gravity; and, for the fitted presets, a two-term Yeoh law
// fitted to Marechal et al.'s curve of the same silicone (scripts/fit-material-presets.sh).
struct PresetRow {
    MaterialPreset fitted, datasheet;
    double modulus100Psi, tensilePsi, elongation, densityKgPerM3;
    double c10Kpa, c20Kpa;         // the fit
    double fitRmsKpa, fitRelativeRms;
    const char* databaseFile;      // the database's file the fit comes from
    std::vector<TensilePoint> (*points)();
};

// The database's rows nearest 10 %, 20 %, ..., 300 % engineering strain (strain, stress in kPa):
// Marechal et al. 2021, Soft Robotics Materials Database, ODbL 1.0 (docs/guide/materials.md).
std::vector<TensilePoint> Ecoflex0030Points() {
    return {{0.09084, 3.43}, {0.20455, 7.52}, {0.29545, 10.73}, {0.40909, 13.82}, {0.5, 16.89}, {0.59091, 19.09}, {0.70454, 21.8}, {0.79546, 24.37}, {0.90909, 26.89}, {0.99999, 29.72},
            {1.0909, 30.96}, {1.2046, 33.83}, {1.2954, 35.1}, {1.4091, 38.55}, {1.5, 40.08}, {1.5909, 42.7}, {1.7045, 45.46}, {1.7955, 46.79}, {1.9091, 50.73}, {2, 52.39},
            {2.0909, 54.57}, {2.2045, 57.75}, {2.2955, 59.99}, {2.4091, 62.98}, {2.5, 65.93}, {2.5909, 68.17}, {2.7045, 71.6}, {2.7955, 74.46}, {2.9091, 77.97}, {3, 80.15}};
}
std::vector<TensilePoint> Ecoflex0050Points() {
    return {{0.09084, 4.435}, {0.20455, 9.94}, {0.29546, 14.28}, {0.40909, 19.29}, {0.5, 22.77}, {0.59091, 26.17}, {0.70454, 30.46}, {0.79545, 33.96}, {0.90909, 37.8}, {1, 40.95},
            {1.0909, 44.46}, {1.2045, 48.36}, {1.2954, 51.64}, {1.4091, 55.96}, {1.5, 59.51}, {1.5909, 63.02}, {1.7046, 67.37}, {1.7955, 70.81}, {1.9091, 75.38}, {2, 79.01},
            {2.0909, 83.34}, {2.2045, 87.92}, {2.2955, 91.84}, {2.4091, 96.92}, {2.5, 101.3}, {2.5909, 105.6}, {2.7045, 111}, {2.7955, 115.7}, {2.9091, 121.2}, {3, 125.8}};
}
std::vector<TensilePoint> DragonSkin10Points() {
    return {{0.090842, 10.13}, {0.20455, 21.87}, {0.29545, 31.26}, {0.40908, 43.37}, {0.50001, 53}, {0.59091, 63.45}, {0.70455, 76.76}, {0.79546, 87.44}, {0.9091, 101}, {1, 113},
            {1.0909, 125.2}, {1.2045, 142.5}, {1.2955, 157.2}, {1.4091, 176}, {1.5, 190.6}, {1.5909, 206.4}, {1.7045, 226.1}, {1.7955, 240.3}, {1.9091, 258.3}, {2, 272.8},
            {2.0909, 287.8}, {2.2045, 306.3}, {2.2954, 321.5}, {2.4091, 340.5}, {2.5, 356}, {2.5909, 372.1}, {2.7045, 392.1}, {2.7954, 407.8}, {2.9091, 428.3}, {3, 444.8}};
}
std::vector<TensilePoint> DragonSkin20Points() {
    return {{0.090843, 26.06}, {0.20455, 58.89}, {0.29546, 85.65}, {0.40909, 120.3}, {0.5, 151.1}, {0.59091, 181}, {0.70455, 217.6}, {0.79545, 247.6}, {0.90909, 286.4}, {1, 318.4},
            {1.0909, 351.3}, {1.2045, 393.3}, {1.2955, 427.9}, {1.4091, 472.8}, {1.5, 509.2}, {1.5909, 546.2}, {1.7045, 594}, {1.7955, 632.8}, {1.9091, 681.9}, {2, 722.3},
            {2.0909, 763.1}, {2.2045, 814.8}, {2.2955, 856.7}, {2.4091, 909.8}, {2.5, 952.8}, {2.5909, 996.1}, {2.7045, 1050}, {2.7955, 1094}, {2.9091, 1149}, {3, 1194}};
}
std::vector<TensilePoint> DragonSkin30Points() {
    return {{0.09084, 41.49}, {0.20455, 91.88}, {0.29545, 130}, {0.40909, 176.1}, {0.5, 213.9}, {0.59091, 253.5}, {0.70455, 302.3}, {0.79545, 342.6}, {0.90909, 394.6}, {1, 437.1},
            {1.0909, 480.8}, {1.2045, 537.2}, {1.2955, 583.4}, {1.4091, 642}, {1.5, 689.4}, {1.5909, 737.5}, {1.7046, 798.5}, {1.7954, 847.7}, {1.9091, 909.7}, {2, 959.5},
            {2.0909, 1009}, {2.2045, 1073}, {2.2955, 1123}, {2.4091, 1187}, {2.5, 1239}, {2.5909, 1291}, {2.7045, 1357}, {2.7955, 1409}, {2.9091, 1476}, {3, 1529}};
}

// The fits' range: 0-200 % engineering strain.
constexpr double kFitMaxStrain = 2;

const PresetRow kPresets[] = {
    {MaterialPreset::Ecoflex0030, MaterialPreset::Ecoflex0030Datasheet, 10, 200, 9.0, 1070, 7.859, 0.0943, 0.435, 0.0135, "Ecoflex 00-30.csv", Ecoflex0030Points},
    {MaterialPreset::Ecoflex0050, MaterialPreset::Ecoflex0050Datasheet, 12, 315, 9.8, 1070, 10.74, 0.2303, 0.501, 0.0106, "Ecoflex 00-50.csv", Ecoflex0050Points},
    {MaterialPreset::DragonSkin10, MaterialPreset::DragonSkin10Datasheet, 22, 475, 10.0, 1070, 25.03, 1.811, 3.93, 0.0264, "Dragon Skin 10 MEDIUM.csv", DragonSkin10Points},
    {MaterialPreset::DragonSkin20, MaterialPreset::DragonSkin20Datasheet, 49, 550, 6.2, 1080, 72.65, 4.199, 10.8, 0.0270, "Dragon Skin 20.csv", DragonSkin20Points},
    {MaterialPreset::DragonSkin30, MaterialPreset::DragonSkin30Datasheet, 86, 500, 3.64, 1080, 103.2, 5.085, 12.7, 0.0235, "Dragon Skin 30.csv", DragonSkin30Points},
};

const PresetRow* RowOf(MaterialPreset preset) {
    for (const PresetRow& row : kPresets)
        if (row.fitted == preset || row.datasheet == preset) return &row;
    return nullptr;
}

}  // namespace

MaterialDef MaterialPresetDef(MaterialPreset preset) {
    MaterialDef m;
    m.preset = preset;
    if (preset == MaterialPreset::Elastosil4601) {
        // Wacker's data sheet (tensile strength 6.5 MPa, elongation 700 %, density 1.13 g/cm^3) and
        // the Yeoh fit of Polygerinos et al. 2015 (C10 = 0.11 MPa, C20 = 0.02 MPa).
        m.law = MaterialLaw::Yeoh;
        m.c10Kpa = 110;
        m.c20Kpa = 20;
        m.tensileStrengthKpa = 6500;
        m.elongationAtBreak = 7.0;
        m.densityKgPerM3 = 1130;
        return m;
    }
    const PresetRow* row = RowOf(preset);
    if (!row) return MaterialDef{};
    m.tensileStrengthKpa = row->tensilePsi * kPsi;
    m.elongationAtBreak = row->elongation;
    m.densityKgPerM3 = row->densityKgPerM3;
    if (preset == row->datasheet) {
        // The nominal uniaxial stress of a neo-Hookean solid at stretch 2 is mu (2 - 1/4) = 1.75 mu.
        m.law = MaterialLaw::NeoHookean;
        m.muKpa = row->modulus100Psi * kPsi / 1.75;
    } else {
        m.law = MaterialLaw::Yeoh;
        m.c10Kpa = row->c10Kpa;
        m.c20Kpa = row->c20Kpa;
    }
    return m;
}

MaterialSource MaterialPresetSource(MaterialPreset preset) {
    MaterialSource s;
    if (preset == MaterialPreset::Elastosil4601) {
        s.source = "Yeoh constants of Polygerinos et al. 2015 (Adv. Eng. Mater., 'Modeling of soft fiber-reinforced bending actuators'); limits and density from Wacker's data sheet";
        s.conditions = "as published (uniaxial tests of the authors)";
        return s;
    }
    const PresetRow* row = RowOf(preset);
    if (!row) return s;
    if (preset == row->datasheet) {
        s.source = "Smooth-On technical bulletin: neo-Hookean mu = 100 % modulus / 1.75; limits and density from the same bulletin";
        s.conditions = "supplier's typical values (ASTM D412 die C)";
        return s;
    }
    s.source = std::string("two-term Yeoh fitted to Marechal et al. 2021, Soft Robotics Materials Database (github.com/LucMarechal/Soft-Robotics-Materials-Database, ODbL 1.0), "
                           "Tensile-Tests-Data/") + row->databaseFile + "; limits and density from Smooth-On's technical bulletin";
    s.conditions = "ASTM D412 dumbbell, 3 x 6 mm section, 33 mm gauge length, pulled to failure at 450 mm/min on an Instron 5569 (1 kN cell), strain from the crosshead, one specimen";
    s.fitMaxStrain = kFitMaxStrain;
    s.fitRmsKpa = row->fitRmsKpa;
    s.fitRelativeRms = row->fitRelativeRms;
    s.datasheet = row->datasheet;
    return s;
}

std::vector<TensilePoint> MaterialPresetPoints(MaterialPreset preset) {
    const PresetRow* row = RowOf(preset);
    return row && row->fitted == preset ? row->points() : std::vector<TensilePoint>{};
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

namespace {
std::string Millimetres(double mm) {
    char text[64];
    std::snprintf(text, sizeof text, "%.4g mm", mm);
    return text;
}
}  // namespace

std::string ShellDefError(const ShellDef& d) {
    const GeometryDef& g = d.geometry;
    auto positive = [](double v) { return std::isfinite(v) && v > 0; };
    if (!positive(g.radiusMm)) return "radius must be a positive number of millimetres";
    if (!positive(g.lengthMm)) return "length must be a positive number of millimetres";
    if (!positive(g.thicknessMm)) return "wall thickness must be a positive number of millimetres";
    if (g.thicknessMm >= g.radiusMm) return "the wall (" + std::to_string(g.thicknessMm) + " mm) must be thinner than the radius (" + std::to_string(g.radiusMm) + " mm)";
    if (g.ringVertices < 6) return "a ring needs at least 6 vertices";
    if (!positive(g.clampMm)) return "the clamp length must be a positive number of millimetres";
    if (g.ends == EndCondition::Clamped && 2 * g.clampMm >= g.lengthMm)
        return "the clamps (" + Millimetres(g.clampMm) + " each) leave no free length on a " + Millimetres(g.lengthMm) + " tube";
    if (!(g.edgeSpacingMm >= 0) || !std::isfinite(g.edgeSpacingMm)) return "the clamps' edge spacing is 0 (evenly spaced rings) or a positive number of millimetres";
    const int rings = RingCount(g);
    if (rings < 6) return "the tube needs at least 6 rings";
    if (g.ends == EndCondition::Clamped && rings - 1 - 2 * ClampIntervals(g) < 3)
        return "the tube needs at least two free rings between its clamps: " + std::to_string(rings) + " rings put " + std::to_string(ClampRingCount(g)) +
               " in each " + Millimetres(g.clampMm) + " clamp";
    const MaterialDef& m = d.material;
    for (const double bound : {d.envelope.maxRadiusRatio, d.envelope.maxRadiusMm, d.envelope.maxSiliconeG})
        if (!(bound >= 0) || !std::isfinite(bound)) return "an envelope's bounds are 0 (none) or positive";
    if (d.envelope.maxRadiusRatio > 0 && d.envelope.maxRadiusRatio < 1)
        return "the envelope's max_radius_ratio is below 1: not even the plain tube fits it";
    if (d.envelope.maxSiliconeG > 0 && !(m.densityKgPerM3 > 0)) return "the envelope's max_silicone_g needs the material's density_kg_per_m3";
    const double modulus = ShearModulusKpa(m);
    if (!positive(modulus)) return "the material's shear modulus must be positive (set mu, or C10 and C01)";
    for (double c : {m.muKpa, m.c10Kpa, m.c01Kpa, m.c20Kpa, m.c30Kpa})
        if (!std::isfinite(c)) return "material constants must be finite numbers";
    // The higher constants may be negative (fits often make them so); the solver then reports a state
    // past the law's stable range as material-unstable (DruckerStability).
    if (m.muKpa < 0 || m.c10Kpa < 0) return "mu and C10 must not be negative";
    if (!std::isfinite(m.tensileStrengthKpa) || m.tensileStrengthKpa < 0 || !std::isfinite(m.elongationAtBreak) || m.elongationAtBreak < 0)
        return "tensile strength and elongation must be finite and not negative";
    if (!std::isfinite(m.stretchLimit) || (m.stretchLimit != 0 && m.stretchLimit <= 1)) return "the stretch limit must be above 1";
    if (!(StretchLimit(m) > 1))
        return "the material has no stretch limit: give stretch_limit (the largest principal stretch the silicone may take) or elongation_at_break "
               "(a preset has both)";
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
    if (d.solver.newtonBudget < 0) return "the Newton budget is 0 (none) or a positive count of iterations";
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
