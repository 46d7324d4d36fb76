// The membrane and shell models through every command, as a user runs them: simulate's JSON in
// physical units, render's pictures, sweeps over pressure, GA runs, archives and --from, and every
// kind of bad input refused with one line, exit code 2 and nothing written.
#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "formats/table.h"
#include "formats/csv.h"
#include "reproduce.h"
#include "sim/model.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using ShellCli = CliTest;

namespace {

// A small, fast mesh and two load steps: the commands' plumbing, not the physics (that is the
// verification label's).
const std::string kSmall = " --ring-vertices 16 --rings 20 --edge-spacing-mm 1 --steps 2";  // rings graded to 1 mm at the clamps: 30 in all

}  // namespace

// The verification tests print the command of a failing evaluation: it must run and give the same
// result, to the bit, for each kind of tube they build (free and held, sliding and clamped ends,
// fibres, a custom law, the self-intersection check off).
TEST_F(ShellCli, AVerificationTestsReproduceLineGivesItsResult) {
    std::vector<sim::EvalJob> jobs(3);
    for (sim::EvalJob& job : jobs) {
        job.SetModel(sim::ModelKind::Membrane);
        job.shape = sim::CylinderShape{};
        sim::ShellDef& d = job.Shell();
        d.geometry.radiusMm = 5;
        d.geometry.lengthMm = 40;
        d.geometry.ringVertices = 12;
        d.geometry.rings = 0;
        d.material = sim::MaterialDef{};
        d.material.muKpa = 0.7;
        d.material.elongationAtBreak = 100;
        d.load.steps = 2;
        d.load.pressureKpa = 0.04;  // P = p R / (mu h) = 0.29: below the plain tube's limit point
    }
    jobs[0].Shell().geometry.ends = sim::EndCondition::Sliding;
    jobs[0].Shell().solver.selfContact = false;
    jobs[1].SetModel(sim::ModelKind::Shell);
    jobs[1].Shell().fibres.layout = sim::FibreLayout::Braid;
    jobs[1].Shell().fibres.angleDeg = 1.0 / 3 * 90;
    jobs[1].Shell().ends.twist = sim::TwistEnd::Held;
    jobs[2].Shell().geometry.ends = sim::EndCondition::Sliding;
    jobs[2].Shell().load.kind = sim::ShellLoad::Blocked;
    jobs[2].Shell().load.strokePercent = 0.1 / 3;
    jobs[2].Shell().fibres.layout = sim::FibreLayout::Braid;
    jobs[2].Shell().contact.mode = sim::ContactMode::Off;
    for (const sim::EvalJob& job : jobs) {
        std::string line = testing_support::ReproduceCommand(job);
        SCOPED_TRACE(line);
        ASSERT_EQ(line.rfind("reproduce: actuator simulate ", 0), 0u);
        line = line.substr(line.find("simulate"));
        line = line.substr(0, line.find("  #"));  // what the command line cannot say, said after it
        const sim::SimResult expected = sim::Evaluate(job);
        const Result r = Run(line);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const auto json = nlohmann::json::parse(r.out);
        ASSERT_EQ(expected.status, sim::Status::Ok) << "a job of this test must be one that solves";
        ASSERT_EQ(json["status"], sim::Name(expected.status));
        EXPECT_EQ(json["contraction_percent"].get<double>(), expected.contractionPercent);
        EXPECT_EQ(json["newton_iterations"].get<int>(), expected.shell.newtonIterations);
    }
}

// The issue's example: a plain tube at P = p R / (mu h) = 0.6 lengthens by about 3 %.
TEST_F(ShellCli, APlainTubeLengthensAndTheJsonCarriesEveryOutputInUnits) {
    const Result r = Run("simulate --model membrane --shape cylinder --radius-mm 10 --length-mm 60 --thickness-mm 1 --mu-kpa 30 "
                         "--ring-vertices 30 --rings 30 --pressure-kpa 1.8 --clamp-mm 2.0689655");  // the clamp of 2 of 30 rings on 60 mm, as measured
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["status"], "ok");
    EXPECT_NEAR(json["contraction_percent"].get<double>(), -3.15, 0.1);
    for (const char* key : {"limit_pressure_kpa", "blocking_force_n", "axial_stiffness_n_per_mm", "volume_mm3", "max_stretch", "max_stress_kpa",
                            "newton_iterations", "curve", "stretch_limit", "tensile_strength_kpa"})
        EXPECT_TRUE(json.contains(key)) << key;
    EXPECT_TRUE(json["limit_pressure_kpa"].is_null()) << "0.6 is below the tube's limit point";
    EXPECT_LT(json["blocking_force_n"].get<double>(), 0) << "a lengthening tube pushes on supports that hold it";
    EXPECT_GT(json["axial_stiffness_n_per_mm"].get<double>(), 0);
    EXPECT_GT(json["volume_mm3"].get<double>(), json["rest_volume_mm3"].get<double>());
    EXPECT_GT(json["max_stretch"].get<double>(), 1);
    EXPECT_GT(json["newton_iterations"].get<int>(), 0);
    EXPECT_EQ(json["curve"].size(), 4u);
    EXPECT_EQ(json["curve"].back()["pressure_kpa"], 1.8) << "the last load step is the target pressure, exactly";
    EXPECT_EQ(json["model"]["name"], "membrane");
    EXPECT_EQ(json["model"]["mu_kpa"], 30);
}

TEST_F(ShellCli, PresetsAndOverridesReachTheModel) {
    const auto preset = nlohmann::json::parse(Run("simulate --model membrane --shape cylinder --material dragon-skin-10" + kSmall).out);
    EXPECT_EQ(preset["model"]["material"], "dragon-skin-10");
    const auto softer = nlohmann::json::parse(Run("simulate --model membrane --shape cylinder --material dragon-skin-10 --mu-kpa 20" + kSmall).out);
    EXPECT_EQ(softer["model"]["mu_kpa"], 20);
    EXPECT_EQ(softer["model"]["law"], "neo-hookean");
    // A softer wall at the same pressure stretches more.
    EXPECT_GT(softer["max_stretch"].get<double>(), preset["max_stretch"].get<double>());
}

