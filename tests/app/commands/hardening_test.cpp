// No crash, no hang, no lost or mixed result: one test per class of hostile input or operator
// mistake, each asserting the exit code, the message, and that nothing was written or lost. Label
// `hardening`; the sanitizer build (-DACTUATOR_SANITIZE=ON) runs these under ASan and UBSan.
#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <zlib.h>

#include "cli_fixture.h"
#include "formats/csv.h"
#include "sim/optimize.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing_support::Child;
using testing_support::WaitUntil;

namespace {

class Hardening : public CliTest {
protected:
    std::string Ga(int generations = 3) const {
        Write("ga.json", R"({"model": {"name": "thesis"}, "id": "h", "seed": 3, "sim": {"iterations": 2000}, "render": {"figures": true},
            "evolve": {"runs": 1, "population": 8, "generations": )" + std::to_string(generations) +
                             R"(, "genome": {"kind": "bspline", "splines": 1, "length": [5, 7]}}})");
        return Path("ga.json");
    }
    static std::vector<std::string> Temporaries(const fs::path& dir) {
        std::vector<std::string> found;
        for (const auto& e : fs::recursive_directory_iterator(dir)) {
            const std::string name = e.path().filename().string();
            if (name.find(".tmp") != std::string::npos) found.push_back(e.path().string());
        }
        return found;
    }
    // Every file under `dir` with the hash of its bytes, to show that a refused command touched nothing.
    static std::map<std::string, size_t> Snapshot(const fs::path& dir) {
        std::map<std::string, size_t> files;
        for (const auto& e : fs::recursive_directory_iterator(dir))
            if (e.is_regular_file() && e.path().filename() != ".lock") files[e.path().string()] = std::hash<std::string>{}(Slurp(e.path()));
        return files;
    }
};

}  // namespace

TEST_F(Hardening, DeepExpressionsAreRefusedWhereverNumbersAreRead) {
    const std::string signs(70000, '-');
    ExpectRefused("simulate --model thesis --shape sine --amplitude " + signs + "1", "nests deeper than");
    Write("deep.obj", "v " + signs + "1 0 0\n");
    ExpectRefused("simulate --model thesis --mesh " + Path("deep.obj"), "nests deeper than");
    Write("deep.json", R"({"model": {"name": "thesis"}, "sweep": {"shape": {"family": "sine", "amplitude": ")" + std::string(300000, '(') + "1" + std::string(300000, ')') +
                           R"("}, "axes": [{"parameter": "amplitude", "values": [1]}]}})");
    ExpectRefused("sweep " + Path("deep.json") + " --out " + Path("o"), "is not a number");
    EXPECT_FALSE(fs::exists(Path("o")));
}

TEST_F(Hardening, HostileCheckpointsAreRefusedOnResume) {
    ASSERT_EQ(Run("evolve " + Ga(2) + " --out " + Path("a")).exitCode, 0);
    const fs::path checkpoint = dir_ / "a" / "run_1" / "checkpoint.json";
    const std::string good = Slurp(checkpoint);
    auto edited = [&](const std::function<void(nlohmann::json&)>& edit, const std::string& mentions, std::source_location where = std::source_location::current()) {
        nlohmann::json j = nlohmann::json::parse(good);
        edit(j);
        Write("a/run_1/checkpoint.json", j.dump());
        const auto before = Snapshot(dir_ / "a");
        ExpectRefused("evolve --resume " + Path("a"), mentions, where);
        EXPECT_EQ(Snapshot(dir_ / "a"), before) << "a refused resume changed the folder";
    };
    edited([](auto& j) { j["population"] = nlohmann::json::array(); }, "population has 0 individuals");
    edited([](auto& j) { j["population"][0]["genome"] = {{1, 2}}; }, "2 control points");
    edited([](auto& j) { j["rng"] = {0, 0, 0, 0}; }, "all zero");
    edited([](auto& j) { j["archive_count"] = 100000; }, "fewer than its checkpoint's");
    Write("a/run_1/checkpoint.json", "{\"version\": 2");
    ExpectRefused("evolve --resume " + Path("a"), "not a checkpoint");
}

