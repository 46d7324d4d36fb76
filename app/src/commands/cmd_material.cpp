// `actuator material list|show|fit`: the silicones the models know, where each comes from, and a
// user's own tensile test made into a material file (docs/guide/materials.md).
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "commands/registry.h"
#include "formats/files.h"
#include "materials/material_file.h"
#include "materials/tensile_curve.h"
#include "options/cli.h"
#include "pictures/figures.h"
#include "pictures/plots.h"
#include "sim/material_fit.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// "C10 7.859 kPa, C20 0.0943 kPa": the constants the law uses.
std::string ConstantsText(const sim::MaterialDef& m) {
    switch (m.law) {
        case sim::MaterialLaw::NeoHookean: return fmt::format("mu {:.4g} kPa", m.muKpa);
        case sim::MaterialLaw::MooneyRivlin: return fmt::format("C10 {:.4g} kPa, C01 {:.4g} kPa", m.c10Kpa, m.c01Kpa);
        case sim::MaterialLaw::Yeoh:
            return fmt::format("C10 {:.4g} kPa, C20 {:.4g} kPa", m.c10Kpa, m.c20Kpa) + (m.c30Kpa != 0 ? fmt::format(", C30 {:.4g} kPa", m.c30Kpa) : "");
    }
    return "";
}

std::string StabilityText(const sim::StabilityCheck& check, double upTo) {
    if (check.stable) return fmt::format("Drucker-stable in uniaxial, equibiaxial and planar tension up to stretch {:.3g}", upTo);
    return fmt::format("NOT Drucker-stable: {} tension fails at stretch {:.3g} (below {:.3g})", check.mode, check.failingStretch, upTo);
}

void WriteFigure(const std::string& path, const TensileFigure& figure) { WritePng(path, TensileCurveImage(figure), 6); }

int RunList(int argc, char** argv, int first) {
    Cli cli("material list", "Lists the silicone presets: law, constants, where they come from and their stretch limit. `actuator material show NAME` "
                             "says more and draws the curve.");
    if (!cli.Parse(argc, argv, first)) return 0;
    std::cout << fmt::format("{:<26} {:<12} {:<34} {:>7} {:>7}  {}\n", "preset", "law", "constants", "mu kPa", "limit", "source");
    for (const auto& [preset, name] : sim::EnumNames<sim::MaterialPreset>::table) {
        if (preset == sim::MaterialPreset::Custom) continue;
        const sim::MaterialDef m = sim::MaterialPresetDef(preset);
        const sim::MaterialSource s = sim::MaterialPresetSource(preset);
        const std::string from = s.fitMaxStrain > 0 ? fmt::format("fitted to Marechal et al. 2021, 0-{:g} % strain, rms {:.2g} kPa ({:.1f} %)", 100 * s.fitMaxStrain,
                                                                  s.fitRmsKpa, 100 * s.fitRelativeRms)
                                 : preset == sim::MaterialPreset::Elastosil4601 ? std::string("Polygerinos et al. 2015")
                                                                                : std::string("Smooth-On data sheet, 100 % modulus / 1.75");
        std::cout << fmt::format("{:<26} {:<12} {:<34} {:>7.3g} {:>7.3g}  {}\n", name, sim::Name(m.law), ConstantsText(m), sim::ShearModulusKpa(m),
                                 sim::StretchLimit(m), from);
    }
    std::cout << "mu: small-strain shear modulus; limit: the largest principal stretch allowed (1 + half the elongation at break)\n";
    return 0;
}

