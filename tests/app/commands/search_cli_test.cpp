// `actuator sweep`, `evolve`, `reproduce` and `inspect` as a user runs them: the thesis's amplitude
// sweep, GA reproducibility across thread counts, kill-and-resume at three moments with every output
// equal to an uninterrupted run's, results folders that never mix, one evaluation id everywhere,
// --set, and precise refusal of bad experiment files.
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_fixture.h"
#include "formats/csv.h"
#include "formats/table.h"
#include "app/report/thesis_report_check.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing_support::Child;
using testing_support::ExpectPicture;
using testing_support::WaitUntil;

namespace {

class SearchCli : public CliTest {
protected:
    // A GA small enough for a test but long enough (about a second per run) to be killed mid-run.
    std::string SmallGa(int generations = 10, int runs = 2, bool figures = true) const {
        Write("ga.json", R"({"model": {"name": "thesis"}, "id": "test", "title": "small GA", "seed": 99, "sim": {"iterations": 3000},
            "evolve": {"runs": )" + std::to_string(runs) + R"(, "population": 10, "generations": )" + std::to_string(generations) +
                             R"(, "tournament": 3, "elite": 1, "mutpb": 0.5, "indpb": 0.2,
                        "genome": {"kind": "bspline", "region": "middle", "splines": 2, "control": [0, 8], "length": [5, 9]}},
            "render": {"figures": )" + (figures ? "true" : "false") + "}}");
        return Path("ga.json");
    }
    // A pagmo optimizer over a fixed-length B-spline genome: CMA-ES under the thesis model (one
    // objective), or NSGA-II under a coarse shell (two). Without figures, a small run is a third of
    // the time.
    std::string SmallOptimizer(const std::string& algorithm, int generations, int runs = 1, bool figures = true) const {
        const bool multi = algorithm == "nsga2" || algorithm == "moead";
        const std::string model = multi ? R"("model": {"name": "shell", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 0}, "load": {"pressure_kpa": 1, "steps": 1},
                                                       "fibres": "braid", "fibre_stiffness_n_per_mm": 50},)"
                                        : R"("model": {"name": "thesis"}, "sim": {"iterations": 3000},)";
        const std::string objectives = multi ? R"(["contraction", "max_stretch"])" : R"(["thesis_fitness"])";
        Write(algorithm + ".json", std::string(R"({"id": "o", "title": "small optimizer", "seed": 5, "render": {"figures": )") + (figures ? "true" : "false") + "}, " + model + R"(
            "optimizer": {"algorithm": ")" + algorithm + R"(", "runs": )" + std::to_string(runs) + R"(, "population": 8, "objectives": )" + objectives +
                                       R"(, "generations": )" + std::to_string(generations) + R"(,
                          "genome": {"family": "bspline", "region": "middle", "splines": 1, "control_points": 6, "control": [0, 8])" +
                                       (multi ? R"(, "fibre_angles": 1, "fibre_angle_range": [10, 80])" : "") + "}}}");
        return Path(algorithm + ".json");
    }
    std::string SmallSweep(int points = 24) const {
        Write("sweep.json", R"({"model": {"name": "thesis"}, "id": "s", "sim": {"iterations": 4000},
            "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]},
                      "axes": [{"parameter": "amplitude", "from": 1, "to": 8, "points": )" + std::to_string(points) + R"(}]},
            "thesis_result": {"points": [{"amplitude": 4.1, "fitness": 0.75}]}})");
        return Path("sweep.json");
    }
    std::string RunFiles(const fs::path& out, int runs) const {
        std::string all;
        for (int r = 1; r <= runs; ++r)
            for (const char* file : {"logbook.csv", "best_per_generation.csv", "halloffame.csv"})
                all += std::string(file) + ":\n" + Slurp(out / ("run_" + std::to_string(r)) / file);
        return all;
    }
    // Every archived record, timing aside, with its meshes exported into `meshes` (a new folder:
    // export refuses to write over one).
    nlohmann::json Records(const fs::path& dir, const fs::path& meshes) const {
        const Result r = Run("inspect " + (dir / "evaluations.capnp").string() + " --json --export-obj " + meshes.string());
        EXPECT_EQ(r.exitCode, 0) << r.err;
        auto json = nlohmann::json::parse(r.out)["evaluations"];
        for (auto& e : json) e.erase("elapsed_ms");
        return json;
    }
    // A report without its lines on this session (time taken, simulations run).
    static std::string WithoutTimes(const std::string& text) {
        std::string kept;
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);)
            if (line.find("this session") == std::string::npos && line.find("This session") == std::string::npos) kept += line + "\n";
        return kept;
    }
    // Every file of two results folders equal, but for summary.json's timings and the lock's pid.
    void ExpectSameOutputs(const fs::path& a, const fs::path& b, std::source_location where = std::source_location::current()) const {
        const ::testing::ScopedTrace trace(where.file_name(), static_cast<int>(where.line()), a.string() + " vs " + b.string());
        std::set<std::string> filesA, filesB;
        for (const auto& e : fs::recursive_directory_iterator(a)) if (e.is_regular_file()) filesA.insert(fs::relative(e.path(), a).string());
        for (const auto& e : fs::recursive_directory_iterator(b)) if (e.is_regular_file()) filesB.insert(fs::relative(e.path(), b).string());
        EXPECT_EQ(filesA, filesB);
        for (const auto& f : filesA) {
            if (f == "summary.json" || f == ".lock" || f == "evaluations.capnp" || !filesB.count(f)) continue;
            // report.md states the wall time and the evaluator: the rest of it must be equal.
            const bool report = fs::path(f).filename() == "report.md";
            EXPECT_TRUE(report ? WithoutTimes(Slurp(a / f)) == WithoutTimes(Slurp(b / f)) : Slurp(a / f) == Slurp(b / f)) << f << " differs";
        }
        // Each comparison exports into folders of its own: two folders of one name (whole/o/seed_1 and
        // cut/o/seed_1) must not share, nor a folder compared twice meet its earlier export.
        const int comparison = ++comparisons_;
        const fs::path meshesA = dir_ / ("meshes_" + std::to_string(comparison) + "_a"), meshesB = dir_ / ("meshes_" + std::to_string(comparison) + "_b");
        EXPECT_EQ(Records(a, meshesA), Records(b, meshesB));
        size_t meshes = 0;
        for (const auto& e : fs::recursive_directory_iterator(meshesA)) {
            ++meshes;
            EXPECT_TRUE(Slurp(e.path()) == Slurp(meshesB / e.path().filename())) << e.path() << " differs";
        }
        EXPECT_GT(meshes, 0u) << "no meshes exported: the comparison proves nothing";
    }
    mutable int comparisons_ = 0;
    // Starts `args`, kills it with SIGKILL once `ready` holds, checks it was really cut off.
    void KillWhen(const std::vector<std::string>& args, const std::function<bool()>& ready, std::source_location where = std::source_location::current()) {
        Child child(args);
        const bool reached = WaitUntil(ready, 60);
        const int status = child.Kill(SIGKILL);
        if (!reached || !WIFSIGNALED(status))
            ADD_FAILURE_AT(where.file_name(), static_cast<int>(where.line())) << "the run finished before it could be killed; the test proves nothing";
    }
    static int Generation(const fs::path& checkpoint) {
        try {
            return nlohmann::json::parse(testing_support::Slurp(checkpoint))["generation"].get<int>();
        } catch (...) {
            return -1;
        }
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
    const app::Table results = app::Table::Read((dir_ / "s41" / "results.csv").string());
    ASSERT_EQ(results.Rows(), 30u);  // 30 amplitudes
    for (size_t k = 0; k < results.Rows(); ++k)
        if (results.Number(k, "amplitude") > 7) EXPECT_LT(results.Number(k, "fitness"), 0) << "A=" << results.Text(k, "amplitude");
    for (const char* figure : {"landscape.png", "best_inflation.png", "best_stretch.png", "contact_sheet.png"}) ExpectPicture(dir_ / "s41" / figure);
}