TEST_F(ShellCli, BadInputIsRefusedWithOneLineAndNothingWritten) {
    const std::string save = " --save-mesh " + Path("out.obj");
    ExpectRefused("simulate --model shell --thickness-mm -1" + save, "--thickness-mm");
    ExpectRefused("simulate --model shell --thickness-mm 0" + save, "--thickness-mm");
    ExpectRefused("simulate --model shell --radius-mm 0" + save, "--radius-mm");
    ExpectRefused("simulate --model shell --length-mm -5" + save, "--length-mm");
    ExpectRefused("simulate --model shell --mu-kpa 0" + save, "shear modulus");
    ExpectRefused("simulate --model shell --mu-kpa -3" + save, "--mu-kpa");
    ExpectRefused("simulate --model shell --pressure-kpa abc" + save, "--pressure-kpa");
    ExpectRefused("simulate --model shell --material unobtainium" + save, "ecoflex-00-30");
    ExpectRefused("simulate --model shell --load stretch" + save, "inflate, gas, volume, force or blocked");
    ExpectRefused("simulate --model shell --iterations 100" + save, "thesis model");
    ExpectRefused("simulate --model thesis --pressure-kpa 3" + save, "membrane and shell");
    ExpectRefused("simulate --model shell --resolution 20" + save, "--ring-vertices");
    ExpectRefused("simulate --model plastic" + save, "thesis, membrane or shell");
    ExpectRefused("render --model shell --shape cylinder --color-by stretch --timelapse 3 --steps 5 --out " + Path("pictures"), "--steps");
    ExpectRefused("render --model thesis --shape cylinder --color-by stress --out " + Path("pictures"), "membrane or shell");
    ExpectRefused("render --model shell --shape cylinder --contact off --color-by gap --out " + Path("pictures"), "--contact on");
    ExpectRefused("simulate --model shell --contact off --contact-gap-fraction 0.05" + save, "applies to --contact on, not --contact off");
    ExpectRefused("simulate --model shell --contact sideways" + save, "off or on");
    // A mesh that is not the model's surface.
    Write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    ExpectRefused("simulate --model shell --mesh " + Path("quad.obj") + save, "triangles");
    Write("few.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
    ExpectRefused("simulate --model shell --mesh " + Path("few.obj") + save, "3 vertices");
    EXPECT_FALSE(fs::exists(dir_ / "out.obj"));
    EXPECT_FALSE(fs::exists(dir_ / "pictures" / "inflation.png"));
}

TEST_F(ShellCli, SavedMeshesReadBackAndAMeshOfAnotherTopologyIsRefused) {
    const Result first = Run("simulate --model membrane --shape sine --amplitude 1" + kSmall + " --save-initial " + Path("rest.obj"));
    ASSERT_EQ(first.exitCode, 0) << first.err;
    const Result again = Run("simulate --model membrane --mesh " + Path("rest.obj") + kSmall);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(nlohmann::json::parse(again.out)["contraction_percent"], nlohmann::json::parse(first.out)["contraction_percent"]);
    // The same vertices with two faces swapped for others: not this mesh's surface.
    std::string text = Slurp(dir_ / "rest.obj");
    const size_t face = text.find("\nf ");
    text.replace(face + 1, text.find('\n', face + 1) - face - 1, "f 1 2 40");
    Write("other.obj", text);
    ExpectRefused("simulate --model membrane --mesh " + Path("other.obj") + kSmall, "expected topology");
}

TEST_F(ShellCli, RenderDrawsStretchThePressureCurveAndAFramePerLoadStep) {
    const Result r = Run("render --model shell --shape sine --amplitude 1.3 --pressure-kpa 1.2 --timelapse 3 --size 320x240" +
                         std::string(" --ring-vertices 16 --rings 20 --out ") + Path("pictures"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["model"], "shell");
    EXPECT_EQ(json["inflation"]["status"], "ok");
    testing_support::ExpectPicture(dir_ / "pictures" / "inflation.png");
    testing_support::ExpectPicture(dir_ / "pictures" / "pressure_curve.png");
    EXPECT_FALSE(fs::exists(dir_ / "pictures" / "stretch.png")) << "the thesis's stretch test is not a shell model's figure";
    for (int k = 0; k < 3; ++k) testing_support::ExpectPicture(dir_ / "pictures" / "timelapse" / ("frame_000" + std::to_string(k) + ".png"));
    EXPECT_FALSE(fs::exists(dir_ / "pictures" / "timelapse" / "frame_0003.png")) << "one frame per load step: --timelapse 3 sets 3 steps";
}

TEST_F(ShellCli, RenderShowsWhereCollapsedWallsTouch) {
    const Result r = Run("render --model shell --shape cylinder --length-mm 60 --ring-vertices 20 --rings 16 --pressure-kpa -0.5 --contact on "
                         "--color-by gap --size 320x240 --out " + Path("pictures"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["inflation"]["status"], "ok");
    EXPECT_GT(json["inflation"]["contact_pairs"].get<int>(), 0);
    EXPECT_LT(json["inflation"]["collapse_pressure_kpa"].get<double>(), 0);
    testing_support::ExpectPicture(dir_ / "pictures" / "inflation.png");
}

// The searches under vacuum: the GA and an optimizer evolve designs whose walls collapse and touch,
// and every design evaluated is a valid state or refused at rest, none passing through itself.
TEST_F(ShellCli, TheGaAndAnOptimizerSearchVacuumDesignsWithContact) {
    const std::string model = R"("model": {"name": "shell", "geometry": {"length_mm": 60, "ring_vertices": 16, "rings": 12, "edge_spacing_mm": 0},
        "load": {"steps": 2, "pressure_kpa": -0.5}, "contact": "on"}, "render": {"figures": false, "thumbnails": false},)";
    Write("ga.json", R"({"id": "ga", "seed": 4, )" + model + R"(
        "evolve": {"runs": 1, "population": 4, "generations": 1, "elite": 1,
                   "genome": {"kind": "bspline", "region": "middle", "splines": 1, "control": [0, 2], "control_step": 0.5}}})");
    Write("cmaes.json", R"({"id": "cmaes", "seed": 3, )" + model + R"(
        "optimizer": {"algorithm": "cmaes", "population": 6, "generations": 1, "objectives": ["contraction"],
                      "genome": {"family": "sine", "amplitude": [0.5, 1.5], "phase_end": [2, 3.1]}}})");
    for (const std::string name : {"ga", "cmaes"}) {
        const Result r = Run("evolve " + Path(name + ".json") + " --out " + Path(name));
        ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
        const app::Table evaluations = app::Table::Read((dir_ / name / "evaluations.csv").string());
        ASSERT_GE(evaluations.Rows(), 4u) << name;
        double best = -INFINITY;
        size_t bestRow = 0;
        for (size_t k = 0; k < evaluations.Rows(); ++k) {
            const std::string status = evaluations.Text(k, "status");
            EXPECT_TRUE(status == "ok" || status == "invalid-geometry") << name << " evaluation " << k << ": " << status;
            if (status == "ok" && evaluations.Number(k, "contraction_percent") > best) {
                best = evaluations.Number(k, "contraction_percent");
                bestRow = k;
            }
        }
        // A collapsed tube shortens: the best design contracts, with its walls in contact.
        EXPECT_GT(best, 0.5) << name;
        const Result again = Run("simulate --from " + Path(name + "/evaluations.capnp") + " --index " + evaluations.Text(bestRow, "evaluation"));
        ASSERT_EQ(again.exitCode, 0) << again.err;
        const auto json = nlohmann::json::parse(again.out);
        EXPECT_EQ(json["contraction_percent"].get<double>(), best) << name;
        EXPECT_GT(json["contact_pairs"].get<int>(), 0) << name;
        EXPECT_LT(json["collapse_pressure_kpa"].get<double>(), 0) << name;
        // The log a researcher reads carries the same contact and collapse outputs.
        EXPECT_EQ(evaluations.Number(bestRow, "contact_pairs"), json["contact_pairs"].get<int>()) << name;
        EXPECT_EQ(evaluations.Number(bestRow, "collapse_pressure_kpa"), json["collapse_pressure_kpa"].get<double>()) << name;
        EXPECT_GE(evaluations.Number(bestRow, "min_gap_mm"), 0) << name;
    }
}

