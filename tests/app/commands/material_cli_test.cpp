// `actuator material list|show|fit` as a user runs them, and a material file used wherever a preset
// is: --material FILE.json, an experiment's material.file. Bad curves are refused with one line
// naming the row, exit code 2 and nothing written.
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <sstream>

#include "cli_fixture.h"
#include "formats/table.h"
#include "sim/material_fit.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using MaterialCli = CliTest;

namespace {

// The synthetic curves' law: two-term Yeoh, C10 12 kPa, C20 0.3 kPa.
sim::MaterialDef SyntheticMaterial() {
    sim::MaterialDef m;
    m.law = sim::MaterialLaw::Yeoh;
    m.c10Kpa = 12;
    m.c20Kpa = 0.3;
    return m;
}

// Its curve in MPa, with a test machine's preamble and a column of true stress that must be left
// alone, as the database's files have.
std::string SyntheticCurve() {
    const sim::MaterialDef m = SyntheticMaterial();
    std::ostringstream text;
    text << "Machine;Instron\nSpeed (mm/min);450\n;;\nTime (s);True Stress (MPa);Engineering Strain;Engineering Stress (MPa)\n";
    for (int k = 1; k <= 120; ++k) {
        const double strain = 0.025 * k;
        const double stress = sim::UniaxialStressKpa(m, 1 + strain) * 1e-3;
        text << k << ";" << stress * (1 + strain) << ";" << strain << ";" << stress << "\n";
    }
    return text.str();
}

}  // namespace

TEST_F(MaterialCli, AFitRecoversTheCurvesConstantsAndItsFileWorksAsAPreset) {
    Write("test.csv", SyntheticCurve());
    const Result r = Run("material fit " + Path("test.csv") + " --out " + Path("mix.json"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("C10 12 kPa, C20 0.3 kPa"));
    EXPECT_THAT(r.out, HasSubstr("Drucker-stable"));
    const auto file = nlohmann::json::parse(Slurp(dir_ / "mix.json"));
    EXPECT_EQ(file["format"], "actuator-material");
    EXPECT_EQ(file["name"], "test");
    EXPECT_NEAR(file["material"]["c10_kpa"].get<double>(), 12, 1e-6);
    EXPECT_NEAR(file["material"]["c20_kpa"].get<double>(), 0.3, 1e-6);
    EXPECT_NEAR(file["material"]["stretch_limit"].get<double>(), 3, 1e-9) << "1 + the largest strain fitted (200 %)";
    EXPECT_EQ(file["fit"]["points"], 80);
    EXPECT_EQ(file["fit"]["stress_unit"], "MPa");
    testing_support::ExpectPicture(dir_ / "mix.png");

    // The same tube under the file and under the same constants given as options.
    const std::string tube = " --model membrane --shape cylinder --ring-vertices 16 --rings 20 --steps 2 --pressure-kpa 1";
    const auto viaFile = nlohmann::json::parse(Run("simulate --material " + Path("mix.json") + tube).out);
    const auto viaOptions = nlohmann::json::parse(
        Run("simulate --material custom --law yeoh --c10-kpa " + file["material"]["c10_kpa"].dump() + " --c20-kpa " + file["material"]["c20_kpa"].dump() +
            " --stretch-limit 3" + tube)
            .out);
    ASSERT_EQ(viaFile["status"], "ok");
    EXPECT_EQ(viaFile["contraction_percent"], viaOptions["contraction_percent"]);
    EXPECT_EQ(viaFile["stretch_limit"], 3);

    // The model's own uniaxial response: a tube on sliding end plates pulled to the curve's stress at
    // 100 % strain stretches to 2 (the mesh and the fit within 2 %).
    const double stressKpa = sim::UniaxialStressKpa(SyntheticMaterial(), 2);
    const Result pulled = Run("simulate --model membrane --shape cylinder --material " + Path("mix.json") +
                              " --radius-mm 10 --length-mm 40 --thickness-mm 0.5 --ring-vertices 24 --rings 0 --ends sliding --load force --steps 8 --force-n " +
                              std::to_string(stressKpa * 1e-3 * 2 * std::numbers::pi * 10 * 0.5));
    ASSERT_EQ(pulled.exitCode, 0) << pulled.err;
    const auto pulledJson = nlohmann::json::parse(pulled.out);
    ASSERT_EQ(pulledJson["status"], "ok");
    EXPECT_NEAR(1 + pulledJson["displacement_mm"].get<double>() / 40, 2, 0.04);

    // In an experiment file, relative to the experiment's folder; the run keeps the constants.
    fs::create_directories(dir_ / "study");
    fs::copy_file(dir_ / "mix.json", dir_ / "study" / "mix.json");
    Write("study/one.json", R"({"id": "one", "model": {"name": "membrane", "geometry": {"ring_vertices": 16, "rings": 20},
        "material": {"file": "mix.json"}, "load": {"pressure_kpa": 1, "steps": 2}},
        "evaluate": {"shapes": [{"family": "cylinder"}]}, "render": {"figures": false, "thumbnails": false}})");
    const Result run = Run("sweep " + Path("study/one.json") + " --out " + Path("runs"));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const app::Table table = app::Table::Read((dir_ / "runs" / "evaluations.csv").string());
    EXPECT_NEAR(table.Number(0, "contraction_percent"), viaFile["contraction_percent"].get<double>(), 1e-9);
    const auto kept = nlohmann::json::parse(Slurp(dir_ / "runs" / "experiment.json"));
    EXPECT_EQ(kept["model"]["material"]["law"], "yeoh");
    EXPECT_FALSE(kept["model"]["material"].contains("file"));
    ExpectRefused("sweep " + Path("study/one.json") + " --set model.material.preset=dragon-skin-10 --out " + Path("runs2"), "not both");
}