TEST_F(SearchCli, EvolveGivesTheSameBytesWhateverTheThreadCount) {
    const std::string experiment = SmallGa(6, 2, false);
    ASSERT_EQ(Run("evolve " + experiment + " --out " + Path("t1") + " --threads 1").exitCode, 0);
    const Result two = Run("evolve " + experiment + " --out " + Path("t2") + " --threads 2");
    ASSERT_EQ(two.exitCode, 0) << two.err;
    ExpectSameOutputs(dir_ / "t1", dir_ / "t2");
    // Different runs get different derived seeds, written into the output.
    const auto seed = [&](int run) {
        return nlohmann::json::parse(Slurp(dir_ / "t2" / ("run_" + std::to_string(run)) / "checkpoint.json"))["seed"].get<std::uint64_t>();
    };
    EXPECT_NE(seed(1), seed(2));
}

TEST_F(SearchCli, EvolveImprovesAndLogsEveryGeneration) {
    const Result r = Run("evolve " + SmallGa(10, 1, false) + " --out " + Path("e"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const app::Table log = app::Table::Read((dir_ / "e" / "run_1" / "logbook.csv").string());
    ASSERT_EQ(log.Rows(), 11u);  // generations 0..10
    EXPECT_EQ(log.Columns(), (std::vector<std::string>{"generation", "evaluations", "best", "worst", "mean", "std", "q1", "median", "q3", "invalid", "stopped_by"}));
    const size_t last = log.Rows() - 1;
    for (size_t g = 0; g < log.Rows(); ++g) {
        // The quartiles lie between the worst and the best, in order.
        EXPECT_LE(log.Number(g, "worst"), log.Number(g, "q1"));
        EXPECT_LE(log.Number(g, "q1"), log.Number(g, "median"));
        EXPECT_LE(log.Number(g, "median"), log.Number(g, "q3"));
        EXPECT_LE(log.Number(g, "q3"), log.Number(g, "best"));
    }
    EXPECT_EQ(log.Text(last, "stopped_by"), "generations");
    EXPECT_EQ(log.Text(last - 1, "stopped_by"), "");
    EXPECT_EQ(log.Text(0, "evaluations"), "10");  // the initial population is evaluated whole
    for (size_t k = 1; k < log.Rows(); ++k) EXPECT_GE(log.Number(k, "best"), log.Number(k - 1, "best")) << "best fell at generation " << k;
    EXPECT_GT(log.Number(last, "best"), log.Number(0, "best")) << "ten generations should improve on the initial best";
    EXPECT_EQ(app::ParseCsv(Slurp(dir_ / "e" / "run_1" / "best_per_generation.csv")).size(), 12u);
    EXPECT_GE(app::ParseCsv(Slurp(dir_ / "e" / "run_1" / "halloffame.csv")).size(), 2u);
}

TEST_F(SearchCli, EvolveStopsAtItsCriteriaAndSaysWhichInTheLogbook) {
    const std::string experiment = SmallGa(10, 1, false);
    const std::pair<std::string, std::string> criteria[] = {
        {"evolve.stop.evaluations=25", "evaluations"}, {"evolve.stop.target=-100", "target"}, {"evolve.stop.stagnation=1", "stagnation"}};
    for (const auto& [set, reason] : criteria) {
        const fs::path out = dir_ / reason;
        const Result r = Run("evolve " + experiment + " --out " + out.string() + " --set " + set);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const app::Table log = app::Table::Read((out / "run_1" / "logbook.csv").string());
        EXPECT_EQ(log.Text(log.Rows() - 1, "stopped_by"), reason) << set;
        EXPECT_LT(log.Rows(), 11u) << set << ": stopped before generation 10";
        EXPECT_THAT(r.out, HasSubstr("stopped by " + reason)) << set;
    }
    int evaluations = 0;
    for (double n : app::Table::Read((dir_ / "evaluations" / "run_1" / "logbook.csv").string()).Numbers("evaluations")) evaluations += static_cast<int>(n);
    EXPECT_GE(evaluations, 25);
}

// Killed early in run 1, mid-way through run 1, and during run 2: each resumed run's every output
// (archive records with their meshes, evaluations.csv, thumbnails, sheets, logbooks, hall of fame,
// figures) equals the uninterrupted run's.
TEST_F(SearchCli, EvolveResumedAfterAKillAtThreeMomentsEndsLikeAnUninterruptedRun) {
    const std::string experiment = SmallGa(6, 2);
    ASSERT_EQ(Run("evolve " + experiment + " --out " + Path("whole")).exitCode, 0);
    struct Moment {
        const char* name;
        std::function<bool(const fs::path&)> ready;
    };
    const Moment moments[] = {
        {"first", [](const fs::path& out) { return fs::exists(out / "thumbnails" / "evaluation_000003.png"); }},
        {"middle", [](const fs::path& out) { return Generation(out / "run_1" / "checkpoint.json") >= 3; }},
        {"second", [](const fs::path& out) { return Generation(out / "run_2" / "checkpoint.json") >= 1; }},
    };
    for (const Moment& m : moments) {
        const fs::path out = dir_ / m.name;
        KillWhen({ACTUATOR_BIN, "evolve", experiment, "--out", out.string()}, [&] { return m.ready(out); });
        EXPECT_FALSE(fs::exists(out / "summary.json")) << m.name;
        const Result resumed = Run("evolve --resume " + out.string());
        ASSERT_EQ(resumed.exitCode, 0) << m.name << ": " << resumed.err;
        ExpectSameOutputs(dir_ / "whole", out);
    }
}

// The optimizers: kill-and-resume at three moments ending like an uninterrupted run (resume replays
// the run from its seed, answered from the archive), each killed on one thread and resumed on two
// against a run on two: thread-count independence in the same runs. NSGA-II's figures (the Pareto
// front's) are compared with the rest; CMA-ES draws the GA's, compared in the GA's test above.
TEST_F(SearchCli, OptimizerRunsGiveTheSameBytesWhateverTheThreadsAndResumeExactly) {
    for (const std::string algorithm : {"cmaes", "nsga2"}) {
        SCOPED_TRACE(algorithm);
        const std::string experiment = SmallOptimizer(algorithm, 4, 2, algorithm == "nsga2");
        const Result whole = Run("evolve " + experiment + " --out " + Path(algorithm + "_whole") + " --threads 2");
        ASSERT_EQ(whole.exitCode, 0) << whole.err;
        const std::pair<const char*, std::function<bool(const fs::path&)>> moments[] = {
            {"first", [](const fs::path& out) { return fs::exists(out / "evaluations.csv") && Slurp(out / "evaluations.csv").size() > 400; }},
            {"middle", [](const fs::path& out) { return Generation(out / "run_1" / "checkpoint.json") >= 3; }},
            {"second", [](const fs::path& out) { return Generation(out / "run_2" / "checkpoint.json") >= 1; }},
        };
        for (const auto& [name, ready] : moments) {
            const fs::path out = dir_ / (algorithm + "_" + name);
            KillWhen({ACTUATOR_BIN, "evolve", experiment, "--out", out.string(), "--threads", "1"}, [&] { return ready(out); });
            const Result resumed = Run("evolve --resume " + out.string() + " --threads 2");
            ASSERT_EQ(resumed.exitCode, 0) << name << ": " << resumed.err;
            ExpectSameOutputs(dir_ / (algorithm + "_whole"), out);
        }
    }
}

TEST_F(SearchCli, EveryAlgorithmRunsUnderTheThesisAndTheShellModel) {
    for (const std::string algorithm : {"cmaes", "xnes", "de", "sade", "pso", "nsga2", "moead"})
        for (const bool shell : {false, true}) {
            const bool multi = algorithm == "nsga2" || algorithm == "moead";
            const std::string model = shell ? R"("model": {"name": "shell", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 0}, "load": {"pressure_kpa": 1, "steps": 2}},)"
                                            : R"("model": {"name": "thesis"}, "sim": {"iterations": 2000},)";
            const std::string objectives = shell ? (multi ? (algorithm == "nsga2" ? R"(["contraction", "blocking_force"])" : R"(["contraction", "limit_margin"])") : R"(["contraction"])")
                                                 : (multi ? R"(["thesis_fitness", "stretch_fitness"])" : R"(["thesis_fitness"])");
            const std::string name = algorithm + (shell ? "_shell" : "_thesis");
            Write(name + ".json", R"({"id": ")" + name + R"(", "seed": 3, )" + model + R"( "render": {"figures": false, "thumbnails": false},
                "optimizer": {"algorithm": ")" + algorithm + R"(", "population": 12, "generations": 2, "objectives": )" + objectives + R"(,
                              "genome": {"family": "sine", "amplitude": [0.5, 4], "phase_end": [2, 3.1]}}})");
            const Result r = Run("evolve " + Path(name + ".json") + " --out " + Path(name));
            ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
            EXPECT_THAT(r.out, HasSubstr("stopped by generations")) << name;
            EXPECT_EQ(app::Table::Read((dir_ / name / "run_1" / "logbook.csv").string()).Rows(), 3u) << name;
            EXPECT_TRUE(fs::exists(dir_ / name / "run_1" / (multi ? "pareto_front.csv" : "halloffame.csv"))) << name;
        }
}

// Every algorithm killed mid-run with one thread and resumed with two ends as an uninterrupted run
// with two threads (the thesis model: quick; several objectives with the stretch test). What is
// compared is each algorithm's state: the figures, the same for every algorithm, are compared in
// the tests above.
TEST_F(SearchCli, EveryAlgorithmResumesExactlyAfterAKillWhateverTheThreads) {
    for (const std::string algorithm : {"xnes", "de", "sade", "pso", "moead"}) {
        SCOPED_TRACE(algorithm);
        const bool multi = algorithm == "moead";
        Write(algorithm + ".json", R"({"model": {"name": "thesis"}, "id": "k", "seed": 8, "sim": {"iterations": 3000}, "render": {"figures": false, "thumbnails": false},
            "optimizer": {"algorithm": ")" + algorithm + R"(", "population": 12, "generations": 5, "objectives": )" +
                                       (multi ? R"(["thesis_fitness", "stretch_fitness"])" : R"(["thesis_fitness"])") + R"(,
                          "genome": {"family": "bspline", "splines": 1, "control_points": 6}}})");
        const fs::path whole = dir_ / (algorithm + "_whole"), killed = dir_ / (algorithm + "_killed");
        ASSERT_EQ(Run("evolve " + Path(algorithm + ".json") + " --threads 2 --out " + whole.string()).exitCode, 0);
        KillWhen({ACTUATOR_BIN, "evolve", Path(algorithm + ".json"), "--threads", "1", "--out", killed.string()},
                 [&] { return Generation(killed / "run_1" / "checkpoint.json") >= 3; });
        const Result resumed = Run("evolve --resume " + killed.string() + " --threads 2");
        ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
        ExpectSameOutputs(whole, killed);
    }
}