TEST_F(Hardening, AResumeUnderAChangedExperimentIsRefusedNamingWhatChanged) {
    ASSERT_EQ(Run("evolve " + Ga(2) + " --out " + Path("a")).exitCode, 0);
    const std::string original = Slurp(dir_ / "a" / "experiment.json");
    nlohmann::json saved = nlohmann::json::parse(original);
    saved["evolve"]["genome"]["kind"] = "free-xy";
    saved["evolve"]["genome"].erase("splines");
    saved["evolve"]["genome"].erase("length");
    Write("a/experiment.json", saved.dump());
    const auto before = Snapshot(dir_ / "a");
    ExpectRefused("evolve --resume " + Path("a"), "evolve.genome.kind: 'bspline' -> 'free-xy'");
    EXPECT_EQ(Snapshot(dir_ / "a"), before);
    // The same through --set on the command line.
    Write("a/experiment.json", original);
    ExpectRefused("evolve --resume " + Path("a") + " --set evolve.population=9", "evolve.population: '8' -> '9'");
}

TEST_F(Hardening, ATornArchiveTailIsCutBeforeAResumeAppends) {
    const std::string experiment = Ga(4);
    ASSERT_EQ(Run("evolve " + experiment + " --out " + Path("whole")).exitCode, 0);
    const fs::path out = dir_ / "torn";
    {
        Child child({ACTUATOR_BIN, "evolve", experiment, "--out", out.string()});
        ASSERT_TRUE(WaitUntil([&] { return fs::exists(out / "run_1" / "checkpoint.json"); }, 60));
        child.Kill(SIGKILL);
    }
    // A crash in the middle of a write: half a record at the end.
    std::ofstream(out / "evaluations.capnp", std::ios::app | std::ios::binary) << std::string("\x90\x01\x00\x00\xde\xad\xbe\xef partial", 17);
    const Result resumed = Run("evolve --resume " + out.string());
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    const Result all = Run("inspect " + (out / "evaluations.capnp").string() + " --json");
    const auto json = nlohmann::json::parse(all.out);
    EXPECT_FALSE(json["truncated"].get<bool>());
    EXPECT_FALSE(json["damaged"].get<bool>());
    EXPECT_EQ(json["total"], nlohmann::json::parse(Run("inspect " + Path("whole/evaluations.capnp") + " --json").out)["total"]);
    EXPECT_EQ(Slurp(out / "evaluations.csv"), Slurp(dir_ / "whole" / "evaluations.csv"));
}

TEST_F(Hardening, TwoRunsIntoOneFolderAreRefusedNamingTheHolder) {
    Write("slow.json", R"({"model": {"name": "thesis"}, "sim": {"iterations": 3000000}, "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1, 2]}]}})");
    Child first({ACTUATOR_BIN, "sweep", Path("slow.json"), "--out", Path("busy")});
    ASSERT_TRUE(WaitUntil([&] { return fs::exists(Path("busy/run.json")); }, 30));
    ExpectRefused("sweep " + Path("slow.json") + " --out " + Path("busy") + " --resume", "is in use by pid " + std::to_string(first.Pid()));
    ExpectRefused("sweep " + Path("slow.json") + " --out " + Path("busy") + " --overwrite", "is in use by pid " + std::to_string(first.Pid()));
    EXPECT_TRUE(first.Running());
}

TEST_F(Hardening, OutputThatCouldNotBeWrittenIsNeverASuccess) {
    ASSERT_EQ(Run("evolve " + Ga(1) + " --out " + Path("a")).exitCode, 0);
    for (const std::string& command : std::vector<std::string>{"simulate --model thesis --iterations 10", "inspect " + Path("a/evaluations.capnp"), "--help", "simulate --help"}) {
        const Result r = Run(command + " > /dev/full");
        EXPECT_NE(r.exitCode, 0) << command;
        EXPECT_THAT(r.err, HasSubstr("could not write the output")) << command;
    }
}