int RunShow(int argc, char** argv, int first) {
    Cli cli("material show", "Shows a preset or a material file: law and constants, limits, density, source and test conditions, the fit's range and "
                             "residual, stability, and the stress at 100 % and 200 % strain beside the measurement.");
    std::string name, figure;
    cli.App().add_option("material", name, "a preset's name or a material file")->required()->type_name("NAME|FILE.json");
    cli.Text("--figure", figure, "draw the uniaxial curve beside its measured points (and a fitted preset's data-sheet law, dashed)")->type_name("FILE.png");
    if (!cli.Parse(argc, argv, first)) return 0;
    if (cli.Given("--figure")) {
        CheckOutputPath(figure, "--figure");
        if (fs::exists(fs::symlink_status(figure))) throw UsageError("--figure: " + Quote(figure) + " already exists; remove it or give another name");
    }
    const MaterialFile file = IsMaterialFileName(name) ? ReadMaterialFile(name) : MaterialFile{};
    const sim::MaterialDef m = IsMaterialFileName(name) ? file.material : MaterialNamed(name, "material show");
    const sim::MaterialSource s = sim::MaterialPresetSource(m.preset);
    const std::vector<sim::TensilePoint> points = sim::MaterialPresetPoints(m.preset);
    const double limit = sim::StretchLimit(m);
    std::cout << "material     " << name << "\n";
    std::cout << "law          " << sim::Name(m.law) << ": " << ConstantsText(m) << fmt::format(" (small-strain shear modulus {:.4g} kPa)\n", sim::ShearModulusKpa(m));
    std::cout << fmt::format("limits       stretch limit {:.3g}; tensile strength {:.4g} kPa; elongation at break {:.0f} %\n", limit, m.tensileStrengthKpa,
                             100 * m.elongationAtBreak);
    std::cout << (m.densityKgPerM3 > 0 ? fmt::format("density      {:g} kg/m^3\n", m.densityKgPerM3) : std::string("density      not given\n"));
    if (!s.source.empty()) std::cout << "source       " << s.source << "\n" << "test         " << s.conditions << "\n";
    std::string fileFit;  // a material file's record of its fit
    if (IsMaterialFileName(name)) {
        const Json& fit = file.fit;
        if (fit.is_object() && fit.contains("curve") && fit.contains("rms_residual_kpa"))
            fileFit = fmt::format("{} fitted to {}, {} points up to {:g} % strain, rms {:.3g} kPa", fit.value("law", std::string("?")),
                                  fit.value("curve", std::string("?")), fit.value("points", 0), 100 * fit.value("largest_strain_fitted", 0.0),
                                  fit.value("rms_residual_kpa", 0.0));
        std::cout << "name         " << (file.name.empty() ? std::string("(none)") : file.name) << "\n";
        if (!fileFit.empty()) std::cout << "fit          " << fileFit << "\n";
    }
    if (s.fitMaxStrain > 0)
        std::cout << fmt::format("fit          0-{:g} % engineering strain, rms residual {:.3g} kPa ({:.2f} % of the rms stress)\n", 100 * s.fitMaxStrain, s.fitRmsKpa,
                                 100 * s.fitRelativeRms);
    if (s.fitMaxStrain > 0 && limit > 1 + s.fitMaxStrain)
        std::cout << fmt::format("note         the stretch limit {:.3g} lies beyond the fitted range (stretch {:.3g}): the law there is an extrapolation\n", limit,
                                 1 + s.fitMaxStrain);
    std::cout << "stability    " << StabilityText(sim::DruckerStability(m, limit), limit) << "\n";
    for (double strain : {1.0, 2.0}) {
        std::string measured;
        for (const sim::TensilePoint& p : points)
            if (std::abs(p.strain - strain) < 1e-3) measured = fmt::format(" (measured {:.4g} kPa)", p.stressKpa);
        std::cout << fmt::format("at {:>3.0f} %     {:.4g} kPa{}\n", 100 * strain, sim::UniaxialStressKpa(m, 1 + strain), measured);
    }
    if (cli.Given("--figure")) {
        TensileFigure f;
        f.title = name + "  -  uniaxial tension";
        f.subtitle = s.fitMaxStrain > 0 ? fmt::format("{}, fitted 0-{:g} %, rms {:.3g} kPa", sim::Name(m.law), 100 * s.fitMaxStrain, s.fitRmsKpa)
                     : !fileFit.empty() ? fileFit
                                        : std::string(sim::Name(m.law)) + " (no measured points ship with it)";
        f.measured = points;
        f.measuredLabel = "measured (Marechal et al. 2021, ODbL)";
        f.laws.push_back({name + ": " + ConstantsText(m), m, false});
        if (const sim::MaterialPreset datasheet = s.datasheet; datasheet != sim::MaterialPreset::Custom) {
            const sim::MaterialDef d = sim::MaterialPresetDef(datasheet);
            f.laws.push_back({std::string(sim::Name(datasheet)) + ": " + ConstantsText(d), d, true});
        }
        f.fitMaxStrain = s.fitMaxStrain;
        f.maxStrain = points.empty() ? std::min(3.0, limit - 1) : points.back().strain;
        WriteFigure(figure, f);
        std::cout << "figure       " << figure << "\n";
    }
    return 0;
}