// A run that wall time ended has ended: resumed, the GA and an optimizer alike only redraw, and
// every output (the logbook still ending "seconds", the archive) is what the first session left.
TEST_F(SearchCli, ARunEndedByWallTimeStaysEndedWhenResumed) {
    const std::pair<std::string, std::string> searches[] = {{SmallGa(10, 1, false), "evolve.stop.seconds=0.001"},
                                                            {SmallOptimizer("cmaes", 10), "optimizer.stop.seconds=0.001"}};
    for (const auto& [experiment, set] : searches) {
        SCOPED_TRACE(set);
        const fs::path ended = dir_ / ("ended_" + set.substr(0, 6)), copy = dir_ / ("copy_" + set.substr(0, 6));
        ASSERT_EQ(Run("evolve " + experiment + " --out " + ended.string() + " --set " + set).exitCode, 0);
        const app::Table log = app::Table::Read((ended / "run_1" / "logbook.csv").string());
        ASSERT_EQ(log.Text(log.Rows() - 1, "stopped_by"), "seconds");
        ASSERT_LT(log.Rows(), 11u) << "wall time stopped the run before its last generation";
        fs::copy(ended, copy, fs::copy_options::recursive);
        const Result resumed = Run("evolve --resume " + ended.string());
        ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
        ExpectSameOutputs(copy, ended);
    }
}