TEST_F(Hardening, OutputsNeverReplaceLinksDevicesOrInputs) {
    fs::create_symlink("/etc/hostname", Path("link.obj"));
    ExpectRefused("simulate --model thesis --iterations 1 --save-mesh " + Path("link.obj"), "symbolic link");
    EXPECT_TRUE(fs::is_symlink(Path("link.obj")));
    ExpectRefused("simulate --model thesis --iterations 1 --save-mesh /dev/null", "not a regular file");
    ASSERT_EQ(Run("render --model thesis --shape sine --size 160x120 --iterations 100 --out " + Path("p")).exitCode, 0);
    const std::string expected = Slurp(dir_ / "p" / "inflation.png");
    ExpectRefused("imgdiff " + Path("p/inflation.png") + " " + Path("p/stretch.png") + " --diff " + Path("p/inflation.png"), "also an input");
    EXPECT_EQ(Slurp(dir_ / "p" / "inflation.png"), expected);
    ASSERT_EQ(Run("simulate --model thesis --iterations 10 --save-mesh " + Path("m.obj")).exitCode, 0);
    const std::string mesh = Slurp(Path("m.obj"));
    ExpectRefused("simulate --model thesis --mesh " + Path("m.obj") + " --save-initial " + Path("m.obj"), "also an input");
    EXPECT_EQ(Slurp(Path("m.obj")), mesh);
}

TEST_F(Hardening, BadInputStopsARunBeforeAnyOutputIsWritten) {
    fs::create_directories(dir_ / "r" / "stretch.png");
    ExpectRefused("render --model thesis --shape sine --out " + Path("r"), "stretch.png");
    EXPECT_FALSE(fs::exists(dir_ / "r" / "inflation.png"));
    fs::create_directories(dir_ / "t");
    std::ofstream(dir_ / "t" / "turntable") << "a file where the frames go";
    ExpectRefused("render --model thesis --shape sine --out " + Path("t") + " --turntable 3", "turntable");
    EXPECT_FALSE(fs::exists(dir_ / "t" / "inflation.png"));
}

TEST_F(Hardening, InterruptedRunsLeaveNoTemporaries) {
    for (int signal : {SIGINT, SIGTERM}) {
        const fs::path out = dir_ / ("frames_" + std::to_string(signal));
        {
            Child render({ACTUATOR_BIN, "render", "--model", "thesis", "--shape", "sine", "--iterations", "100", "--turntable", "400", "--png-level", "9", "--out", out.string()});
            // The frames wait as temporaries until the whole set is written (OutputBatch).
            ASSERT_TRUE(WaitUntil([&] { return fs::exists(out / "turntable") && Temporaries(out).size() >= 4; }, 60));
            render.Kill(signal);
        }
        EXPECT_THAT(Temporaries(out), ::testing::IsEmpty()) << "signal " << signal;
        const fs::path ga = dir_ / ("ga_" + std::to_string(signal));
        {
            Child evolve({ACTUATOR_BIN, "evolve", Ga(30), "--out", ga.string()});
            ASSERT_TRUE(WaitUntil([&] { return fs::exists(ga / "run_1" / "checkpoint.json"); }, 60));
            evolve.Kill(signal);
        }
        EXPECT_THAT(Temporaries(ga), ::testing::IsEmpty()) << "signal " << signal;
    }
    // SIGKILL cannot be caught: the next run into the folder removes what the dead process left.
    // Six generations: the resume runs the rest to the end (thirty took 25 s under the sanitizers).
    const fs::path ga = dir_ / "ga_kill";
    {
        Child evolve({ACTUATOR_BIN, "evolve", Ga(6), "--out", ga.string()});
        ASSERT_TRUE(WaitUntil([&] { return fs::exists(ga / "run_1" / "checkpoint.json"); }, 60));
        std::ofstream(ga / ".act4194300-7.tmp") << "left by a killed process";
        ASSERT_TRUE(WIFSIGNALED(evolve.Kill(SIGKILL))) << "the run ended before it was killed: the resume proves nothing";
    }
    ASSERT_EQ(Run("evolve --resume " + ga.string()).exitCode, 0);
    EXPECT_THAT(Temporaries(ga), ::testing::IsEmpty());
}

TEST_F(Hardening, TextInCsvIsQuotedAsRfc4180Says) {
    const std::string label = R"(say "hi", then
a new line)";
    nlohmann::json experiment = {{"model", {{"name", "thesis"}}}, {"sim", {{"iterations", 200}}}, {"render", {{"figures", false}}},
                                 {"evaluate", {{"shapes", {{{"family", "cylinder"}, {"label", label}}, {{"family", "sine"}, {"amplitude", 2}, {"phase", {0.5, 2.6}}}}}}}};
    Write("list.json", experiment.dump());
    ASSERT_EQ(Run("sweep " + Path("list.json") + " --out " + Path("l")).exitCode, 0);
    for (const char* file : {"results.csv", "evaluations.csv"}) {
        const auto rows = app::ParseCsv(Slurp(dir_ / "l" / file));
        ASSERT_EQ(rows.size(), 3u) << file;
        EXPECT_EQ(rows[1].size(), rows[0].size()) << file;
        EXPECT_TRUE(std::find(rows[1].begin(), rows[1].end(), label) != rows[1].end()) << file;
    }
}