// A sweep over pressure is a design's contraction-pressure curve; its archive gives each point back.
TEST_F(ShellCli, APressureSweepIsTheContractionPressureCurveAndItsArchiveReplays) {
    Write("pressure.json", R"({"id": "p", "model": {"name": "membrane", "geometry": {"ring_vertices": 16, "rings": 20}, "load": {"steps": 2}},
        "sweep": {"shape": {"family": "sine", "amplitude": 1.3}, "axes": [{"parameter": "pressure_kpa", "values": [0.4, 0.8, 1.2]}]},
        "render": {"figures": false, "thumbnails": false}})");
    const Result r = Run("sweep " + Path("pressure.json") + " --out " + Path("runs"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const app::Table results = app::Table::Read((dir_ / "runs" / "results.csv").string());
    ASSERT_EQ(results.Rows(), 3u);
    EXPECT_EQ(results.Numbers("pressure_kpa"), (std::vector<double>{0.4, 0.8, 1.2}));
    const std::vector<double> contraction = results.Numbers("contraction_percent");
    EXPECT_GT(contraction[0], contraction[1]) << "lengthens more with pressure";
    EXPECT_GT(contraction[1], contraction[2]);
    const app::Table log = app::Table::Read((dir_ / "runs" / "evaluations.csv").string());
    EXPECT_EQ(log.Text(0, "model"), "membrane");
    EXPECT_EQ(log.Text(2, "pressure_kpa"), "1.2");
    EXPECT_FALSE(log.Text(2, "max_stretch").empty());
    // The stored job replays to the same number.
    const Result replay = Run("simulate --from " + Path("runs/evaluations.capnp") + " --index 2");
    ASSERT_EQ(replay.exitCode, 0) << replay.err;
    EXPECT_EQ(nlohmann::json::parse(replay.out)["contraction_percent"].get<double>(), contraction[2]);
    // And the thesis model has no pressure axis.
    Write("thesis.json", R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "pressure_kpa", "values": [1, 2]}]}})");
    ExpectRefused("sweep " + Path("thesis.json") + " --out " + Path("never"), "pressure_kpa");
    EXPECT_FALSE(fs::exists(dir_ / "never" / "evaluations.capnp"));
}

TEST_F(ShellCli, ModelBlockKeysThatDoNotApplyAreRefused) {
    const std::string sweep = R"("sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]})";
    Write("a.json", R"({"model": {"name": "thesis", "geometry": {"radius_mm": 5}}, )" + sweep + "}");
    ExpectRefused("sweep " + Path("a.json") + " --out " + Path("a"), "does not apply to the thesis model");
    Write("b.json", R"({"model": {"name": "shell"}, "sim": {"iterations": 100}, )" + sweep + "}");
    ExpectRefused("sweep " + Path("b.json") + " --out " + Path("b"), "thesis model only");
    Write("c.json", R"({"model": {"name": "shell", "material": {"preset": "ecoflex-00-30", "mu_kpa": -1}}, )" + sweep + "}");
    ExpectRefused("sweep " + Path("c.json") + " --out " + Path("c"), "model.material.mu_kpa");
    Write("d.json", R"({"model": {"name": "shell", "geometry": {"thickness": 1}}, )" + sweep + "}");
    ExpectRefused("sweep " + Path("d.json") + " --out " + Path("d"), "model.geometry.thickness_mm");
    for (const char* folder : {"a", "b", "c", "d"}) EXPECT_FALSE(fs::exists(dir_ / folder / "evaluations.capnp")) << folder;
}