TEST_F(SearchCli, ParetoFrontsAreNonDominatedAndPictured) {
    const Result r = Run("evolve " + SmallOptimizer("nsga2", 4) + " --out " + Path("pareto"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const app::Table front = app::Table::Read((dir_ / "pareto" / "run_1" / "pareto_front.csv").string());
    ASSERT_GE(front.Rows(), 2u);
    EXPECT_THAT(front.Columns(), ::testing::ElementsAre("front", "evaluation", "generation", "status", "contraction_percent", "largest_stretch", "design",
                                                 "gene_spline1.c1", "gene_spline1.c2", "gene_spline1.c3", "gene_spline1.c4", "gene_spline1.c5",
                                                 "gene_spline1.c6", "gene_fibre_angle_deg"));
    // Nothing evaluated dominates a front design (contraction up, stretch down).
    const app::Table all = app::Table::Read((dir_ / "pareto" / "evaluations.csv").string());
    for (size_t f = 0; f < front.Rows(); ++f) {
        const double c = front.Number(f, "contraction_percent"), s = front.Number(f, "largest_stretch");
        for (size_t k = 0; k < all.Rows(); ++k) {
            if (all.Text(k, "status") != "ok") continue;
            const double c2 = all.Number(k, "contraction_percent"), s2 = all.Number(k, "max_stretch");
            EXPECT_FALSE(c2 >= c && s2 <= s && (c2 > c || s2 < s)) << "evaluation " << all.Text(k, "evaluation") << " dominates front design " << f;
        }
    }
    const std::vector<double> hypervolume = app::Table::Read((dir_ / "pareto" / "run_1" / "logbook.csv").string()).Numbers("hypervolume");
    ASSERT_EQ(hypervolume.size(), 5u);
    for (size_t g = 1; g < hypervolume.size(); ++g) EXPECT_GE(hypervolume[g], hypervolume[g - 1]) << "hypervolume fell";
    for (const char* figure : {"pareto_front.png", "pareto_designs.png", "hypervolume.png", "best_inflation.png"}) ExpectPicture(dir_ / "pareto" / figure);
}

TEST_F(SearchCli, OptimizerDefinitionsThatCannotRunAreRefused) {
    const std::string good = Slurp(SmallOptimizer("cmaes", 2));
    auto with = [&](const std::string& from, const std::string& to) {
        std::string text = good;
        const size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        Write("bad.json", text.replace(at, from.size(), to));
        return "evolve " + Path("bad.json") + " --out " + Path("bad");
    };
    ExpectRefused(with("\"cmaes\"", "\"cma-es\""), "unknown value 'cma-es' (choose cmaes, xnes, de, sade, pso, nsga2, moead or sga)");
    ExpectRefused(with("\"cmaes\"", "\"ga\""), "the thesis's GA (variable-length genomes) is the 'evolve' block");
    ExpectRefused(with("\"cmaes\"", "\"nsga2\""), "nsga2 optimises several objectives");
    ExpectRefused(with("\"population\": 8", "\"population\": 3"), "cmaes needs a population of at least 5 (got 3)");
    ExpectRefused(with("\"control\": [0, 8]", "\"control\": [8, 0]"), "low end above high end");
    ExpectRefused(with("[\"thesis_fitness\"]", "[\"blocking_force\"]"), "the thesis model gives only thesis_fitness, stretch_fitness and contraction");
    ExpectRefused(with("\"population\": 8", "\"population\": 8, \"parameters\": {\"sigma\": 0.2}"), "cmaes has no parameter 'sigma' (valid: sigma0, cc, cs, c1, cmu)");
    ExpectRefused(with("\"generations\": 2", "\"generation\": 2"), "did you mean 'optimizer.generations'?");
    ExpectRefused(with("\"generations\": 2", "\"generations\": 2, \"stop\": {\"stagnation\": -1}"), "'optimizer.stop.stagnation': '-1' is out of range (0 to 100000)");
    ExpectRefused("sweep " + SmallOptimizer("cmaes", 2) + " --out " + Path("bad"), "run it with 'actuator evolve'");
    Write("n.json", std::string(Slurp(SmallOptimizer("nsga2", 2))));
    std::string text = Slurp(Path("n.json"));
    text.replace(text.find("\"population\": 8"), 15, "\"population\": 10");
    Write("n.json", text);
    ExpectRefused("evolve " + Path("n.json") + " --out " + Path("bad"), "nsga2 needs a population that is a multiple of 4 (got 10; try 12)");
}

TEST_F(SearchCli, CompareRunsEveryContenderWithTheSameSeedsToTheSameBudget) {
    const std::string cmaes = SmallOptimizer("cmaes", 10);
    // The GA on the optimizer's problem: one spline of 6 control points in [0, 8], 3,000 iterations.
    Write("ga.json", R"({"model": {"name": "thesis"}, "id": "test", "title": "small GA", "seed": 99, "sim": {"iterations": 3000},
        "evolve": {"runs": 1, "population": 10, "generations": 10, "tournament": 3, "elite": 1, "mutpb": 0.5, "indpb": 0.2,
                   "genome": {"kind": "bspline", "region": "middle", "splines": 1, "control": [0, 8], "length": [6, 6]}}})");
    const std::string ga = Path("ga.json");
    const Result r = Run("compare " + ga + " " + cmaes + " --seeds 2 --evaluations 20 --out " + Path("cmp"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto ends = app::Table::Read((dir_ / "cmp" / "comparison.csv").string());
    ASSERT_EQ(ends.Rows(), 4u);  // 2 contenders x 2 seeds
    for (size_t k = 0; k < ends.Rows(); ++k) {
        EXPECT_GE(ends.Number(k, "evaluations"), 20) << ends.Text(k, "contender");
        EXPECT_LT(ends.Number(k, "evaluations"), 20 + 10) << ends.Text(k, "contender") << ": stops at the first generation past the budget";
    }
    // Each curve is the quantity its header names: it never falls, and it ends at the run's own best so
    // far (the optimizer's logbook column of that name; the GA's best individual, its hall of fame's
    // first). A reader that took another logbook column (a quartile) fails here.
    const auto curves = app::Table::Read((dir_ / "cmp" / "comparison_curves.csv").string());
    for (const std::string contender : {"o (cmaes)", "test (thesis GA)"})
        for (const std::string seed : {"1", "2"}) {
            double last = -INFINITY, lastEvaluations = 0;
            int points = 0;
            for (size_t k = 0; k < curves.Rows(); ++k) {
                if (curves.Text(k, "contender") != contender || curves.Text(k, "seed") != seed) continue;
                ++points;
                EXPECT_GE(curves.Number(k, "best_so_far"), last) << contender << " seed " << seed << ": a best so far that falls";
                last = curves.Number(k, "best_so_far");
                lastEvaluations = curves.Number(k, "evaluations");
            }
            ASSERT_GT(points, 1) << contender << " seed " << seed;
            const fs::path run = dir_ / "cmp" / (contender[0] == 'o' ? "o" : "test") / ("seed_" + seed) / "run_1";
            const auto logbook = app::Table::Read((run / "logbook.csv").string());
            if (contender[0] == 'o') {
                EXPECT_EQ(last, logbook.Number(logbook.Rows() - 1, "best_so_far")) << contender << " seed " << seed;
                EXPECT_EQ(lastEvaluations, logbook.Number(logbook.Rows() - 1, "evaluations"));
            } else {
                EXPECT_EQ(last, app::Table::Read((run / "halloffame.csv").string()).Number(0, "fitness")) << contender << " seed " << seed;
            }
            for (size_t k = 0; k < ends.Rows(); ++k)
                if (ends.Text(k, "contender") == contender && ends.Text(k, "seed") == seed) EXPECT_EQ(ends.Number(k, "best"), last);
        }
    // Each run is an ordinary results folder, seeded 1, 2, ...
    EXPECT_EQ(nlohmann::json::parse(Slurp(dir_ / "cmp" / "o" / "seed_2" / "experiment.json"))["seed"], 2);
    ExpectPicture(dir_ / "cmp" / "comparison.png");
    EXPECT_THAT(Slurp(dir_ / "cmp" / "report.md"), HasSubstr("| o (cmaes) | 2 |"));
    // Killed mid-way and resumed (with the --set it was started with): the same numbers, and the run
    // that was cut off ends as it would have (its figures left out: they are the runs' own).
    const std::vector<std::string> args{ACTUATOR_BIN, "compare", ga, cmaes, "--seeds", "2", "--evaluations", "20", "--set", "sim.iterations=2500",
                                        "--set", "render.figures=false", "--out", Path("cut")};
    ASSERT_EQ(Run("compare " + ga + " " + cmaes + " --seeds 2 --evaluations 20 --set sim.iterations=2500 --set render.figures=false --out " + Path("whole")).exitCode, 0);
    KillWhen(args, [&] { return fs::exists(dir_ / "cut" / "o" / "seed_1" / "evaluations.csv"); });
    const Result resumed = Run("compare --resume " + Path("cut"));
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_EQ(Slurp(dir_ / "cut" / "comparison.csv"), Slurp(dir_ / "whole" / "comparison.csv"));
    ExpectSameOutputs(dir_ / "whole" / "o" / "seed_1", dir_ / "cut" / "o" / "seed_1");
    ExpectRefused("compare --resume " + Path("cut") + " --set seed=3", "--set '[\"seed=3\"]' is not what");
    // Contenders must share one problem and one objective.
    ExpectRefused("compare " + ga + " " + SmallOptimizer("nsga2", 2) + " --out " + Path("bad"), "compare draws one objective's best");
    ExpectRefused("compare " + ga + " --out " + Path("bad"), "compare needs two or more experiment files");
    Write("other.json", Slurp(Path("ga.json")).replace(Slurp(Path("ga.json")).find("3000"), 4, "4000"));
    ExpectRefused("compare " + Path("other.json") + " " + cmaes + " --out " + Path("bad"), "iterations: '4000' -> '3000'");
    ExpectRefused("compare " + SmallGa(2, 1, false) + " " + cmaes + " --out " + Path("bad"),
                  "ga.json 2 B-spline(s) over the middle, 5 to 9 control points in [0, 8]; compare runs one problem");
    Write("dots.json", Slurp(Path("ga.json")).replace(Slurp(Path("ga.json")).find("\"test\""), 6, "\"..\""));
    ExpectRefused("compare " + Path("dots.json") + " " + cmaes + " --out " + Path("bad"), "its id is '..', which names no folder of its own");
    EXPECT_FALSE(fs::exists(Path("bad")));
    EXPECT_FALSE(fs::exists(dir_ / "seed_1"));
}

TEST_F(SearchCli, SweepResumedAfterAKillEndsLikeAnUninterruptedRun) {
    const std::string experiment = SmallSweep();
    ASSERT_EQ(Run("sweep " + experiment + " --out " + Path("whole") + " --threads 1").exitCode, 0);
    const fs::path out = dir_ / "cut";
    KillWhen({ACTUATOR_BIN, "sweep", experiment, "--out", out.string(), "--threads", "1"},
             [&] { return fs::exists(out / "thumbnails" / "evaluation_000007.png"); });
    const Result resumed = Run("sweep --resume " + out.string() + " --threads 2");
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    ExpectSameOutputs(dir_ / "whole", out);
}

TEST_F(SearchCli, AFolderWithResultsIsNeverMixedInto) {
    const std::string experiment = SmallGa(1, 1, false);
    ASSERT_EQ(Run("evolve " + experiment + " --out " + Path("a")).exitCode, 0);
    const std::string archive = Slurp(dir_ / "a" / "evaluations.capnp"), csv = Slurp(dir_ / "a" / "evaluations.csv");
    ExpectRefused("evolve " + experiment + " --out " + Path("a"), "already holds results");
    ExpectRefused("sweep " + SmallSweep() + " --out " + Path("a"), "already holds results");
    EXPECT_EQ(Slurp(dir_ / "a" / "evaluations.capnp"), archive);
    EXPECT_EQ(Slurp(dir_ / "a" / "evaluations.csv"), csv);
    ExpectRefused("evolve " + experiment + " --out " + Path("a") + " --resume --overwrite", "exclude each other");
    ExpectRefused("evolve --resume " + Path("nothing-here"), "holds no experiment.json");
    // Resuming a finished run changes nothing.
    ASSERT_EQ(Run("evolve --resume " + Path("a")).exitCode, 0);
    EXPECT_EQ(Slurp(dir_ / "a" / "evaluations.csv"), csv);
}

// A folder started by a version whose defaults for the model differ is not resumed: its results and
// new ones would be of two models. run.json holds the model as this version resolved it (defaults
// included); folders from before it resume as they did.
TEST_F(SearchCli, AResumeUnderOtherModelDefaultsIsRefused) {
    Write("shell.json", R"({"model": {"name": "shell", "geometry": {"length_mm": 30, "ring_vertices": 12, "rings": 8},
        "load": {"pressure_kpa": 0.5, "steps": 1}},
        "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]}, "axes": [{"parameter": "amplitude", "values": [1]}]}})");
    ASSERT_EQ(Run("sweep " + Path("shell.json") + " --out " + Path("shell")).exitCode, 0);
    const fs::path run = dir_ / "shell" / "run.json";
    nlohmann::ordered_json recorded = nlohmann::ordered_json::parse(Slurp(run));
    ASSERT_EQ(recorded["model"]["contact"], "on");
    ASSERT_EQ(Run("sweep --resume " + Path("shell")).exitCode, 0);  // the same version resumes
    recorded["model"]["contact"] = "off";  // as a version without contact by default recorded it
    Write("shell/run.json", recorded.dump(2));
    ExpectRefused("sweep --resume " + Path("shell"), "(contact: 'off' -> 'on')");
    recorded.erase("model");
    Write("shell/run.json", recorded.dump(2));
    EXPECT_EQ(Run("sweep --resume " + Path("shell")).exitCode, 0);
}

TEST_F(SearchCli, OverwriteKeepsTheOldResultsUntilTheNewRunHasOne) {
    ASSERT_EQ(Run("evolve " + SmallGa(1, 1, false) + " --out " + Path("a")).exitCode, 0);
    const std::string old = Slurp(dir_ / "a" / "evaluations.csv");
    // A run that fails before its first result puts the old results back.
    Write("bad.json", R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]}, "render": {"figures": 1}})");
    ExpectRefused("sweep " + Path("bad.json") + " --out " + Path("a") + " --overwrite", "expected true or false");
    EXPECT_EQ(Slurp(dir_ / "a" / "evaluations.csv"), old);
    // Interrupted (SIGTERM) before its first result: the old results are back in place.
    Write("slow.json", R"({"model": {"name": "thesis"}, "sim": {"iterations": 3000000}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]}})");
    {
        Child child({ACTUATOR_BIN, "sweep", Path("slow.json"), "--out", Path("a"), "--overwrite"});
        ASSERT_TRUE(WaitUntil([&] { return fs::exists(Path("a/run.json")) && Slurp(dir_ / "a" / "run.json").find("3000000") != std::string::npos; }, 30));
        EXPECT_TRUE(fs::exists(Path("a.replaced-" + std::to_string(child.Pid())))) << "the old results are set aside, not deleted";
        child.Kill(SIGTERM);
    }
    EXPECT_EQ(Slurp(dir_ / "a" / "evaluations.csv"), old);
    // A run that gets its results replaces them.
    ASSERT_EQ(Run("sweep " + SmallSweep(3) + " --out " + Path("a") + " --overwrite").exitCode, 0);
    EXPECT_THAT(Slurp(dir_ / "a" / "evaluations.csv"), HasSubstr(",grid,"));
    for (const auto& e : fs::directory_iterator(dir_)) EXPECT_THAT(e.path().filename().string(), ::testing::Not(HasSubstr("replaced")));
}

