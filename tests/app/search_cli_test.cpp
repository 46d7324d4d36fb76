// `actuator sweep` and `actuator evolve`: the thesis's amplitude sweep, GA reproducibility across
// thread counts, resume after a kill, and precise refusal of bad experiment files.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "cli_fixture.h"
#include "render/image.h"

extern char** environ;
namespace fs = std::filesystem;

namespace {

class SearchCli : public CliTest {
protected:
    // A GA small enough for a test but long enough (about a second per run) to be killed mid-run.
    std::string SmallGa(int generations = 10, int runs = 2) const {
        const std::string path = Path("ga.json");
        Write("ga.json", R"({"id": "test", "title": "small GA", "seed": 99, "iterations": 3000,
            "evolve": {"runs": )" + std::to_string(runs) + R"(, "population": 10, "generations": )" + std::to_string(generations) +
                             R"(, "tournament": 3, "elite": 1, "mutpb": 0.5, "indpb": 0.2,
                        "genome": {"kind": "bspline", "region": "middle", "splines": 2, "control": [0, 8], "length": [5, 9]}},
            "render": {"figures": false}})");
        return path;
    }
    std::string RunFiles(const fs::path& out, int runs) const {
        std::string all;
        for (int r = 1; r <= runs; ++r)
            for (const char* file : {"logbook.csv", "best_per_generation.csv", "halloffame.csv"})
                all += std::string(file) + ":\n" + Slurp(out / ("run_" + std::to_string(r)) / file);
        return all;
    }
    static std::vector<std::vector<std::string>> ReadCsv(const std::string& text) {
        std::vector<std::vector<std::string>> rows;
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);) {
            std::vector<std::string> cells;
            std::istringstream fields(line);
            for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
            rows.push_back(cells);
        }
        return rows;
    }
};

}  // namespace