TEST_F(Hardening, JobsTooLargeForTheMachineAreRefusedUpFront) {
    ExpectRefused("render --model thesis --resolution 256 --turns 256 --iterations 100000 --timelapse 100000 --out " + Path("big"), "GB of snapshots");
    EXPECT_FALSE(fs::exists(Path("big/inflation.png")));
    const auto started = std::chrono::steady_clock::now();
    ExpectRefused("simulate --model thesis --mesh /dev/zero", "is a device");
    ExpectRefused("simulate --model thesis --shape free-xy --offsets /dev/zero", "is a device");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 5);
    ExpectRefused("simulate --model thesis --resolution 4096 --turns 4096", "vertices");
    // The physical models' work is bounded from the mesh before anything is built: 1000 x 1000 would
    // need about 35 GB; a long thin tube meshed near-equilateral (--rings 0) would need far more.
    ExpectRefused("simulate --model shell --shape cylinder --ring-vertices 1000 --rings 1000", "would need about 35");
    ExpectRefused("render --model membrane --shape cylinder --ring-vertices 1000 --rings 1000 --out " + Path("big"), "GB per evaluation");
    ExpectRefused("simulate --model shell --shape cylinder --ring-vertices 4096 --rings 0 --length-mm 1e5", "GB per evaluation");
    Write("big.json", R"({"id": "b", "model": {"name": "shell", "geometry": {"ring_vertices": 1000, "rings": 1000}},
        "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]}})");
    ExpectRefused("sweep " + Path("big.json") + " --out " + Path("big"), "GB per evaluation");
    EXPECT_FALSE(fs::exists(Path("big")));
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 10);
}

TEST_F(Hardening, LongFileNamesWorkUpToTheSystemsLimit) {
    const std::string name254 = std::string(250, 'm') + ".obj";
    const Result ok = Run("simulate --model thesis --iterations 1 --save-mesh " + Path(name254));
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_TRUE(fs::exists(Path(name254)));
    ExpectRefused("simulate --model thesis --iterations 1 --save-mesh " + Path(std::string(260, 'm') + ".obj"), "longer than 255 bytes");
}