TEST_F(SearchCli, OneEvaluationIdInTheArchiveTheLogTheThumbnailsAndRender) {
    ASSERT_EQ(Run("evolve " + SmallGa(3, 2) + " --out " + Path("a")).exitCode, 0);
    const std::string archive = Path("a/evaluations.capnp");
    const auto records = Records(dir_ / "a", dir_ / "meshes");
    const auto log = app::ParseCsv(Slurp(dir_ / "a" / "evaluations.csv"));
    ASSERT_EQ(log.size(), records.size() + 1);
    const size_t thumbnail = static_cast<size_t>(std::find(log[0].begin(), log[0].end(), "thumbnail") - log[0].begin());
    ASSERT_LT(thumbnail, log[0].size()) << "evaluations.csv has a thumbnail column";
    for (size_t k = 0; k < records.size(); ++k) {
        EXPECT_EQ(records[k]["id"].get<size_t>(), k);
        EXPECT_EQ(log[k + 1][0], std::to_string(k));
        EXPECT_EQ(log[k + 1][1], records[k]["role"]);
        EXPECT_TRUE(fs::exists(dir_ / "a" / "thumbnails" / log[k + 1][thumbnail])) << log[k + 1][thumbnail];
    }
    EXPECT_EQ(log[5][thumbnail], "evaluation_000004.png");
    // inspect filters.
    const auto count = [&](const std::string& filter) {
        const Result r = Run("inspect " + archive + " --json " + filter);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return nlohmann::json::parse(r.out)["evaluations"];
    };
    for (const auto& e : count("--run 2")) EXPECT_EQ(e["run"], 2);
    EXPECT_EQ(count("--generation 0 --run 1").size(), 10u);  // the initial population
    for (const auto& e : count("--min-fitness 0.1")) EXPECT_GE(e["fitness"].get<double>(), 0.1);
    EXPECT_EQ(count("--limit 3").size(), 3u);
    const auto top = count("--top 3");
    ASSERT_EQ(top.size(), 3u);
    EXPECT_GE(top[0]["fitness"].get<double>(), top[1]["fitness"].get<double>());
    EXPECT_EQ(count("--role figure").size(), 2u);  // the best design's stretch test and its first hundred iterations
    // Complete records: every control point of every spline, with the region.
    EXPECT_EQ(records[0]["shape"]["region"], "middle");
    EXPECT_EQ(records[0]["shape"]["control_points"].size(), 2u);
    const Result table = Run("inspect " + archive + " --status ok --limit 2");
    EXPECT_THAT(table.out, HasSubstr("2 of " + std::to_string(records.size()) + " evaluations shown"));

    // render --from and simulate --from take the same id.
    const Result rendered = Run("render --from " + archive + " --index 4 --out " + Path("again") + " --turntable 2");
    ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
    EXPECT_EQ(nlohmann::json::parse(rendered.out)["simulated"], false);
    ExpectPicture(dir_ / "again" / "evaluation_000004.png");
    EXPECT_TRUE(fs::exists(dir_ / "again" / "turntable" / "frame_0001.png"));
    const Result again = Run("simulate --from " + archive + " --index 4");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(nlohmann::json::parse(again.out)["fitness"], records[4]["fitness"]);
    // The design column feeds straight back into simulate.
    const size_t design = static_cast<size_t>(std::find(log[0].begin(), log[0].end(), "design") - log[0].begin());
    ASSERT_LT(design, log[0].size()) << "evaluations.csv has a design column";
    const Result fromCsv = Run("simulate --model thesis --shape bspline --control-points \"" + log[5][design] + "\" --iterations 3000");
    ASSERT_EQ(fromCsv.exitCode, 0) << fromCsv.err;
    EXPECT_EQ(nlohmann::json::parse(fromCsv.out)["fitness"], records[4]["fitness"]);

    ExpectRefused("render --from " + archive + " --out " + Path("x"), "--index");
    ExpectRefused("render --from " + archive + " --index 100000 --out " + Path("x"), "holds evaluations 0 to");
    ExpectRefused("render --from " + archive + " --index 1 --shape sine --out " + Path("x"), "--shape");
    ExpectRefused("render --from " + archive + " --index 1 --timelapse 3 --out " + Path("x"), "--timelapse");
    ExpectRefused("simulate --from " + archive + " --index 1 --amplitude 3", "--amplitude");
    ExpectRefused("inspect " + Path("missing.capnp"), "missing.capnp");
    Write("junk.capnp", std::string(3000, '\x7f'));
    ExpectRefused("inspect " + Path("junk.capnp"), "not an evaluation archive");
    ExpectRefused("inspect " + archive + " --status weird", "weird");
    ExpectRefused("inspect " + archive + " --top 2 --sort id", "--top");
}

