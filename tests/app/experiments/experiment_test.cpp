// The experiment parser in process: defaults from the def structs, the sim block, --set, and
// messages that name the file, the key and (for a typo) the nearest valid key.
#include "experiments/experiment.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/errors.h"

using ::testing::HasSubstr;

namespace {

const char* kSweep = R"({"model": {"name": "thesis"}, "id": "t", "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 3}]}})";
const char* kGa = R"({"model": {"name": "thesis"}, "id": "g", "evolve": {"genome": {"kind": "bspline"}}})";

std::string Refusal(const std::string& text, const std::vector<app::Override>& overrides = {}) {
    try {
        app::ParseExperiment(text, "x.json", overrides);
    } catch (const app::UsageError& error) {
        return error.what();
    }
    return "accepted";
}

}  // namespace

TEST(Experiment, DefaultsComeFromTheDefStructs) {
    const app::Experiment e = app::ParseExperiment(kGa, "x.json");
    const sim::GaDef ga;
    EXPECT_EQ(e.ga.population, ga.population);
    EXPECT_EQ(e.ga.generations, ga.generations);
    EXPECT_EQ(e.ga.mutpb, ga.mutpb);
    EXPECT_EQ(e.ga.genome.lengthMax, ga.genome.lengthMax);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.iterations, sim::DefaultSimParams().iterations);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.pressureScale, sim::DefaultSimParams().pressureScale);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).mesh.resolution, sim::DefaultMeshDef().resolution);
    const app::Experiment s = app::ParseExperiment(kSweep, "x.json");
    EXPECT_EQ(std::get<sim::SineShape>(s.sweep.base).phaseEnd, sim::SineShape{}.phaseEnd);
}

TEST(Experiment, TheSimBlockSetsEveryThesisConstant) {
    const app::Experiment e = app::ParseExperiment(
        R"({"model": {"name": "thesis"}, "evolve": {"genome": {"kind": "bspline"}}, "sim": {"iterations": 500, "load": "stretch", "spring_constant": 0.02,
            "pressure_scale": "0.01", "pull_force": 0.001, "step_scale": 0.05, "divergence_limit": 100, "precision": "double"}})",
        "x.json");
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.iterations, 500);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.load, sim::Load::Stretch);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.springConstant, 0.02);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.pressureScale, 0.01);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.pullForce, 0.001);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.stepScale, 0.05);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.divergenceLimit, 100);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.precision, sim::Precision::Double);
}

TEST(Experiment, SetOverridesAnyKeyAndCreatesBlocks) {
    const app::Experiment e = app::ParseExperiment(kGa, "x.json",
                                                   {{"evolve.generations", "3"}, {"sim.pressure_scale", "0.01"}, {"seed", "7"}, {"title", "renamed"}});
    EXPECT_EQ(e.ga.generations, 3);
    EXPECT_EQ(std::get<sim::ThesisDef>(e.def).params.pressureScale, 0.01);
    EXPECT_EQ(e.seed, 7u);
    EXPECT_EQ(e.title, "renamed");
    EXPECT_EQ(e.document["sim"]["pressure_scale"], 0.01);  // what DIR/experiment.json will hold
    const app::Experiment s = app::ParseExperiment(kSweep, "x.json", {{"sweep.axes[0].to", "pi"}, {"sweep.shape.family", "abs-sine"}});
    EXPECT_DOUBLE_EQ(s.sweep.axes[0].values.back(), 3.141592653589793);
    EXPECT_TRUE(std::holds_alternative<sim::AbsSineShape>(s.sweep.base));
}

TEST(Experiment, MessagesNameTheFileTheKeyAndTheNearestValidKey) {
    EXPECT_THAT(Refusal(kGa, {{"evolve.generatons", "3"}}), HasSubstr("did you mean 'evolve.generations'?"));
    EXPECT_THAT(Refusal(kGa, {{"evolve.generatons", "3"}}), HasSubstr("--set evolve.generatons=3"));
    EXPECT_THAT(Refusal(kGa, {{"evolve.population", "many"}}), HasSubstr("'evolve.population': expected a whole number, got 'many'"));
    EXPECT_THAT(Refusal(R"({"model": {"name": "thesis"}, "evolve": {"genome": {"kind": "bspline"}}, "sim": {"pressure": 0.01}})"),
                HasSubstr("x.json: 'sim.pressure': unknown key (did you mean 'sim.pressure_scale'?)"));
    EXPECT_THAT(Refusal(R"({"model": {"name": "thesis"}, "evolve": {"genome": {"kind": "bspline"}}, "zzzz": 1})"), HasSubstr("valid here:"));
    EXPECT_THAT(Refusal(R"({"model": {"name": "thesis"}, "evolve": {"genome": {"kind": "bspline"}}, "sim": {"iterations": 1e400}})"), HasSubstr("key 'iterations'"));
    EXPECT_THAT(Refusal(kGa, {{"sweep.axes[2].to", "1"}}), HasSubstr("'sweep.axes' is not a list"));
    // 100,000 signs before a digit: refused as not a number, quoted short, no stack overflow.
    const std::string deep = Refusal(std::string(R"({"model": {"name": "thesis"}, "evolve": {"genome": {"kind": "bspline"}}, "sim": {"step_scale": ")") + std::string(100000, '-') + "1\"}}");
    EXPECT_THAT(deep, HasSubstr("'sim.step_scale': '-----"));
    EXPECT_THAT(deep, HasSubstr("is not a number"));
    EXPECT_LT(deep.size(), 300u);
}