TEST_F(Hardening, AFailedRunIsPicturedAsFarAsItIsFinite) {
    const Result r = Run("render --model thesis --shape sine --amplitude 4.1 --iterations 40000 --size 320x240 --out " + Path("nan"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(nlohmann::json::parse(r.out)["inflation"]["status"], "ok");
    const render::Image image = testing_support::LoadPng(dir_ / "nan" / "inflation.png");
    ASSERT_FALSE(image.Empty());
    // The "before" mesh (left half) is drawn: not all white.
    int dark = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width / 2; ++x) dark += image.rgba[4 * (y * image.width + x)] < 200;
    EXPECT_GT(dark, 500);
}

TEST_F(Hardening, DeeplyNestedJsonIsRefusedByEveryReader) {
    // 100,000 levels: copying or destroying such a document recurses once per level.
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    Write("deep.json", R"({"id": "d", "note": )" + deep + R"(, "model": {"name": "thesis"}, "sim": {"iterations": 100},
        "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1]}]}})");
    for (const std::string command : {"sweep", "evolve"}) ExpectRefused(command + " " + Path("deep.json") + " --out " + Path("o"), "levels deep at line 1");
    ExpectRefused("compare " + Path("deep.json") + " " + Path("deep.json") + " --out " + Path("o"), "levels deep");
    fs::create_directories(dir_ / "experiments");
    fs::copy_file(Path("deep.json"), dir_ / "experiments" / "deep.json");
    ExpectRefused("reproduce --experiments " + Path("experiments") + " --part thesis --out " + Path("o"), "levels deep");
    // One argument holds at most 128 KiB: 50,000 levels.
    ExpectRefused("evolve " + Ga(1) + " --out " + Path("o") + " --set 'note=" + std::string(50000, '[') + std::string(50000, ']') + "'", "levels deep");
    std::string path;
    for (int k = 0; k < 1000; ++k) path += "a.";
    ExpectRefused("evolve " + Ga(1) + " --out " + Path("o") + " --set " + path + "b=1", "levels deep");
    EXPECT_FALSE(fs::exists(Path("o")));
    // The files a resume reads back: the run's record, its checkpoint, a comparison's contenders.
    ASSERT_EQ(Run("evolve " + Ga(1) + " --out " + Path("a")).exitCode, 0);
    for (const std::string file : {"run.json", "run_1/checkpoint.json"}) {
        const std::string good = Slurp(dir_ / "a" / file);
        Write("a/" + file, R"({"note": )" + deep + "}");
        ExpectRefused("evolve --resume " + Path("a"), "levels deep");
        Write("a/" + file, good);
    }
    fs::create_directories(dir_ / "c");
    Write("c/contenders.json", R"({"files": )" + deep + "}");
    ExpectRefused("compare --resume " + Path("c"), "levels deep");
}

// Every algorithm with each parameter at the ends of its range, at populations around its smallest:
// what the definition's check lets through runs (pagmo neither throws nor reads past its swarm; the
// sanitizer build would see it), and what would not run is refused.
TEST(HardeningOptimizers, EveryDefinitionTheCheckAcceptsRuns) {
    using namespace sim;
    const MeshDef mesh{30, 30};
    const VectorEvaluator bowl = [](const std::vector<std::vector<double>>& xs) {
        std::vector<DesignScore> out;
        for (const auto& x : xs) {
            double d = 0;
            for (double v : x) d += (v - 3) * (v - 3);
            out.push_back({{5 - d, 1 + d}, Status::Ok});
        }
        return out;
    };
    int accepted = 0, refused = 0;
    for (const auto& [algorithm, name] : EnumNames<Algorithm>::table) {
        std::vector<std::pair<std::string, double>> settings{{"", 0}};
        for (const AlgorithmParameter& p : AlgorithmParameters())
            if (p.algorithm == algorithm)
                for (double v : {p.min, p.max}) settings.push_back({p.name, v});
        for (const auto& [parameter, value] : settings)
            for (int population : {1, 2, 3, 4, 5, 7, 8, 12, 16}) {
                OptimizerDef def;
                def.algorithm = algorithm;
                def.population = population;
                def.generations = 2;
                def.objectives = {Objective{ObjectiveKind::Contraction, true}};
                if (IsMultiObjective(algorithm)) def.objectives.push_back(Objective{ObjectiveKind::MaxStretch, false});
                if (!parameter.empty()) def.parameters[parameter] = value;
                def.genome.family = VectorFamily::Sine;
                def.genome.amplitude = {0, 10};
                def.genome.phaseStart = {0, 10};
                const std::string error = OptimizerDefError(def, ModelKind::Shell, mesh);
                if (!error.empty()) {
                    ++refused;
                    continue;
                }
                ++accepted;
                const std::string what = std::string(name) + " population " + std::to_string(population) + " " + parameter + "=" + std::to_string(value);
                EXPECT_NO_THROW(RunOptimizer(def, mesh, 1, bowl, {})) << what;
            }
    }
    EXPECT_GT(accepted, 100);
    EXPECT_GT(refused, 20);
}

TEST_F(Hardening, OptimizerParametersAreCheckedAgainstThePopulation) {
    Write("pso.json", R"({"model": {"name": "thesis"}, "id": "p", "sim": {"iterations": 100}, "optimizer": {"algorithm": "pso", "population": 8, "generations": 1,
        "parameters": {"neighb_param": 1000}, "objectives": ["thesis_fitness"], "genome": {"family": "sine", "amplitude": [0, 5]}}})");
    ExpectRefused("evolve " + Path("pso.json") + " --out " + Path("o"), "pso's ring topology (neighb_type 2) needs neighb_param from 2 to the population (8), got 1000");
    EXPECT_FALSE(fs::exists(Path("o")));
}