TEST_F(SearchCli, SetOverridesAnyExperimentKeyAndIsCheckedLikeTheFile) {
    const Result r = Run("evolve " + SmallGa(10, 2, false) + " --out " + Path("o") + " --set evolve.generations=2 --set evolve.runs=1 --set sim.iterations=500");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(app::ParseCsv(Slurp(dir_ / "o" / "run_1" / "logbook.csv")).size(), 4u);
    EXPECT_FALSE(fs::exists(dir_ / "o" / "run_2"));
    // The saved experiment is what ran.
    const auto saved = nlohmann::json::parse(Slurp(dir_ / "o" / "experiment.json"));
    EXPECT_EQ(saved["evolve"]["generations"], 2);
    EXPECT_EQ(saved["sim"]["iterations"], 500);
    ExpectRefused("evolve " + SmallGa() + " --out " + Path("p") + " --set evolve.generatons=2", "did you mean 'evolve.generations'");
    ExpectRefused("evolve " + SmallGa() + " --out " + Path("p") + " --set sim.pressure_scale=-1", "--set sim.pressure_scale=-1");
    ExpectRefused("evolve " + SmallGa() + " --out " + Path("p") + " --set evolve", "KEY.PATH=VALUE");
    ExpectRefused("sweep " + SmallSweep() + " --out " + Path("p") + " --set sweep.axes[3].points=2", "has 1 entries");
    EXPECT_FALSE(fs::exists(Path("p")) && fs::exists(Path("p/evaluations.capnp")));
}