TEST(Experiment, HashAndDifferenceTellWhatChanged) {
    const app::Experiment a = app::ParseExperiment(kGa, "x.json");
    const app::Experiment b = app::ParseExperiment(kGa, "x.json", {{"evolve.genome.kind", "free-xy"}});
    EXPECT_EQ(app::ExperimentHash(a), app::ExperimentHash(app::ParseExperiment(kGa, "y.json")));
    EXPECT_NE(app::ExperimentHash(a), app::ExperimentHash(b));
    EXPECT_THAT(app::ExperimentDifference(a.document, b.document), HasSubstr("evolve.genome.kind: 'bspline' -> 'free-xy'"));
}

TEST(Experiment, TheQuickVersionReReadsAsWhatRan) {
    const app::Experiment quick = app::QuickVersion(app::ParseExperiment(kGa, "x.json"));
    EXPECT_EQ(quick.ga.generations, 2);
    EXPECT_EQ(std::get<sim::ThesisDef>(quick.def).params.iterations, 2000);
    const app::Experiment again = app::ParseExperiment(quick.document.dump(), "x.json");
    EXPECT_EQ(app::ExperimentHash(again), app::ExperimentHash(quick));
}

// A key that has no effect is refused, as the command line refuses an option that does not apply:
// one that the load, the law, the ends or the fibres make moot, or that the experiment replaces.
TEST(Experiment, KeysWithoutEffectAreRefusedNamingWhatDecides) {
    auto shell = [](const std::string& model, const std::string& rest = R"("sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]})") {
        return R"({"id": "k", "model": {"name": "shell", )" + model + "}, " + rest + "}";
    };
    EXPECT_THAT(Refusal(shell(R"("load": {"kind": "blocked", "force_n": 2})")),
                HasSubstr("'model.load.force_n': has no effect here: it applies when \"kind\" is inflate, gas, volume or force, not blocked"));
    EXPECT_THAT(Refusal(shell(R"("load": {"kind": "inflate", "stroke_percent": 5})")),
                HasSubstr("'model.load.stroke_percent': has no effect here: it applies when \"kind\" is blocked, not inflate"));
    EXPECT_THAT(Refusal(shell(R"("ends": {"torque_n_mm": 5})")),
                HasSubstr("'model.ends.torque_n_mm': has no effect here: it applies when \"twist\" is loaded, not free"));
    EXPECT_THAT(Refusal(shell(R"("geometry": {"ends": "sliding"}, "ends": {"twist": "held"})")), HasSubstr("'model.ends.twist'"));
    EXPECT_THAT(Refusal(shell(R"("load": {"twist": "held"})")), HasSubstr("'model.load.twist'"));  // the top's turn is an end's, not the load's
    EXPECT_THAT(Refusal(R"({"model": {"name": "thesis", "ends": {"twist": "held"}}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]}})"),
                HasSubstr("'model.ends': does not apply to the thesis model"));
    EXPECT_THAT(Refusal(shell(R"("load": {"kind": "force", "pressure_kpa": 20})")), HasSubstr("\"kind\" is inflate, gas or blocked, not force"));
    EXPECT_THAT(Refusal(shell(R"("load": {"volume_ratio": 2})")), HasSubstr("'model.load.volume_ratio'"));
    EXPECT_THAT(Refusal(shell(R"("load": {"kind": "volume"}, "solver": {"max_bisections": 3})")), HasSubstr("'model.solver.max_bisections'"));
    EXPECT_THAT(Refusal(shell(R"("material": {"law": "yeoh", "c10_kpa": 100, "mu_kpa": 30})")), HasSubstr("\"law\" is neo-hookean, not yeoh"));
    // The density weighs the wall (silicone_g, per-gram objectives, the envelope's max_silicone_g): it has an effect.
    EXPECT_EQ(Refusal(shell(R"("material": {"density_kg_per_m3": 1100})")), "accepted");
    EXPECT_THAT(Refusal(shell(R"("envelope": {"max_radius": 2})")), HasSubstr("'model.envelope.max_radius'"));
    EXPECT_THAT(Refusal(shell(R"("envelope": {"max_radius_ratio": 0.5})")), HasSubstr("not even the plain tube fits it"));
    EXPECT_THAT(Refusal(shell(R"("material": {"density_kg_per_m3": 0}, "envelope": {"max_silicone_g": 8})")), HasSubstr("max_silicone_g needs the material's density"));
    EXPECT_THAT(Refusal(R"({"model": {"name": "thesis", "envelope": {"max_radius_ratio": 2}}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]}})"),
                HasSubstr("'model.envelope': does not apply to the thesis model"));
    EXPECT_THAT(Refusal(shell(R"("geometry": {"ends": "sliding", "clamp_mm": 8})")), HasSubstr("'model.geometry.clamp_mm'"));
    EXPECT_THAT(Refusal(shell(R"("fibre_angle_deg": 40)")), HasSubstr("\"fibres\" is braid or single, not none"));
    EXPECT_THAT(Refusal(shell(R"("fibre_stiffness_n_per_mm": 5)")), HasSubstr("'model.fibre_stiffness_n_per_mm'"));
    EXPECT_THAT(Refusal(shell(R"("fibres": "hoop", "fibre_bands": [{"from": 0, "to": 1, "angle_deg": 30}])")), HasSubstr("'model.fibre_bands'"));
    EXPECT_THAT(Refusal(shell(R"("fibres": "braid", "fibre_angle_deg": 40, "fibre_bands": [{"from": 0, "to": 1, "angle_deg": 30}])")),
                HasSubstr("'model.fibre_angle_deg'"));
    // Replaced by the experiment: a swept setting, the shape's amplitude under an amplitude axis, the
    // angles under fibre angle genes.
    EXPECT_THAT(Refusal(shell(R"("load": {"pressure_kpa": 2})",
                              R"("sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "pressure_kpa", "values": [1, 2]}]})")),
                HasSubstr("'model.load.pressure_kpa': has no effect here: sweep.axes[0] varies it"));
    EXPECT_THAT(Refusal(R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine", "amplitude": 2}, "axes": [{"parameter": "amplitude", "values": [1, 2]}]}})"),
                HasSubstr("'sweep.shape.amplitude'"));
    EXPECT_THAT(Refusal(shell(R"("fibres": "braid", "fibre_angle_deg": 40)", R"("evolve": {"genome": {"kind": "bspline", "fibre_angles": 1}})")),
                HasSubstr("the genome's fibre angle genes give the angles"));
    // What applies is accepted.
    EXPECT_EQ(Refusal(shell(R"("load": {"kind": "blocked", "stroke_percent": 5}, "ends": {"twist": "loaded", "torque_n_mm": -2})")), "accepted");
    EXPECT_EQ(Refusal(shell(R"("load": {"kind": "force", "force_n": 0.5}, "material": {"law": "yeoh", "c10_kpa": 100, "c20_kpa": 10}, "fibres": "braid", "fibre_angle_deg": 40)")),
              "accepted");
}