// A full disk (here a file-size limit, which fails a write the same way) is exit code 74, one line,
// and never half of a set of files: a command that writes several writes all or none.
TEST_F(Hardening, AFullDiskIsExit74AndLeavesNoHalfOfAnOutput) {
    auto limited = [&](int kilobytes, const std::string& args) {
        return testing_support::RunShell("ulimit -f " + std::to_string(kilobytes) + "; exec " ACTUATOR_BIN " " + args, dir_);
    };
    auto expectFull = [&](const Result& r, std::source_location where = std::source_location::current()) {
        const ::testing::ScopedTrace trace(where.file_name(), static_cast<int>(where.line()), "");
        EXPECT_EQ(r.exitCode, 74) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_THAT(r.err, HasSubstr("could not write the output"));
    };
    // export: the first solid is larger than the limit; nothing, not even the folder, is left.
    expectFull(limited(64, "export --model shell --shape sine --amplitude 1.3 --phase 0.5,pi-0.5 --out " + Path("part")));
    EXPECT_FALSE(fs::exists(Path("part")));
    // render: the two figures (about 130 and 110 kB) fit, the turntable's frames (about 210 kB) do not.
    expectFull(limited(180, "render --model thesis --shape sine --amplitude 4.1 --turntable 2 --out " + Path("pictures")));
    EXPECT_FALSE(fs::exists(Path("pictures")));
    ASSERT_EQ(Run("render --model thesis --shape sine --amplitude 4.1 --turntable 2 --out " + Path("pictures")).exitCode, 0);
    EXPECT_GT(fs::file_size(Path("pictures/turntable/frame_0000.png")), 180u << 10) << "the case no longer tests a set cut in the middle";
    EXPECT_LT(fs::file_size(Path("pictures/inflation.png")), 180u << 10);
    // simulate: both meshes or neither (the thesis OBJs are about 60 kB each).
    expectFull(limited(40, "simulate --model thesis --iterations 10 --save-initial " + Path("a.obj") + " --save-mesh " + Path("b.obj")));
    EXPECT_FALSE(fs::exists(Path("a.obj")));
    EXPECT_FALSE(fs::exists(Path("b.obj")));
    // A run that writes as it goes stops with 74, keeps whole records, and resumes to the end.
    expectFull(limited(24, "evolve " + Ga(2) + " --out " + Path("s")));
    const Result resumed = Run("evolve --resume " + Path("s"));
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    ASSERT_EQ(Run("evolve " + Ga(2) + " --out " + Path("whole")).exitCode, 0);
    EXPECT_EQ(Slurp(dir_ / "s" / "evaluations.csv"), Slurp(dir_ / "whole" / "evaluations.csv"));
    EXPECT_EQ(Slurp(dir_ / "s" / "run_1" / "logbook.csv"), Slurp(dir_ / "whole" / "run_1" / "logbook.csv"));
}

// A resumed run is the run it resumes: reproduce keeps its folder of experiments, its part, --quick
// and --set; compare its files, seeds and budget. Another one given on resume is refused, not mixed in.
TEST_F(Hardening, AResumeContinuesTheRunItResumesAndNoOther) {
    fs::create_directories(dir_ / "mine");
    Write("mine/s.json", R"({"model": {"name": "thesis"}, "id": "s", "sim": {"iterations": 200}, "render": {"figures": false},
        "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1, 2]}]}})");
    ASSERT_EQ(Run("reproduce --experiments " + Path("mine") + " --part thesis --out " + Path("r")).exitCode, 0);
    const std::string report = Slurp(dir_ / "r" / "report.md");
    fs::remove(dir_ / "r" / "report.md");
    // From another folder, without --experiments: the run's own experiments, not the thesis's.
    const Result resumed = testing_support::RunShell(std::string("cd / && ") + ACTUATOR_BIN + " reproduce --resume " + Path("r"), dir_);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_TRUE(fs::exists(dir_ / "r" / "report.md"));
    EXPECT_FALSE(fs::exists(dir_ / "r" / "4.1_amplitude_sweep")) << "the default experiments were started into the run";
    ExpectRefused("reproduce --resume " + Path("r") + " --experiments " + Path("elsewhere"), "--experiments");
    ExpectRefused("reproduce --resume " + Path("r") + " --quick", "--quick 'true' is not what");
    ExpectRefused("reproduce --resume " + Path("r") + " --part both", "--part");
    ExpectRefused("reproduce --resume " + Path("r") + " --set sim.iterations=300", "--set");
    EXPECT_FALSE(fs::exists(dir_ / "elsewhere"));
    // compare: the budget and seeds it was started with.
    Write("c1.json", R"({"model": {"name": "thesis"}, "id": "c1", "sim": {"iterations": 200}, "render": {"figures": false}, "optimizer": {"algorithm": "de", "population": 5,
        "generations": 2, "objectives": ["thesis_fitness"], "genome": {"family": "sine", "amplitude": [0, 5]}}})");
    Write("c2.json", R"({"model": {"name": "thesis"}, "id": "c2", "sim": {"iterations": 200}, "render": {"figures": false}, "optimizer": {"algorithm": "pso", "population": 5,
        "generations": 2, "objectives": ["thesis_fitness"], "genome": {"family": "sine", "amplitude": [0, 5]}}})");
    ASSERT_EQ(Run("compare " + Path("c1.json") + " " + Path("c2.json") + " --seeds 1 --evaluations 10 --out " + Path("c")).exitCode, 0);
    ExpectRefused("compare --resume " + Path("c") + " --evaluations 20", "--evaluations '20' is not what");
    ExpectRefused("compare --resume " + Path("c") + " --seeds 2", "--seeds '2' is not what");
    ExpectRefused("compare --resume " + Path("c") + " " + Path("c2.json") + " " + Path("c1.json"), "the experiment files");
    const Result again = Run("compare --resume " + Path("c") + " --seeds 1");
    EXPECT_EQ(again.exitCode, 0) << again.err;
}