// The GA under the membrane model gives the same bytes on one thread or two.
TEST_F(ShellCli, EvolveUnderTheMembraneModelDoesNotDependOnThreads) {
    Write("ga.json", R"({"id": "g", "seed": 4, "model": {"name": "membrane", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 0},
        "load": {"steps": 1, "pressure_kpa": 0.5}},
        "evolve": {"runs": 1, "population": 4, "generations": 1, "elite": 1, "genome": {"kind": "bspline", "region": "middle", "splines": 1}},
        "render": {"figures": false, "thumbnails": false}})");
    ASSERT_EQ(Run("evolve " + Path("ga.json") + " --threads 1 --out " + Path("one")).exitCode, 0);
    ASSERT_EQ(Run("evolve " + Path("ga.json") + " --threads 2 --out " + Path("two")).exitCode, 0);
    for (const char* file : {"evaluations.csv", "run_1/logbook.csv", "run_1/halloffame.csv"})
        EXPECT_EQ(Slurp(dir_ / "one" / file), Slurp(dir_ / "two" / file)) << file;
    const app::Table logbook = app::Table::Read((dir_ / "one" / "run_1" / "logbook.csv").string());
    ASSERT_EQ(logbook.Rows(), 2u);
    EXPECT_FALSE(logbook.Text(0, "best").empty()) << "generation 0 has a best contraction";
}

// Fibres from the command line and from experiment files; bad fibre input refused.
TEST_F(ShellCli, FibresReachTheModelAndBadFibreInputIsRefused) {
    const Result braid = Run("simulate --model membrane --shape cylinder --fibres braid --fibre-angle-deg 30 --fibre-stiffness-n-per-mm 40" + kSmall);
    ASSERT_EQ(braid.exitCode, 0) << braid.err;
    const auto json = nlohmann::json::parse(braid.out);
    EXPECT_GT(json["contraction_percent"].get<double>(), 0) << "a braid at 30 degrees makes the tube contract";
    EXPECT_EQ(json["model"]["fibres"], "braid");
    EXPECT_EQ(json["model"]["fibre_angle_deg"], 30);
    EXPECT_GE(json["max_fibre_strain"].get<double>(), 0);
    EXPECT_GT(json["deformed_fibre_angle_deg"].get<double>(), 30) << "the braid opens towards the magic angle";
    ExpectRefused("simulate --model shell --fibres braid --fibre-angle-deg nan", "--fibre-angle-deg");
    ExpectRefused("simulate --model shell --fibres braid --fibre-angle-deg 91", "--fibre-angle-deg");
    ExpectRefused("simulate --model shell --fibres braid --fibre-stiffness-n-per-mm -2", "--fibre-stiffness-n-per-mm");
    ExpectRefused("simulate --model shell --fibres knitted", "braid");
    ExpectRefused("simulate --model thesis --fibres braid", "membrane and shell");
    const std::string sweep = R"("sweep": {"shape": {"family": "sine", "amplitude": 1}, "axes": [{"parameter": "fibre_angle_deg", "values": [20, 40]}]})";
    Write("gap.json", R"({"model": {"name": "shell", "fibres": "braid", "fibre_bands": [{"from": 0, "to": 0.4, "angle_deg": 20},
        {"from": 0.5, "to": 1, "angle_deg": 40}]}, )" + sweep + "}");
    ExpectRefused("sweep " + Path("gap.json") + " --out " + Path("gap"), "cover the length");
    Write("short.json", R"({"model": {"name": "shell", "fibres": "braid", "fibre_bands": [{"from": 0, "to": 0.7, "angle_deg": 20}]}, )" + sweep + "}");
    ExpectRefused("sweep " + Path("short.json") + " --out " + Path("short"), "up to 1");
    Write("none.json", R"({"model": {"name": "shell"}, )" + sweep + "}");
    ExpectRefused("sweep " + Path("none.json") + " --out " + Path("none"), "fibre_angle_deg axis needs fibres");
    Write("genes.json", R"({"model": {"name": "shell"}, "evolve": {"genome": {"kind": "bspline", "fibre_angles": 1}}})");
    ExpectRefused("evolve " + Path("genes.json") + " --out " + Path("genes"), "fibre genes need fibres");
    for (const char* folder : {"gap", "short", "none", "genes"}) EXPECT_FALSE(fs::exists(dir_ / folder / "evaluations.capnp")) << folder;
}