// The bench objectives ask the study's settings for their meaning: the force at a held stroke needs
// the top held at one, the twist a top that may turn.
TEST(Experiment, BenchObjectivesNeedTheEndsThatGiveThemAMeaning) {
    auto study = [](const std::string& model, const std::string& objectives) {
        return R"({"id": "o", "model": {"name": "membrane", "fibres": "single", )" + model + R"(}, "optimizer": {"algorithm": "nsga2", "population": 8,
            "objectives": )" + objectives + R"(, "genome": {"family": "bspline", "control_points": 4}}})";
    };
    EXPECT_THAT(Refusal(study(R"("load": {"kind": "inflate"})", R"(["force_at_stroke", "max_stretch"])")),
                HasSubstr("'optimizer.objectives': objective force_at_stroke is the force with the top held at the load's stroke_percent: give the load kind blocked (now inflate)"));
    EXPECT_THAT(Refusal(study(R"("load": {"kind": "blocked", "stroke_percent": 5}, "ends": {"twist": "held"})", R"(["force_at_stroke", "twist"])")),
                HasSubstr("objective twist needs a top that may turn"));
    EXPECT_EQ(Refusal(study(R"("load": {"kind": "blocked", "stroke_percent": 5})", R"(["force_at_stroke", "twist"])")), "accepted");
    EXPECT_THAT(Refusal(R"({"id": "o", "model": {"name": "thesis"}, "optimizer": {"algorithm": "cmaes", "population": 8, "objectives": ["twist"],
        "genome": {"family": "sine"}}})"), HasSubstr("needs units and equilibrium"));
}