TEST_F(SearchCli, ThesisAmplitudeSweepPeaksBetween3And5AndTurnsNegativePast7) {
    const Result r = Run(std::string("sweep ") + ACTUATOR_ASSETS_DIR + "/experiments/4.1_amplitude_sweep.json --out " + Path("s41"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto summary = nlohmann::json::parse(r.out);
    double bestAmplitude = NAN;
    for (const auto& row : summary["results"])
        if (row["quantity"] == "best amplitude") bestAmplitude = row["ours"].get<double>();
    EXPECT_GE(bestAmplitude, 3.0);
    EXPECT_LE(bestAmplitude, 5.0);
    const auto rows = ReadCsv(Slurp(dir_ / "s41" / "results.csv"));
    ASSERT_EQ(rows.size(), 31u);  // header + 30 amplitudes
    EXPECT_EQ(rows[0][1], "amplitude");
    for (size_t k = 1; k < rows.size(); ++k)
        if (std::stod(rows[k][1]) > 7) EXPECT_LT(std::stod(rows[k][2]), 0) << "A=" << rows[k][1];
    for (const char* figure : {"landscape.png", "best_inflation.png", "best_stretch.png"})
        EXPECT_GT(fs::file_size(dir_ / "s41" / figure), 10000u) << figure;
}

TEST_F(SearchCli, EvolveGivesTheSameBytesWhateverTheThreadCount) {
    const std::string experiment = SmallGa(6, 2);
    ASSERT_EQ(Run("evolve " + experiment + " --out " + Path("t1") + " --threads 1").exitCode, 0);
    const Result two = Run("evolve " + experiment + " --out " + Path("t2") + " --threads 2");
    ASSERT_EQ(two.exitCode, 0) << two.err;
    EXPECT_EQ(RunFiles(dir_ / "t1", 2), RunFiles(dir_ / "t2", 2));
    // Different runs get different derived seeds, written into the output.
    const auto seed = [&](int run) {
        return nlohmann::json::parse(Slurp(dir_ / "t2" / ("run_" + std::to_string(run)) / "checkpoint.json"))["seed"].get<std::uint64_t>();
    };
    EXPECT_NE(seed(1), seed(2));
}

TEST_F(SearchCli, EvolveImprovesAndLogsEveryGeneration) {
    const Result r = Run("evolve " + SmallGa(10, 1) + " --out " + Path("e"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = ReadCsv(Slurp(dir_ / "e" / "run_1" / "logbook.csv"));
    ASSERT_EQ(rows.size(), 12u);  // header + generations 0..10
    EXPECT_EQ(rows[0], (std::vector<std::string>{"generation", "evaluations", "best", "worst", "mean", "std", "invalid"}));
    EXPECT_EQ(rows[1][1], "10");  // the initial population is evaluated whole
    for (size_t k = 2; k < rows.size(); ++k) EXPECT_GE(std::stod(rows[k][2]), std::stod(rows[k - 1][2])) << "best fell at row " << k;
    EXPECT_GT(std::stod(rows.back()[2]), std::stod(rows[1][2])) << "ten generations should improve on the initial best";
    EXPECT_EQ(ReadCsv(Slurp(dir_ / "e" / "run_1" / "best_per_generation.csv")).size(), 12u);
    EXPECT_GE(ReadCsv(Slurp(dir_ / "e" / "run_1" / "halloffame.csv")).size(), 2u);
}

TEST_F(SearchCli, ResumeAfterAKillEndsLikeAnUninterruptedRun) {
    const std::string experiment = SmallGa(12, 2);
    ASSERT_EQ(Run("evolve " + experiment + " --out " + Path("whole")).exitCode, 0);

    // Start the same run, kill it hard once the first run has checkpointed generation 3.
    const std::string out = Path("killed");
    std::vector<std::string> args{ACTUATOR_BIN, "evolve", experiment, "--out", out};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t child = 0;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    ASSERT_EQ(posix_spawn(&child, ACTUATOR_BIN, &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    const fs::path checkpoint = fs::path(out) / "run_1" / "checkpoint.json";
    int generation = -1;
    for (int wait = 0; wait < 3000 && generation < 3; ++wait) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        if (!fs::exists(checkpoint)) continue;
        try { generation = nlohmann::json::parse(Slurp(checkpoint))["generation"].get<int>(); } catch (...) {}
    }
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed; the test proves nothing";
    ASSERT_GE(generation, 3);
    EXPECT_FALSE(fs::exists(fs::path(out) / "summary.json"));

    // The archive survived the kill: inspect reads every complete evaluation of it.
    const Result afterKill = Run("inspect " + out + "/evaluations.capnp --json");
    ASSERT_EQ(afterKill.exitCode, 0) << afterKill.err;
    EXPECT_GE(nlohmann::json::parse(afterKill.out)["total"].get<int>(), 10);

    const Result resumed = Run("evolve --resume " + out);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_EQ(RunFiles(out, 2), RunFiles(dir_ / "whole", 2));
}

TEST_F(SearchCli, BadExperimentFilesAreRefusedPrecisely) {
    const std::string sweep = R"({"shape": {"family": "sine"}, "sweep": {"axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 3}]}})";
    auto refuse = [&](const std::string& text, const std::string& mentions) {
        Write("bad.json", text);
        ExpectRefused("sweep " + Path("bad.json") + " --out " + Path("o"), mentions);
    };
    refuse(R"({"shape": {"family": "sine"}, "sweep": {"axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 3}]}, "iteratons": 5})",
           "'iteratons': unknown key");
    refuse(R"({"shape": {"family": "sine"}, "sweep": {"axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": "many"}]}})",
           "'sweep.axes[0].points': expected a whole number");
    refuse(R"({"shape": {"family": "sine"}, "sweep": {"axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 0}]}})",
           "'sweep.axes[0].points': out of range");
    refuse(R"({"shape": {"family": "cone"}, "sweep": {"axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 3}]}})",
           "'shape.family': unknown value 'cone'");
    refuse(R"({"evolve": {"population": 10, "tournament": 3, "mutpb": 1.5, "genome": {"kind": "bspline"}}})", "'evolve.mutpb': out of range");
    refuse(R"({"evolve": {"genome": {"kind": "bspline", "length": [3, 9]}}})", "'evolve.genome.length'");
    refuse(R"({"evolve": {"genome": {"kind": "bspline", "splines": 3}}})", "'evolve.genome.splines'");
    refuse(R"({"shape": {"family": "sine"}})", "exactly one of");
    refuse(R"({"shape": {"family": "sine"}, "sweep": )", "not valid JSON");
    refuse("[1, 2]", "must hold a JSON object");
    refuse(R"({"load": "squash", )" + sweep.substr(1), "'load': unknown value");
    Write("ok.json", sweep);
    ExpectRefused("evolve " + Path("ok.json") + " --out " + Path("o"), "run it with 'actuator sweep'");
    ExpectRefused("sweep " + Path("missing.json") + " --out " + Path("o"), "missing.json");
    ExpectRefused("sweep " + Path("ok.json"), "--out");
    ExpectRefused("evolve --resume " + Path("nothing-here"), "experiment.json");
    EXPECT_FALSE(fs::exists(Path("o/results.csv")));
}

TEST_F(SearchCli, EveryShippedExperimentFileIsValid) {
    // Parsing happens before any work: a missing --out is reported only after the file was read.
    int files = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(ACTUATOR_ASSETS_DIR) / "experiments")) {
        const std::string command = entry.path().filename().string().rfind("5.", 0) == 0 ? "evolve " : "sweep ";
        const Result r = Run(command + entry.path().string());
        EXPECT_NE(r.err.find("--out DIR is required"), std::string::npos) << entry.path() << ": " << r.err;
        ++files;
    }
    EXPECT_EQ(files, 10);
}