// A record whose checksum is right but whose packed message declares a gigabyte (runs of zero words
// pack 128-fold): refused as damaged before the reader allocates it.
TEST_F(Hardening, AnArchiveRecordCannotUnpackToMoreThanAFewTimesItsFrame) {
    std::string packed;
    packed += '\x80';  // the segment table's word: one segment (count - 1 = 0) of 0x08000000 words (1 GiB)
    packed += '\x08';
    for (int k = 0; k < (1 << 19); ++k) packed += std::string("\x00\xff", 2);  // 2^19 x 256 zero words
    std::string archive = std::string("ACTARCH\x02", 8);
    auto u32 = [](std::uint32_t v) { return std::string{char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; };
    const auto crc = static_cast<std::uint32_t>(crc32(crc32(0, nullptr, 0), reinterpret_cast<const Bytef*>(packed.data()), static_cast<uInt>(packed.size())));
    archive += u32(static_cast<std::uint32_t>(packed.size())) + u32(crc) + packed;
    Write("bomb.capnp", archive);
    const Result r = Run("inspect " + Path("bomb.capnp"));
    EXPECT_THAT(r.err, HasSubstr("record 0 does not decode"));
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    EXPECT_LT(usage.ru_maxrss, 256 << 10) << "KB: the record was unpacked";
}

// A flag takes no value (CLI11 would read --help=1 or --quick=true as the flag), and an evaluation
// option that has nothing to act on is refused: threads on this machine with only servers to run on.
TEST_F(Hardening, FlagsTakeNoValueAndOptionsWithoutEffectAreRefused) {
    for (const std::string command : {"simulate", "render", "sweep", "evolve", "reproduce", "export", "compare", "inspect", "serve", "imgdiff"})
        ExpectRefused(command + " --help=1", "--help takes no value");
    ExpectRefused("reproduce --quick=true --out " + Path("r"), "--quick takes no value");
    ExpectRefused("render --model thesis --shape sine --video=1 --out " + Path("r"), "--video takes no value");
    EXPECT_FALSE(fs::exists(Path("r")));
    ExpectRefused("evolve " + Ga(1) + " --out " + Path("r") + " --threads 2 --workers 127.0.0.1:1", "--threads counts this machine's threads");
    ExpectRefused("simulate --model shell --shape cylinder --stroke-percent 3", "--stroke-percent applies to --load blocked, not --load inflate");
    ExpectRefused("simulate --model shell --shape cylinder --load blocked --force-n 3", "--force-n applies to --load inflate, gas, volume or force, not --load blocked");
    ExpectRefused("simulate --model shell --shape cylinder --torque-n-mm 3", "--torque-n-mm applies to --twist loaded, not --twist free");
    ExpectRefused("simulate --model shell --load force --pressure-kpa 20", "--pressure-kpa applies to --load inflate, gas or blocked, not --load force");
    ExpectRefused("simulate --model shell --volume-ratio 2", "--volume-ratio applies to --load volume");
    ExpectRefused("export --model shell --shape cylinder --pressure-kpa 20 --out " + Path("r"), "nothing is simulated");
    EXPECT_FALSE(fs::exists(Path("r")));
}