// A fibre angle sweep: the braid's angle is a sweep axis, and the magic angle shows in the numbers.
TEST_F(ShellCli, AFibreAngleSweepCrossesZeroAtTheMagicAngle) {
    Write("angles.json", R"({"id": "a", "model": {"name": "membrane", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 2}, "load": {"steps": 2},
        "fibres": "braid"}, "sweep": {"shape": {"family": "sine", "amplitude": 1, "phase": ["pi/2", "pi/2"]},
        "axes": [{"parameter": "pressure_kpa", "values": [2, 4]}, {"parameter": "fibre_angle_deg", "values": [35, 75]}]},
        "render": {"thumbnails": false}})");
    const Result r = Run("sweep " + Path("angles.json") + " --out " + Path("angles"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const app::Table results = app::Table::Read((dir_ / "angles" / "results.csv").string());
    ASSERT_EQ(results.Rows(), 4u);
    for (size_t k = 0; k < results.Rows(); ++k) {
        const double angle = results.Number(k, "fibre_angle_deg"), contraction = results.Number(k, "contraction_percent");
        EXPECT_EQ(contraction > 0, angle < 54.7) << "at " << results.Text(k, "pressure_kpa") << " kPa and " << angle << " degrees";
    }
    // Its columns are the model's outputs by name, as the evaluation log writes them.
    const app::Table log = app::Table::Read((dir_ / "angles" / "evaluations.csv").string());
    for (const char* column : {"twist_deg", "torque_n_mm", "max_stretch", "deformed_fibre_angle_deg", "newton_iterations"})
        for (size_t k = 0; k < results.Rows(); ++k) EXPECT_EQ(results.Text(k, column), log.Text(k, column)) << column;
    EXPECT_NEAR(results.Number(0, "twist_deg"), 0, 1e-6);  // a braid does not turn its top
    testing_support::ExpectPicture(dir_ / "angles" / "landscape.png");
}

// The GA searches fibre genes beside the shape's, and they are archived with the design.
TEST_F(ShellCli, TheGaSearchesFibreGenes) {
    Write("genes.json", R"({"id": "g", "seed": 7, "model": {"name": "membrane", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 0},
        "load": {"pressure_kpa": 3, "steps": 1}, "fibres": "braid"},
        "evolve": {"runs": 1, "population": 6, "generations": 2, "elite": 1,
                   "genome": {"kind": "bspline", "region": "middle", "splines": 1, "control": [1, 3], "fibre_angles": 2, "fibre_switches": true}},
        "render": {"figures": false, "thumbnails": false}})");
    const Result r = Run("evolve " + Path("genes.json") + " --out " + Path("genes"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto fame = app::ParseCsv(Slurp(dir_ / "genes" / "run_1" / "halloffame.csv"));
    ASSERT_GE(fame.size(), 2u);
    // The genome: the spline's control points, then two angles and two switches.
    const std::string genome = fame[1][2];
    const std::string fibres = genome.substr(genome.find(';') + 1);
    EXPECT_EQ(std::count(fibres.begin(), fibres.end(), ','), 3) << genome;
    const auto log = app::ParseCsv(Slurp(dir_ / "genes" / "evaluations.csv"));
    const size_t column = static_cast<size_t>(std::find(log[0].begin(), log[0].end(), "fibres") - log[0].begin());
    ASSERT_LT(column, log[0].size());
    EXPECT_EQ(log[1][column], "braid");
    // The archive gives the fibres back: the best design replays to its fitness.
    const Result replay = Run("simulate --from " + Path("genes/evaluations.capnp") + " --index 0");
    ASSERT_EQ(replay.exitCode, 0) << replay.err;
    EXPECT_EQ(nlohmann::json::parse(replay.out)["model"]["fibres"], "braid");
}

// The characteristic curves, read back by column name: the isobaric force falls from the blocked
// force (simulate's blocked test gives it, and the isometric curve ends at it) towards the free
// stroke (simulate's free inflation); bad input is refused with nothing written.
TEST_F(ShellCli, CharacterizeDrawsTheMusclesCurvesFromItsOwnTests) {
    const std::string design = " --shape cylinder --fibres braid --fibre-angle-deg 30" + kSmall;
    const Result r = Run("characterize" + design + " --pressures-kpa 5,10 --points 3 --threads 2 --out " + Path("c"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* name : {"characteristic.csv", "force_contraction.png", "force_pressure.png", "stroke_pressure.png"})
        EXPECT_TRUE(fs::exists(dir_ / "c" / name)) << name;
    const app::Table table = app::Table::Read(Path("c/characteristic.csv"));
    const auto json = nlohmann::json::parse(r.out);
    const Result blocked = Run("simulate" + design + " --load blocked --pressure-kpa 10");
    const Result free = Run("simulate" + design + " --pressure-kpa 10");
    ASSERT_EQ(blocked.exitCode, 0) << blocked.err;
    ASSERT_EQ(free.exitCode, 0) << free.err;
    const double blockedForce = nlohmann::json::parse(blocked.out)["blocking_force_n"].get<double>();
    const double stroke = nlohmann::json::parse(free.out)["contraction_percent"].get<double>();
    EXPECT_NEAR(json["isobaric"][1]["free_stroke_percent"].get<double>(), stroke, 1e-9);
    EXPECT_NEAR(json["isometric_force_n"].get<double>(), blockedForce, 1e-9);
    std::vector<double> force, contraction;
    for (size_t row = 0; row < table.Rows(); ++row)
        if (table.Text(row, "curve") == "isobaric" && table.Number(row, "pressure_kpa") == 10) {
            ASSERT_EQ(table.Text(row, "status"), "ok");
            force.push_back(table.Number(row, "force_n"));
            contraction.push_back(table.Number(row, "contraction_percent"));
        }
    ASSERT_EQ(force.size(), 3u);
    EXPECT_NEAR(force.front(), blockedForce, 1e-6 * blockedForce) << "no contraction: the blocking force";
    EXPECT_NEAR(contraction.back(), stroke, 1e-9);
    EXPECT_EQ(force.back(), 0) << "the curve ends at the free state, where the muscle pulls with nothing";
    EXPECT_GT(force[0], force[1]) << "held half way to the free stroke, it pulls with less than blocked";
    EXPECT_GT(force[1], 0) << "and still pulls";

    // Every evaluation is archived: per pressure the free inflation and its held strokes, then the
    // isometric test; a held stroke replays from the archive to the force on its curve.
    const app::Table log = app::Table::Read(Path("c/evaluations.csv"));
    ASSERT_EQ(log.Rows(), 2u * 3u + 1u);
    for (size_t row = 0; row < log.Rows(); ++row) {
        EXPECT_EQ(log.Number(row, "evaluation"), double(row));
        EXPECT_EQ(log.Text(row, "role"), "characteristic");
    }
    EXPECT_EQ(log.Text(4, "label"), "held at 0 % contraction at 10 kPa");
    EXPECT_EQ(log.Number(4, "stroke_force_n"), force[0]);
    EXPECT_EQ(log.Number(5, "stroke_force_n"), force[1]);
    EXPECT_NEAR(log.Number(5, "contraction_percent"), contraction[1], 1e-9);
    const Result replay = Run("simulate --from " + Path("c/evaluations.capnp") + " --index 5");
    ASSERT_EQ(replay.exitCode, 0) << replay.err;
    EXPECT_NEAR(nlohmann::json::parse(replay.out)["stroke_force_n"].get<double>(), force[1], 1e-6 * force[0])
        << "the blocked test from rest reaches the held state the curve reached from the free state";
    EXPECT_NEAR(log.Number(6, "blocking_force_n"), blockedForce, 1e-9);
    // A second run into the same folder is refused unless asked to replace it.
    const std::string before = Slurp(dir_ / "c" / "characteristic.csv");
    const Result again = Run("characterize" + design + " --pressures-kpa 5 --points 3 --out " + Path("c"));
    EXPECT_EQ(again.exitCode, 2);
    EXPECT_NE(again.err.find("--overwrite"), std::string::npos) << again.err;
    EXPECT_EQ(Slurp(dir_ / "c" / "characteristic.csv"), before);
    ASSERT_EQ(Run("characterize" + design + " --pressures-kpa 5 --points 3 --overwrite --out " + Path("c")).exitCode, 0);
    EXPECT_EQ(app::Table::Read(Path("c/evaluations.csv")).Rows(), 3u + 1u);

    // A stored design is characterized as it was simulated: the archive's record 0 is this design's
    // free inflation at 5 kPa, with the same model settings.
    const Result stored = Run("characterize --from " + Path("c/evaluations.capnp") + " --index 0 --pressures-kpa 5 --points 3 --out " + Path("s"));
    ASSERT_EQ(stored.exitCode, 0) << stored.err;
    EXPECT_EQ(Slurp(dir_ / "s" / "characteristic.csv"), Slurp(dir_ / "c" / "characteristic.csv"));
    EXPECT_EQ(Run("characterize --from " + Path("c/evaluations.capnp") + " --pressures-kpa 5 --out " + Path("t")).exitCode, 2) << "--index is needed";
    EXPECT_EQ(Run("characterize --from " + Path("c/evaluations.capnp") + " --index 0 --shape sine --out " + Path("t")).exitCode, 2);

    for (const std::string& bad : {std::string("characterize --model thesis --shape sine --out ") + Path("t"),
                                   "characterize" + design + " --pressures-kpa 10,5 --out " + Path("t"),
                                   "characterize" + design + " --pressure-kpa 10 --out " + Path("t"), "characterize" + design}) {
        const Result refused = Run(bad);
        EXPECT_EQ(refused.exitCode, 2) << bad;
        EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
    }
    EXPECT_FALSE(fs::exists(dir_ / "t"));
}

// The bench objectives are the evaluations' own outputs: the isobaric force at the held stroke and
// the top's turn, each front design's values those of its row in the evaluation log.
TEST_F(ShellCli, TheForceAtAStrokeAndTheTwistAreObjectives) {
    Write("bench.json", R"({"id": "o", "seed": 3, "model": {"name": "membrane", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 0}, "fibres": "single",
        "fibre_angle_deg": 30, "load": {"kind": "blocked", "pressure_kpa": 1.2, "stroke_percent": 2, "steps": 1}},
        "optimizer": {"algorithm": "nsga2", "population": 8, "generations": 2, "objectives": ["force_at_stroke", "twist"],
                      "genome": {"family": "bspline", "control_points": 4}}, "render": {"figures": false, "thumbnails": false}})");
    const Result r = Run("evolve " + Path("bench.json") + " --out " + Path("bench"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const app::Table front = app::Table::Read((dir_ / "bench" / "run_1" / "pareto_front.csv").string());
    const app::Table log = app::Table::Read((dir_ / "bench" / "evaluations.csv").string());
    ASSERT_GE(front.Rows(), 2u);
    for (size_t k = 0; k < front.Rows(); ++k) {
        const size_t row = static_cast<size_t>(front.Number(k, "evaluation"));
        ASSERT_LT(row, log.Rows());
        EXPECT_EQ(front.Number(k, "force_at_the_held_stroke_N"), log.Number(row, "stroke_force_n"));
        EXPECT_EQ(front.Number(k, "twist_magnitude_deg"), std::fabs(log.Number(row, "twist_deg")));
    }
    EXPECT_GT(front.Number(0, "twist_magnitude_deg"), 1) << "one family turns the top";
}

// One evaluation gives the isobaric curve and the work of one stroke (its area) when asked: from the
// blocking force at no contraction to none at the free stroke; and work per gram is an objective
// that a search can maximise, its values those of the evaluation log.
TEST_F(ShellCli, AnInflationWithIsobaricPointsGivesTheWorkOfAStroke) {
    const std::string braid = "simulate --model membrane --shape cylinder --fibres braid --fibre-angle-deg 30 --pressure-kpa 10" + kSmall;
    const auto j = nlohmann::json::parse(Run(braid + " --isobaric-points 4").out);
    ASSERT_EQ(j["status"], "ok");
    const auto& curve = j["isobaric"];
    ASSERT_EQ(curve.size(), 4u);
    EXPECT_NEAR(curve[0]["force_n"].get<double>(), j["blocking_force_n"].get<double>(), 1e-6 * j["blocking_force_n"].get<double>());
    EXPECT_EQ(curve[3]["contraction_percent"], j["contraction_percent"]);
    EXPECT_EQ(curve[3]["force_n"], 0.0);
    double work = 0;
    for (size_t k = 1; k < 4; ++k)
        work += 0.5 * (curve[k]["force_n"].get<double>() + curve[k - 1]["force_n"].get<double>()) *
                (curve[k]["contraction_percent"].get<double>() - curve[k - 1]["contraction_percent"].get<double>()) / 100 * j["model"]["length_mm"].get<double>();
    EXPECT_NEAR(j["work_per_stroke_mj"].get<double>(), work, 1e-9 * work);
    EXPECT_GT(j["work_per_gram_mj_per_g"].get<double>(), 0);
    const auto plain = nlohmann::json::parse(Run(braid).out);
    EXPECT_FALSE(plain.contains("isobaric"));
    EXPECT_TRUE(plain["work_per_stroke_mj"].is_null());
    EXPECT_EQ(plain["contraction_percent"], j["contraction_percent"]) << "the held strokes come after the free state is measured";
    ExpectRefused(braid + " --load blocked --isobaric-points 4", "--isobaric-points applies to --load inflate, not --load blocked");
    ExpectRefused("simulate --model shell --load force --force-n 0.1 --held-push-diameters 2", "--held-push-diameters applies to --load inflate, gas or blocked, not --load force");

    const std::string study = R"({"id": "w", "seed": 5, "model": {"name": "membrane", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 0}, "fibres": "braid",
        "fibre_angle_deg": 30, "load": {"pressure_kpa": 5, "steps": 1LOAD}}, "optimizer": {"algorithm": "nsga2", "population": 8, "generations": 1,
        "objectives": ["work_per_gram", "max_stretch"], "genome": {"family": "bspline", "control_points": 4}}, "render": {"figures": false, "thumbnails": false}})";
    auto withLoad = [&](const std::string& extra) { std::string s = study; s.replace(s.find("LOAD"), 4, extra); return s; };
    Write("work_refused.json", withLoad(""));
    const Result refused = Run("evolve " + Path("work_refused.json") + " --out " + Path("work_refused"));
    EXPECT_EQ(refused.exitCode, 2);
    EXPECT_NE(refused.err.find("isobaric_points"), std::string::npos) << refused.err;
    Write("work.json", withLoad(R"(, "isobaric_points": 3)"));
    const Result r = Run("evolve " + Path("work.json") + " --out " + Path("work"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const app::Table front = app::Table::Read((dir_ / "work" / "run_1" / "pareto_front.csv").string());
    const app::Table log = app::Table::Read((dir_ / "work" / "evaluations.csv").string());
    ASSERT_GE(front.Rows(), 1u);
    for (size_t k = 0; k < front.Rows(); ++k) {
        const size_t row = static_cast<size_t>(front.Number(k, "evaluation"));
        EXPECT_EQ(front.Number(k, "work_per_stroke_per_gram_mJ_g"), log.Number(row, "work_per_gram_mj_per_g"));
        EXPECT_GT(front.Number(k, "work_per_stroke_per_gram_mJ_g"), 0);
    }
}

// A held stroke in mm is the same test as in percent of the length; both at once is refused.
TEST_F(ShellCli, AHeldStrokeInMillimetresIsTheSameTestAsInPercent) {
    const std::string braid = "simulate --model membrane --shape cylinder --fibres braid --fibre-angle-deg 30 --load blocked --pressure-kpa 20" + kSmall;
    const auto percent = nlohmann::json::parse(Run(braid + " --stroke-percent 5").out);
    const auto mm = nlohmann::json::parse(Run(braid + " --stroke-mm " + std::to_string(0.05 * percent["model"]["length_mm"].get<double>())).out);
    ASSERT_EQ(percent["status"], "ok");
    EXPECT_GT(percent["stroke_force_n"].get<double>(), 0);
    EXPECT_EQ(mm["stroke_force_n"], percent["stroke_force_n"]);
    EXPECT_EQ(mm["curve"], percent["curve"]);  // every load step's force
    ExpectRefused(braid + " --stroke-percent 5 --stroke-mm 7.5", "give the held stroke once");
    ExpectRefused("simulate --model membrane --stroke-mm 7.5" + kSmall, "--stroke-mm applies to --load blocked, not --load inflate");
}

// A bending actuator (meridian threads on one half, hoop threads on the other) as a bench sees it:
// held square on the axis by default, the bench feels a bending moment; with --tip free (or the
// experiment's "ends": {"tip": "free"}) the tip tilts and swings off the axis, and the results say
// how far. The option is refused where it cannot apply, and old archives read as held.
TEST_F(ShellCli, ABendingActuatorsTipTiltsWhenFreeAndFeelsAMomentWhenHeld) {
    const std::string model = R"("name": "membrane", "geometry": {"ring_vertices": 16, "rings": 20}, "load": {"pressure_kpa": 3, "steps": 3},
        "fibres": "single", "fibre_sectors_deg": [0, 90])";
    const std::string rest = R"("evaluate": {"shapes": [{"family": "cylinder"}]}, "render": {"figures": false, "thumbnails": false}})";
    Write("held.json", R"({"id": "held", "model": {)" + model + "}, " + rest);
    Write("free.json", R"({"id": "free", "model": {)" + model + R"(, "ends": {"tip": "free"}}, )" + rest);
    for (const char* name : {"held", "free"}) {
        const Result r = Run(std::string("sweep ") + Path(std::string(name) + ".json") + " --out " + Path(name));
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    const app::Table held = app::Table::Read((dir_ / "held" / "evaluations.csv").string());
    const app::Table free = app::Table::Read((dir_ / "free" / "evaluations.csv").string());
    EXPECT_GT(held.Number(0, "tip_moment_n_mm"), 0.1);
    EXPECT_TRUE(held.Text(0, "tip_tilt_deg").empty()) << "a held tip does not tilt";
    EXPECT_GT(free.Number(0, "tip_tilt_deg"), 10);
    EXPECT_GT(free.Number(0, "tip_lateral_mm"), 1);
    EXPECT_TRUE(free.Text(0, "tip_moment_n_mm").empty()) << "nothing holds a free tip";
    // The stored job keeps its ends: replayed, the tip tilts as it did.
    const Result replay = Run("simulate --from " + Path("free/evaluations.capnp") + " --index 0");
    ASSERT_EQ(replay.exitCode, 0) << replay.err;
    const auto json = nlohmann::json::parse(replay.out);
    EXPECT_EQ(json["model"]["tip"], "free");
    EXPECT_EQ(json["tip_tilt_deg"].get<double>(), free.Number(0, "tip_tilt_deg"));
    // Where a tip cannot move: sliding ends, and the thesis model.
    ExpectRefused("simulate --model membrane --ends sliding --tip free --ring-vertices 16 --rings 20", "--tip applies to --ends clamped, not --ends sliding");
    ExpectRefused("simulate --model thesis --tip free", "--tip");
    ExpectRefused("simulate --model membrane --tip bent" + kSmall, "held or free");
}

// --mesh-check: the same design meshed twice as finely (every edge halved, the clamps the same length
// in millimetres), its contraction and how far it moved; the thesis model, whose mesh is its
// definition, is refused.
TEST_F(ShellCli, MeshCheckReportsTheSameDesignAtTwiceTheMeshAgainstTheRule) {
    const std::string design = "simulate --model shell --shape sine --amplitude 1.3 --steps 2 --pressure-kpa 1";
    const Result checked = Run(design + " --ring-vertices 12 --rings 16 --edge-spacing-mm 2 --mesh-check");
    ASSERT_EQ(checked.exitCode, 0) << checked.err;
    const auto json = nlohmann::json::parse(checked.out);
    ASSERT_TRUE(json.contains("mesh_check"));
    const auto& check = json["mesh_check"];
    // Every length halved: the rings' spacing in the middle and at the clamps' edges.
    const auto fine = nlohmann::json::parse(Run(design + " --ring-vertices 24 --rings 31 --edge-spacing-mm 1").out);
    const int fineRings = fine["model"]["rings_used"].get<int>();
    EXPECT_GT(fineRings, 31) << "graded toward the clamps";
    EXPECT_THAT(check["mesh"].get<std::string>(), HasSubstr("24 vertices per ring x " + std::to_string(fineRings) + " rings (1 mm apart at the clamps' edges)"));
    EXPECT_EQ(check["contraction_percent"], fine["contraction_percent"]) << "the refined design is the plain run at that mesh";
    const double coarse = json["contraction_percent"].get<double>(), finer = fine["contraction_percent"].get<double>();
    EXPECT_NEAR(check["difference_points"].get<double>(), std::fabs(finer - coarse), 1e-12);
    EXPECT_NEAR(check["relative_difference_percent"].get<double>(), 100 * std::fabs(finer - coarse) / std::fabs(finer), 1e-9);
    EXPECT_EQ(check["converged"].get<bool>(), std::fabs(finer) < 1 ? std::fabs(finer - coarse) <= 0.05 : 100 * std::fabs(finer - coarse) / std::fabs(finer) <= 5);
    // The held state's force, refined: the blocking force of the plain run at that mesh.
    const double coarseForce = json["blocking_force_n"].get<double>(), fineForce = fine["blocking_force_n"].get<double>();
    EXPECT_EQ(check["blocking_force_n"], fine["blocking_force_n"]);
    EXPECT_NEAR(check["blocking_force_difference_percent"].get<double>(), 100 * std::fabs(fineForce - coarseForce) / std::fabs(fineForce), 1e-9);
    EXPECT_EQ(check["blocking_force_converged"].get<bool>(),
              std::fabs(fineForce) < 0.02 ? std::fabs(fineForce - coarseForce) <= 0.001 : 100 * std::fabs(fineForce - coarseForce) / std::fabs(fineForce) <= 5);
    EXPECT_FALSE(nlohmann::json::parse(Run(design + " --ring-vertices 12 --rings 16 --edge-spacing-mm 2").out).contains("mesh_check")) << "only when asked";
    ExpectRefused("simulate --model thesis --mesh-check", "--mesh-check");
}

// sweep --mesh-check: the best design again at twice the mesh, in summary.json and the report, equal
// to simulating that design at that mesh, its held force included; a thesis-model experiment is refused.
TEST_F(ShellCli, ASweepsMeshCheckIsItsBestDesignAtTwiceTheMesh) {
    Write("checked.json", R"({"id": "c", "model": {"name": "shell", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 2}, "load": {"steps": 2},
        "fibres": "braid"}, "sweep": {"shape": {"family": "sine", "amplitude": 1, "phase": ["pi/2", "pi/2"]},
        "axes": [{"parameter": "fibre_angle_deg", "values": [25, 40]}]}, "render": {"thumbnails": false, "figures": false}})");
    const Result r = Run("sweep " + Path("checked.json") + " --out " + Path("checked") + " --mesh-check");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto summary = nlohmann::json::parse(r.out);
    ASSERT_TRUE(summary.contains("mesh_check")) << r.out;
    const auto& check = summary["mesh_check"];
    double bestAngle = NAN;
    for (const auto& row : summary["results"])
        if (row["quantity"] == "best fibre_angle_deg") bestAngle = row["ours"].get<double>();
    ASSERT_TRUE(std::isfinite(bestAngle));
    const std::string best = "simulate --model shell --shape sine --amplitude 1 --phase pi/2,pi/2 --fibres braid --steps 2 --fibre-angle-deg " + std::to_string(bestAngle);
    const auto fine = nlohmann::json::parse(Run(best + " --ring-vertices 24 --rings 31 --edge-spacing-mm 1").out);
    EXPECT_EQ(check["contraction_percent"], fine["contraction_percent"]);
    EXPECT_THAT(check["mesh"].get<std::string>(), HasSubstr("24 vertices per ring x " + std::to_string(fine["model"]["rings_used"].get<int>()) + " rings"));
    // The best design's held force, refined as simulate --mesh-check refines it.
    const auto coarse = nlohmann::json::parse(Run(best + " --ring-vertices 12 --rings 16 --edge-spacing-mm 2 --mesh-check").out);
    ASSERT_TRUE(fine["blocking_force_n"].is_number());
    EXPECT_EQ(check["blocking_force_n"], fine["blocking_force_n"]);
    EXPECT_EQ(check["blocking_force_converged"], coarse["mesh_check"]["blocking_force_converged"]);
    EXPECT_EQ(check["blocking_force_difference_percent"], coarse["mesh_check"]["blocking_force_difference_percent"]);
    const std::string report = Slurp(dir_ / "checked" / "report.md");
    EXPECT_THAT(report, HasSubstr("mesh check of the best design: "));
    EXPECT_THAT(report, HasSubstr("its held force "));
    ExpectRefused("sweep 4.1_amplitude_sweep --out " + Path("thesis") + " --mesh-check", "--mesh-check");
}