TEST_F(SearchCli, QuickReproductionWritesACompleteReport) {
    const Result r = Run("reproduce --quick --out " + Path("thesis"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string report = Slurp(dir_ / "thesis" / "report.md");
    for (const char* section : {"## 4.1 ", "## 4.2 ", "## 4.3 ", "## 5.1 ", "## 5.2 ", "## 5.3 ", "## 5.4 ", "## 5.5 ", "## 6.1 ", "## 6.2 "})
        EXPECT_NE(report.find(section), std::string::npos) << "missing section " << section;
    EXPECT_NE(report.find("| ours | thesis |"), std::string::npos);
    // Every figure the report shows exists and is a real picture.
    size_t images = 0;
    for (size_t at = report.find("]("); at != std::string::npos; at = report.find("](", at + 2)) {
        if (report.compare(at - 1, 1, "`") == 0 || report[report.rfind('[', at) - 1] != '!') continue;  // links, not images
        const size_t end = report.find(')', at);
        const std::string file = report.substr(at + 2, end - at - 2);
        ++images;
        const std::string bytes = Slurp(dir_ / "thesis" / file);
        render::Image image;
        std::string error;
        ASSERT_TRUE(render::DecodePng(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), &image, &error)) << file << ": " << error;
        EXPECT_FALSE(render::IsUniform(image)) << file;
    }
    EXPECT_GE(images, 30u);
    EXPECT_TRUE(fs::exists(dir_ / "thesis" / "5.2_bspline_middle" / "run_1" / "thumbnails" / "evaluation_00001.png"));
    EXPECT_TRUE(fs::exists(dir_ / "thesis" / "4.1_amplitude_sweep" / "thumbnails" / "point_0000.png"));
}

TEST_F(SearchCli, ArchivesListFilterAndRenderWithoutSimulating) {
    ASSERT_EQ(Run("evolve " + SmallGa(3, 2) + " --out " + Path("a")).exitCode, 0);
    const std::string archive = Path("a/evaluations.capnp");
    const Result all = Run("inspect " + archive + " --json");
    ASSERT_EQ(all.exitCode, 0) << all.err;
    const auto json = nlohmann::json::parse(all.out);
    const auto& evaluations = json["evaluations"];
    ASSERT_EQ(json["total"].get<size_t>(), evaluations.size());
    EXPECT_FALSE(json["truncated"].get<bool>());
    // Every simulation of both runs is there: the logbooks' evaluation counts add up (the cache can only lower them).
    size_t logged = 0;
    for (int run = 1; run <= 2; ++run)
        for (const auto& row : ReadCsv(Slurp(dir_ / "a" / ("run_" + std::to_string(run)) / "evaluations.csv"))) logged += row[0] != "evaluation";
    EXPECT_EQ(evaluations.size(), logged);
    for (size_t k = 0; k < evaluations.size(); ++k) EXPECT_EQ(evaluations[k]["index"].get<size_t>(), k);

    const auto count = [&](const std::string& filter) {
        const Result r = Run("inspect " + archive + " --json " + filter);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return nlohmann::json::parse(r.out)["evaluations"];
    };
    for (const auto& e : count("--run 2")) EXPECT_EQ(e["run"], 2);
    for (const auto& e : count("--generation 0")) EXPECT_EQ(e["generation"], 0);
    EXPECT_EQ(count("--generation 0 --run 1").size(), 10u);  // the initial population
    for (const auto& e : count("--min-fitness 0.1")) EXPECT_GE(e["fitness"].get<double>(), 0.1);
    EXPECT_EQ(count("--limit 3").size(), 3u);
    const Result table = Run("inspect " + archive + " --status ok --limit 2");
    EXPECT_NE(table.out.find("2 of " + std::to_string(evaluations.size()) + " evaluations shown"), std::string::npos) << table.out;

    const Result rendered = Run("render --from " + archive + " --index 4 --out " + Path("again"));
    ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
    EXPECT_EQ(nlohmann::json::parse(rendered.out)["simulated"], false);
    const std::string bytes = Slurp(dir_ / "again" / "evaluation_4.png");
    render::Image image;
    std::string error;
    ASSERT_TRUE(render::DecodePng(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), &image, &error)) << error;
    EXPECT_FALSE(render::IsUniform(image));

    ExpectRefused("render --from " + archive + " --out " + Path("x"), "--index");
    ExpectRefused("render --from " + archive + " --index 100000 --out " + Path("x"), "holds");
    ExpectRefused("render --from " + archive + " --index 1 --shape sine --out " + Path("x"), "--shape");
    ExpectRefused("inspect " + Path("missing.capnp"), "missing.capnp");
    Write("junk.capnp", std::string(3000, '\x7f'));
    ExpectRefused("inspect " + Path("junk.capnp"), "not an evaluation archive");
    ExpectRefused("inspect " + archive + " --status weird", "weird");
}