TEST_F(SearchCli, BadExperimentFilesAreRefusedPrecisely) {
    const std::string sweep = R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 3}]}})";
    auto refuse = [&](const std::string& text, const std::string& mentions, std::source_location where = std::source_location::current()) {
        Write("bad.json", text);
        ExpectRefused("sweep " + Path("bad.json") + " --out " + Path("o"), mentions, where);
    };
    refuse(R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 3}]}, "iteratons": 5})",
           "'iteratons': unknown key");
    refuse(R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": "many"}]}})",
           "'sweep.axes[0].points': expected a whole number, got 'many'");
    refuse(R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 0}]}})",
           "'sweep.axes[0].points': '0' is out of range");
    refuse(R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "cone"}, "axes": [{"parameter": "amplitude", "from": 1, "to": 2, "points": 3}]}})",
           "'sweep.shape.family': unknown value 'cone'");
    refuse(R"({"model": {"name": "thesis"}, "evolve": {"population": 10, "tournament": 3, "mutpb": 1.5, "genome": {"kind": "bspline"}}})", "'evolve.mutpb': '1.5' is out of range");
    refuse(R"({"model": {"name": "thesis"}, "evolve": {"genome": {"kind": "bspline", "length": [3, 9]}}})", "'evolve.genome.length'");
    refuse(R"({"model": {"name": "thesis"}, "evolve": {"genome": {"kind": "bspline", "splines": 3}}})", "'evolve.genome.splines'");
    refuse(R"({"model": {"name": "thesis"}, "evolve": {"genome": {"kind": "bspline"}}, "sim": {"iterations": 18446744073709551615}})", "'18446744073709551615' is out of range");
    refuse(R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine", "amplitude": 1e400}, "axes": []}})", "line 1");
    refuse(R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine"}}})", "'sweep.axes': missing");
    refuse(R"({"model": {"name": "thesis"}, "shape": {"family": "sine"}, "sweep": {}})", "'shape': has moved");
    refuse(R"({"model": {"name": "thesis"}, "iterations": 100, "sweep": {}})", "'iterations': has moved");
    refuse(R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]}, "sim": {"pressure": 0.01}})",
           "did you mean 'sim.pressure_scale'");
    refuse(R"({"model": {"name": "thesis"}, "sweep": )", "not valid JSON");
    refuse("[1, 2]", "must hold a JSON object");
    refuse(R"({"sim": {"load": "squash"}, )" + sweep.substr(1), "'sim.load': unknown value 'squash'");
    Write("ok.json", sweep);
    ExpectRefused("evolve " + Path("ok.json") + " --out " + Path("o"), "run it with 'actuator sweep'");
    ExpectRefused("sweep " + Path("missing.json") + " --out " + Path("o"), "missing.json");
    ExpectRefused("sweep " + Path("ok.json"), "--out");
    EXPECT_FALSE(fs::exists(Path("o/results.csv")));
}

TEST_F(SearchCli, EveryShippedExperimentFileIsValid) {
    // Parsing happens before any work: a missing --out is reported only after the file was read.
    int files = 0;
    for (const auto& folder : {fs::path(ACTUATOR_ASSETS_DIR) / "experiments", fs::path(ACTUATOR_ASSETS_DIR) / "experiments" / "shell",
                               fs::path(ACTUATOR_ASSETS_DIR) / "experiments" / "optimizers", fs::path(ACTUATOR_ASSETS_DIR) / "experiments" / "optimizers" / "compare",
                               fs::path(ACTUATOR_ASSETS_DIR) / "experiments" / "optimizers" / "compare_shell"})
        for (const auto& entry : fs::directory_iterator(folder)) {
            if (entry.is_directory()) continue;
            const std::string name = entry.path().filename().string();
            const bool optimizers = folder.string().find("optimizers") != std::string::npos;
            const std::string command = name.find("5.") <= 2 || optimizers ? "evolve " : "sweep ";
            const Result r = Run(command + entry.path().string());
            EXPECT_THAT(r.err, HasSubstr("--out DIR is required")) << entry.path();
            ++files;
        }
    EXPECT_EQ(files, 10 + 12 + 5 + 3 + 3) << "the thesis's experiments, part 2's under the shell model (2 under vacuum), the optimizers' and their comparisons'";
}

// --thumbnails pictures every evaluation of the experiments that ask for it, as evolve and sweep do,
// and a resume keeps what the reproduction was started with.
TEST_F(SearchCli, ReproduceMakesThumbnailsOnlyWhenAskedTo) {
    fs::create_directories(dir_ / "one");
    fs::copy_file(fs::path(ACTUATOR_ASSETS_DIR) / "experiments" / "4.1_amplitude_sweep.json", dir_ / "one" / "4.1_amplitude_sweep.json");
    const std::string experiments = " --quick --part thesis --experiments " + (dir_ / "one").string();
    ASSERT_EQ(Run("reproduce" + experiments + " --thumbnails --out " + Path("with")).exitCode, 0);
    EXPECT_TRUE(fs::exists(dir_ / "with" / "4.1_amplitude_sweep" / "thumbnails" / "evaluation_000000.png"));
    ASSERT_EQ(Run("reproduce" + experiments + " --out " + Path("without")).exitCode, 0);
    EXPECT_FALSE(fs::exists(dir_ / "without" / "4.1_amplitude_sweep" / "thumbnails"));
    const Result refused = Run("reproduce --resume " + Path("without") + " --thumbnails");
    EXPECT_EQ(refused.exitCode, 2);
    EXPECT_THAT(refused.err, HasSubstr("--thumbnails"));
}

