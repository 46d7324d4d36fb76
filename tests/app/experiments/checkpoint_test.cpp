// Checkpoints read back are checked like user input: a hostile or edited file is refused with a
// message, never a crash, a hang or a silently wrong run.
#include "experiments/checkpoint.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/errors.h"

using ::testing::HasSubstr;
using Json = nlohmann::ordered_json;

namespace {

const char* kGa = R"({"model": {"name": "thesis"}, "id": "g", "evolve": {"population": 6, "generations": 3, "genome": {"kind": "bspline", "splines": 2, "length": [5, 8]}}})";

std::vector<std::pair<double, sim::Status>> Synthetic(const std::vector<const sim::Genome*>& genomes) {
    std::vector<std::pair<double, sim::Status>> out;
    for (const auto* g : genomes) out.push_back({(*g)[0][0] + (*g)[1].size(), sim::Status::Ok});
    return out;
}

struct Fixture {
    app::Experiment e = app::ParseExperiment(kGa, "g.json");
    app::RunCheckpoint c;
    Fixture() {
        c.seed = 5;
        c.experimentHash = app::ExperimentHash(e);
        c.experiment = e.document;
        c.state = sim::StartEvolution(e.ga, app::DesignMesh(e), c.seed, Synthetic);
        sim::EvolveOneGeneration(e.ga, app::DesignMesh(e), c.state, Synthetic);
        c.archiveCount = 11;
    }
    std::string Refusal(const std::function<void(Json&)>& edit) const {
        Json j = Json::parse(app::FormatCheckpoint(c));
        edit(j);
        try {
            app::ParseCheckpoint(j.dump(), "checkpoint.json", e);
        } catch (const app::UsageError& error) {
            return error.what();
        }
        return "accepted";
    }
};

}  // namespace

TEST(Checkpoint, RoundTripsExactly) {
    const Fixture f;
    const app::RunCheckpoint back = app::ParseCheckpoint(app::FormatCheckpoint(f.c), "checkpoint.json", f.e);
    EXPECT_EQ(app::FormatCheckpoint(back), app::FormatCheckpoint(f.c));
    EXPECT_EQ(back.state.rng.State(), f.c.state.rng.State());
    EXPECT_EQ(back.archiveCount, 11u);
}

TEST(Checkpoint, HostileContentsAreRefused) {
    const Fixture f;
    EXPECT_THAT(f.Refusal([](Json& j) { j["population"] = Json::array(); }), HasSubstr("population has 0 individuals"));
    EXPECT_THAT(f.Refusal([](Json& j) { j["population"][0]["genome"][0] = {1, 2}; }), HasSubstr("2 control points"));
    EXPECT_THAT(f.Refusal([](Json& j) { j["population"][0]["genome"][0][0] = 99; }), HasSubstr("outside the control range"));
    EXPECT_THAT(f.Refusal([](Json& j) { j["rng"] = {0, 0, 0, 0}; }), HasSubstr("all zero"));
    EXPECT_THAT(f.Refusal([](Json& j) { j["generation"] = 7; }), HasSubstr("generation out of range"));
    EXPECT_THAT(f.Refusal([](Json& j) { j["logbook"] = Json::array(); }), HasSubstr("logbook"));
    EXPECT_THAT(f.Refusal([](Json& j) { j["population"][1]["status"] = "great"; }), HasSubstr("unknown status"));
    EXPECT_THAT(f.Refusal([](Json& j) { j["population"][1]["fitness"] = nullptr; }), HasSubstr("no fitness"));
    EXPECT_THAT(f.Refusal([](Json& j) { j.erase("rng"); }), HasSubstr("not a usable checkpoint"));
    EXPECT_THAT(f.Refusal([](Json& j) { j["version"] = 1; }), HasSubstr("another version"));
    EXPECT_THROW(app::ParseCheckpoint("{not json", "c.json", f.e), app::UsageError);
}

TEST(Checkpoint, ARunResumedUnderAnEditedExperimentIsRefusedNamingTheChange) {
    const Fixture f;
    const app::Experiment edited = app::ParseExperiment(kGa, "g.json", {{"evolve.mutpb", "0.9"}, {"sim.iterations", "5"}});
    try {
        app::ParseCheckpoint(app::FormatCheckpoint(f.c), "checkpoint.json", edited);
        ADD_FAILURE() << "accepted";
    } catch (const app::UsageError& error) {
        EXPECT_THAT(error.what(), HasSubstr("evolve.mutpb: (none) -> '0.9'"));
        EXPECT_THAT(error.what(), HasSubstr("sim"));
    }
}

TEST(OptimizerCheckpoint, RoundTripsAndRefusesHostileOrEditedContents) {
    const char* experiment = R"({"model": {"name": "thesis"}, "id": "o", "optimizer": {"algorithm": "cmaes", "population": 8, "objectives": ["thesis_fitness"],
                                "genome": {"family": "sine"}}})";
    const app::Experiment e = app::ParseExperiment(experiment, "o.json");
    const app::OptimizerCheckpoint c{7, 3, 40, "", 0};
    const app::OptimizerCheckpoint back = app::ParseOptimizerCheckpoint(app::FormatOptimizerCheckpoint(c, e), "c.json", e);
    EXPECT_EQ(std::tie(back.seed, back.generation, back.archiveCount, back.stopReason), std::tie(c.seed, c.generation, c.archiveCount, c.stopReason));
    auto refusal = [&](const std::function<void(Json&)>& edit) {
        Json j = Json::parse(app::FormatOptimizerCheckpoint(c, e));
        edit(j);
        try {
            app::ParseOptimizerCheckpoint(j.dump(), "c.json", e);
        } catch (const app::UsageError& error) {
            return std::string(error.what());
        }
        return std::string("accepted");
    };
    EXPECT_THAT(refusal([](Json& j) { j["generation"] = -4; }), HasSubstr("values out of range"));
    EXPECT_THAT(refusal([](Json& j) { j["seed"] = "x"; }), HasSubstr("not a usable optimizer checkpoint"));
    EXPECT_THAT(refusal([](Json& j) { j["kind"] = "checkpoint"; }), HasSubstr("not an optimizer checkpoint"));
    EXPECT_THROW(app::ParseOptimizerCheckpoint("{", "c.json", e), app::UsageError);
    const app::Experiment edited = app::ParseExperiment(experiment, "o.json", {{"optimizer.population", "12"}});
    EXPECT_THAT(refusal([&](Json& j) { j = Json::parse(app::FormatOptimizerCheckpoint(c, edited)); }),
                HasSubstr("optimizer.population: '12' -> '8'"));
}