TEST_F(MaterialCli, ListAndShowNameEverySourceAndDrawTheCurveBesideItsData) {
    const Result list = Run("material list");
    ASSERT_EQ(list.exitCode, 0) << list.err;
    for (const char* name : {"ecoflex-00-30 ", "ecoflex-00-50 ", "dragon-skin-10 ", "dragon-skin-20 ", "dragon-skin-30 ", "elastosil-m4601", "ecoflex-00-30-datasheet"})
        EXPECT_THAT(list.out, HasSubstr(name));
    EXPECT_THAT(list.out, HasSubstr("Marechal et al. 2021"));
    const Result show = Run("material show dragon-skin-20 --figure " + Path("ds20.png"));
    ASSERT_EQ(show.exitCode, 0) << show.err;
    EXPECT_THAT(show.out, HasSubstr("ASTM D412"));
    EXPECT_THAT(show.out, HasSubstr("measured 318.4 kPa"));
    EXPECT_THAT(show.out, HasSubstr("beyond the fitted range"));
    testing_support::ExpectPicture(dir_ / "ds20.png");
    ExpectRefused("material show dragon-skin-20 --figure " + Path("ds20.png"), "already exists");
    ExpectRefused("material show unobtainium", "ecoflex-00-30");
    ExpectRefused("material melt", "list, show, fit");
}