// Part 2 alone has no thesis-model bests to re-evaluate: its finding says so instead of counting
// "0 best designs".
TEST_F(SearchCli, PartTwoAloneSaysPartOneIsMissing) {
    // Two of part 2's files (an inflated and a vacuum study) are enough to say so.
    const fs::path shipped = fs::path(ACTUATOR_ASSETS_DIR) / "experiments" / "shell";
    fs::create_directories(dir_ / "experiments" / "shell");
    for (const char* name : {"S4.1_amplitude_sweep.json", "SV4.1_vacuum_amplitude_sweep.json"})
        fs::copy_file(shipped / name, dir_ / "experiments" / "shell" / name);
    const Result r = Run("reproduce --quick --part physical --experiments " + Path("experiments") + " --out " + Path("physical"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string report = Slurp(dir_ / "physical" / "report.md");
    EXPECT_THAT(report, HasSubstr("**Finding.**"));
    EXPECT_THAT(report, HasSubstr("Part 1's results (the thesis model's runs) are not in this folder"));
    EXPECT_THAT(report, Not(HasSubstr("Of the thesis model's 0 best designs")));
}

TEST_F(SearchCli, QuickReproductionWritesACompleteReport) {
    const Result r = Run("reproduce --quick --out " + Path("thesis"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string report = Slurp(dir_ / "thesis" / "report.md");
    for (const char* section : {"## 4.1 ", "## 4.2 ", "## 4.3 ", "## 5.1 ", "## 5.2 ", "## 5.3 ", "## 5.4 ", "## 5.5 ", "## 6.1 ", "## 6.2 ", "## S4.1 ",
                                "## S5.4 ", "## SV4.1 ", "## SV5.2 ", "# Part 2: the thesis's experiments under the `shell` model", "**Finding.**",
                                "**Under vacuum.**", "# Part 3: optimizers compared",
                                "## Under the thesis model", "## Under the shell model"})
        EXPECT_THAT(report, HasSubstr(section));
    const auto comparison = app::ParseCsv(Slurp(dir_ / "thesis" / "comparison" / "comparison.csv"));
    EXPECT_EQ(comparison.size(), 12u) << "a row per experiment of part 2 that re-runs one of part 1 (the header, 7 isotropic, 2 with fibres, 2 under vacuum)";
    // The vacuum studies' best beside the best inflated design, with its walls in contact.
    const size_t vacuum = report.find("**Under vacuum.**");
    ASSERT_NE(vacuum, std::string::npos);
    const std::string vacuumText = report.substr(vacuum, report.find("\n\n", vacuum) - vacuum);
    EXPECT_THAT(vacuumText, HasSubstr("contact pairs"));
    EXPECT_THAT(vacuumText, HasSubstr("Beside it, the best inflated design without fibres"));
    EXPECT_THAT(report, HasSubstr("**With fibres.**"));
    // The best fibre-reinforced design's characteristic curves, drawn and tabled (the figure is
    // checked below with every picture the report shows).
    EXPECT_THAT(report, HasSubstr("Its characteristic curves (experiment "));
    EXPECT_THAT(report, HasSubstr("_best_force_contraction.png)"));
    bool curvesTable = false;
    for (const auto& entry : fs::directory_iterator(dir_ / "thesis" / "comparison"))
        if (entry.path().filename().string().ends_with("_best_characteristic.csv")) {
            curvesTable = true;
            const app::Table curves = app::Table::Read(entry.path().string());
            EXPECT_GT(curves.Rows(), 3u * 6u) << "three isobaric curves of six points, the isometric and free-stroke curves";
        }
    EXPECT_TRUE(curvesTable);
    EXPECT_THAT(report, HasSubstr("Of the thesis model's "));
    EXPECT_THAT(report, Not(HasSubstr("Part 1's results")));
    EXPECT_THAT(report, HasSubstr("| ours | thesis |"));
    // Every figure the report shows exists and is a real picture.
    size_t images = 0;
    for (size_t at = report.find("]("); at != std::string::npos; at = report.find("](", at + 2)) {
        if (report.compare(at - 1, 1, "`") == 0 || report[report.rfind('[', at) - 1] != '!') continue;  // links, not images
        const size_t end = report.find(')', at);
        ++images;
        ExpectPicture(dir_ / "thesis" / report.substr(at + 2, end - at - 2));
    }
    EXPECT_GE(images, 30u);
    // A design refused before any solve (unbuildable, or outside the study's envelope) is said in
    // words, never drawn as an empty frame "at nan kPa".
    size_t unbuildable = 0;
    for (size_t at = report.find(" beside "); at != std::string::npos; at = report.find(" beside ", at + 1)) {
        const size_t end = std::min(report.find("\n### ", at), report.find("\n# ", at));
        const std::string section = report.substr(at, end == std::string::npos ? std::string::npos : end - at);
        if (section.find(": invalid-geometry.") == std::string::npos && section.find(": outside-envelope.") == std::string::npos) continue;
        ++unbuildable;
        EXPECT_THAT(section, Not(HasSubstr("_thesis_best_under_"))) << section;
    }
    EXPECT_GT(unbuildable, 0u) << "the quick run's 4.2 and 4.3 bests pass through zero radius";
    // A thesis shape under a fibre study carries the study's braid: not "the same design".
    EXPECT_THAT(report, Not(HasSubstr("the same design under")));
    EXPECT_THAT(report, HasSubstr("### S5.4F beside 5.4"));
    const size_t fibreSection = report.find("### S5.4F beside 5.4");
    EXPECT_THAT(report.substr(fibreSection, report.find("\n### ", fibreSection + 1) - fibreSection), HasSubstr("with a braid at +/-30 deg added"));
    // Part 2's finding is computed: part 3's shell searches are cited with their numbers, and the fibre
    // studies' designs are counted by class.
    EXPECT_THAT(report, HasSubstr("Part 3's searches aimed at contraction alone under the same model ("));
    EXPECT_THAT(report, HasSubstr("counted by what their wall carries"));
    // Every table and figure of chapters 4-6 has a row and a verdict, and no reason contradicts the
    // run's own numbers.
    EXPECT_THAT(testing_support::ThesisReportProblems(report), ::testing::IsEmpty());
    for (const char* figure : {"4.3_abs_sine_sweep/thesis_points.png", "5.2_bspline_middle/run_bests.png", "5.1_bspline_entire/best_time_lapse.png"})
        ExpectPicture(dir_ / "thesis" / figure);
    // Thumbnails are asked for (--thumbnails, below): by default no experiment makes them.
    for (const auto& entry : fs::recursive_directory_iterator(dir_ / "thesis"))
        EXPECT_NE(entry.path().filename(), "thumbnails") << entry.path();
}