int RunFit(int argc, char** argv, int first) {
    Cli cli("material fit",
            "Fits a hyperelastic law to a uniaxial tensile test (least squares on engineering stress) and writes a material file usable wherever a "
            "preset is (--material FILE.json, an experiment's material.file, Python's Material.from_file), with a figure of data and fit.");
    std::string curvePath, out, figure, name, unitName;
    sim::MaterialFitDef def;
    double stretchLimit = 0, tensileKpa = 0, density = 0;
    bool overwrite = false;
    cli.App().add_option("curve", curvePath, "engineering strain and stress, one header row naming them (docs/guide/materials.md)")->required()->type_name("CURVE.csv");
    cli.Enum("--law", def.law, "the law to fit");
    cli.Integer("--terms", def.terms, "Yeoh: how many constants, C10 to C30", 1, 3);
    cli.Number("--max-strain", def.maxStrain, "fit the points up to this engineering strain (2 = 200 %)", 1e-3, 100);
    cli.Text("--unit", unitName, "the stress's unit when the header does not name it: kpa or mpa")->type_name("kpa|mpa");
    cli.Text("--out", out, "the material file to write")->required()->type_name("FILE.json");
    cli.Text("--figure", figure, "the figure of data and fit (default: --out with .png)")->type_name("FILE.png");
    cli.Text("--name", name, "the material's name in the file (default: the curve file's name)");
    cli.Number("--stretch-limit", stretchLimit, "the largest principal stretch the models allow", 1, 100)->default_str("1 + the largest strain fitted");
    cli.Number("--tensile-strength-kpa", tensileKpa, "tensile strength, kPa", 0, kUnbounded)->default_str("the largest stress measured");
    cli.Number("--density-kg-per-m3", density, "density, kg/m^3 (for the silicone's mass in exports)", 0, kUnbounded)->default_str("not given");
    cli.Flag("--overwrite", overwrite, "replace existing output files");
    if (!cli.Parse(argc, argv, first)) return 0;
    if (cli.Given("--terms") && def.law != sim::MaterialLaw::Yeoh) throw UsageError("--terms applies to --law yeoh (neo-Hookean has 1 constant, Mooney-Rivlin 2)");
    StressUnit unit = StressUnit::FromHeader;
    if (cli.Given("--unit")) {
        if (unitName == "kpa") unit = StressUnit::Kpa;
        else if (unitName == "mpa") unit = StressUnit::Mpa;
        else throw UsageError("--unit: unknown value " + Quote(unitName) + " (choose kpa, mpa)");
    }
    if (!IsMaterialFileName(out)) throw UsageError("--out: " + Quote(out) + " must end in .json (a material file)");
    if (!cli.Given("--figure")) figure = out.substr(0, out.size() - 5) + ".png";
    for (const auto& [path, what] : {std::pair{out, "--out"}, std::pair{figure, "--figure"}}) {
        CheckOutputPath(path, what);
        RefuseOutputThatIsInput(path, what, {curvePath});
        if (!overwrite && fs::exists(fs::symlink_status(path))) throw UsageError(std::string(what) + ": " + Quote(path) + " already exists; add --overwrite to replace it");
    }
    if (figure == out) throw UsageError("--figure must differ from --out");

    const TensileCurve curve = ReadTensileCurve(curvePath, unit);
    sim::MaterialDef base;
    double largestStrain = 0, largestStress = 0;
    for (const sim::TensilePoint& p : curve.points) largestStrain = std::max(largestStrain, p.strain), largestStress = std::max(largestStress, p.stressKpa);
    base.tensileStrengthKpa = cli.Given("--tensile-strength-kpa") ? tensileKpa : largestStress;
    base.elongationAtBreak = largestStrain;
    base.densityKgPerM3 = density;
    sim::MaterialFit fit = sim::FitMaterial(curve.points, def, base);
    if (!fit.error.empty()) throw UsageError(curvePath + ": " + fit.error);
    fit.material.stretchLimit = cli.Given("--stretch-limit") ? stretchLimit : 1 + fit.maxStrainFitted;
    if (!(fit.material.stretchLimit > 1)) throw UsageError("--stretch-limit must be above 1");
    if (sim::ShearModulusKpa(fit.material) <= 0 || fit.material.c10Kpa < 0 || fit.material.muKpa < 0)
        throw UsageError(curvePath + ": the fitted " + std::string(sim::Name(def.law)) + " law has a shear modulus that is not positive (" + ConstantsText(fit.material) +
                         "): the curve does not look like a rubber's in tension; check the columns and the unit");
    if (name.empty()) name = fs::path(curvePath).stem().string();
    const sim::StabilityCheck stability = sim::DruckerStability(fit.material, fit.material.stretchLimit);

    Json fitJson = Json::object();
    fitJson["curve"] = fs::path(curvePath).filename().string();
    fitJson["strain_column"] = curve.strainColumn;
    fitJson["stress_column"] = curve.stressColumn;
    fitJson["stress_unit"] = curve.unit;
    fitJson["law"] = sim::Name(def.law);
    if (def.law == sim::MaterialLaw::Yeoh) fitJson["terms"] = def.terms;
    fitJson["max_strain"] = def.maxStrain;
    fitJson["points"] = fit.points;
    fitJson["specimens"] = fit.specimens;
    fitJson["largest_strain_fitted"] = fit.maxStrainFitted;
    fitJson["rms_residual_kpa"] = fit.rmsKpa;
    fitJson["max_residual_kpa"] = fit.maxErrorKpa;
    fitJson["relative_rms_residual"] = fit.relativeRms;
    fitJson["drucker_stable_to_stretch_limit"] = stability.stable;

    TensileFigure f;
    f.title = name + "  -  " + std::string(sim::Name(def.law)) + " fitted to " + fs::path(curvePath).filename().string();
    f.subtitle = fmt::format("{} points, 0-{:g} % strain used, rms residual {:.3g} kPa ({:.2f} %)", fit.points, 100 * def.maxStrain, fit.rmsKpa, 100 * fit.relativeRms);
    f.measured = curve.points;
    f.measuredLabel = fmt::format("measured ({} specimen{})", curve.specimens, curve.specimens == 1 ? "" : "s");
    f.laws.push_back({"fit: " + ConstantsText(fit.material), fit.material, false});
    f.fitMaxStrain = std::min(def.maxStrain, largestStrain);
    f.maxStrain = std::min(largestStrain, std::max(1.5 * def.maxStrain, fit.maxStrainFitted));

    OutputBatch batch;
    WriteFileAtomically(out, MaterialFileText(name, fit.material, fitJson));
    WriteFigure(figure, f);
    batch.Commit();
    std::cout << "law          " << sim::Name(def.law) << "\n";
    std::cout << "constants    " << ConstantsText(fit.material) << fmt::format(" (small-strain shear modulus {:.4g} kPa)\n", sim::ShearModulusKpa(fit.material));
    std::cout << fmt::format("residual     rms {:.3g} kPa ({:.2f} % of the rms stress), largest {:.3g} kPa, over {} points of {} specimen{}, strain 0-{:g} %\n", fit.rmsKpa,
                             100 * fit.relativeRms, fit.maxErrorKpa, fit.points, fit.specimens, fit.specimens == 1 ? "" : "s", 100 * fit.maxStrainFitted);
    std::cout << fmt::format("limits       stretch limit {:.3g}, tensile strength {:.4g} kPa\n", fit.material.stretchLimit, fit.material.tensileStrengthKpa);
    std::cout << "stable       " << StabilityText(stability, fit.material.stretchLimit) << "\n";
    if (!stability.stable)
        std::cout << "warning      the law is not stable within the range: a wall stretched past " << fmt::format("{:.3g}", stability.failingStretch)
                  << " ends material-unstable; fit fewer terms or a smaller --max-strain\n";
    std::cout << "wrote        " << out << ", " << figure << "\n";
    return 0;
}

int RunMaterial(int argc, char** argv, int first) {
    const std::string usage = "usage: actuator material list | show NAME|FILE.json [--figure FILE.png] | fit CURVE.csv --out FILE.json [options]; add --help to any";
    if (first >= argc) throw UsageError(usage);
    const std::string verb = argv[first];
    if (verb == "list") return RunList(argc, argv, first + 1);
    if (verb == "show") return RunShow(argc, argv, first + 1);
    if (verb == "fit") return RunFit(argc, argv, first + 1);
    if (verb == "--help" || verb == "-h") {
        std::cout << usage << "\n  list   the presets\n  show   one preset or material file, with its curve\n  fit    a material file from your tensile test\n";
        return 0;
    }
    throw UsageError("material: unknown action " + Quote(verb) + " (choose list, show, fit)");
}

}  // namespace

static const RegisterCommand kMaterialCommand{{"material", "silicones: list the presets, show one, fit your own tensile test into a material file", 75, RunMaterial}};

}  // namespace app