TEST_F(MaterialCli, BadCurvesAreRefusedNamingTheRowAndNothingIsWritten) {
    struct Case {
        const char* name;
        std::string text;
        std::string mentions;
        std::string options = "";
    };
    const std::string header = "strain,stress_kpa\n";
    for (const Case& c : {Case{"text.csv", header + "0.1,3\n0.2,abc\n", "row 3: 'abc' in 'stress_kpa' is not a number"},
                          Case{"falls.csv", header + "0.1,3\n0.3,9\n0.2,7\n", "row 4: strain 0.2 is below"},
                          Case{"one.csv", header + "0.1,3\n", "1 point"},
                          Case{"negative.csv", header + "0.1,3\n0.2,-1\n", "row 3: negative stress"},
                          Case{"nounit.csv", "strain,stress\n0.1,3\n0.2,6\n", "names no unit"},
                          Case{"psi.csv", "strain,stress (psi)\n0.1,3\n0.2,6\n", "names the unit 'psi'"},
                          Case{"clash.csv", header + "0.1,3\n0.2,6\n", "another unit", " --unit mpa"},
                          Case{"noheader.csv", "a,b\n1,2\n", "no header row"},
                          Case{"short.csv", header + "0.1,3\n0.2\n", "row 3: has 1 fields"}}) {
        Write(c.name, c.text);
        ExpectRefused("material fit " + Path(c.name) + " --out " + Path("mix.json") + c.options, c.mentions);
    }
    ExpectRefused("material fit " + Path("missing.csv") + " --out " + Path("mix.json"), "missing.csv");
    Write("ok.csv", SyntheticCurve());
    ExpectRefused("material fit " + Path("ok.csv") + " --law neo-hookean --terms 2 --out " + Path("mix.json"), "--terms applies to --law yeoh");
    ExpectRefused("material fit " + Path("ok.csv") + " --out " + Path("mix.txt"), "must end in .json");
    EXPECT_FALSE(fs::exists(dir_ / "mix.json"));
    EXPECT_FALSE(fs::exists(dir_ / "mix.png"));
    // An existing output is not replaced without --overwrite.
    ASSERT_EQ(Run("material fit " + Path("ok.csv") + " --out " + Path("mix.json")).exitCode, 0);
    ExpectRefused("material fit " + Path("ok.csv") + " --law neo-hookean --out " + Path("mix.json"), "--overwrite");
    EXPECT_THAT(Slurp(dir_ / "mix.json"), HasSubstr("yeoh"));
}

TEST_F(MaterialCli, AnUnstableFitIsWarnedAboutAndBadMaterialFilesAreRefused) {
    // A curve that softens: a three-term Yeoh fit turns unstable within its range.
    sim::MaterialDef m;
    m.law = sim::MaterialLaw::Yeoh;
    m.c10Kpa = 20;
    m.c20Kpa = -0.8;
    m.c30Kpa = 0.01;
    std::string text = "strain,stress_kpa\n";
    for (int k = 1; k <= 60; ++k) text += std::to_string(0.05 * k) + "," + std::to_string(sim::UniaxialStressKpa(m, 1 + 0.05 * k)) + "\n";
    Write("soft.csv", text);
    const Result r = Run("material fit " + Path("soft.csv") + " --terms 3 --max-strain 3 --out " + Path("soft.json"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("warning"));
    EXPECT_THAT(r.out, HasSubstr("NOT Drucker-stable"));
    // Material files: not one, a typo, an unknown law, constants a model refuses.
    Write("other.json", R"({"format": "something-else"})");
    ExpectRefused("simulate --material " + Path("other.json"), "not a material file");
    Write("typo.json", R"({"format": "actuator-material", "version": 1, "material": {"law": "yeoh", "c10kpa": 3}})");
    ExpectRefused("simulate --material " + Path("typo.json"), "'material.c10kpa': unknown key");
    Write("law.json", R"({"format": "actuator-material", "version": 1, "material": {"law": "ogden", "c10_kpa": 3}})");
    ExpectRefused("simulate --material " + Path("law.json"), "neo-hookean, mooney-rivlin or yeoh");
    Write("nolimit.json", R"({"format": "actuator-material", "version": 1, "material": {"law": "yeoh", "c10_kpa": 3}})");
    ExpectRefused("simulate --material " + Path("nolimit.json"), "no stretch limit");
    ExpectRefused("simulate --material " + Path("absent.json"), "absent.json");
    // A custom material with no limit is refused rather than over-stretched on every run.
    ExpectRefused("simulate --material custom --mu-kpa 30", "no stretch limit");
}
