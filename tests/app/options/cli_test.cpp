// `actuator simulate` as a user runs it: JSON on stdout, OBJ round trips, designs from archives, and
// every kind of bad input refused with one line on stderr, exit code 2 and no file written.
#include <nlohmann/json.hpp>

#include "cli_fixture.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using Cli = CliTest;

TEST_F(Cli, SimulatePrintsOneJsonObjectWithTheResult) {
    const Result r = Run("simulate --model thesis --shape abs-sine --amplitude 4 --phase 0,12.566370614359172");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["status"], "ok");
    EXPECT_NEAR(json["fitness"].get<double>(), 0.964, 0.005);
    EXPECT_NEAR(json["contraction_percent"].get<double>(), 100 * json["fitness"].get<double>() / 30, 1e-9);
    EXPECT_EQ(json["iterations"], 10000);
    EXPECT_GT(json["elapsed_ms"].get<double>(), 0);
    EXPECT_EQ(json["shape"]["name"], "abs-sine");
    EXPECT_EQ(json["shape"]["amplitude"], 4);
    EXPECT_EQ(json["model"]["springs"], 3509);
    EXPECT_EQ(json["model"]["pressure_scale"], 0.005);
}

TEST_F(Cli, PhaseAcceptsMultiplesOfPi) {
    const auto a = nlohmann::json::parse(Run("simulate --model thesis --shape abs-sine --phase 0,4pi --iterations 100").out);
    const auto b = nlohmann::json::parse(Run("simulate --model thesis --shape abs-sine --phase 0,12.566370614359172 --iterations 100").out);
    EXPECT_EQ(a["final_positions_hash"], b["final_positions_hash"]);
}

TEST_F(Cli, EveryShapeRuns) {
    for (const std::string args : {"--shape cylinder", "--shape sine --amplitude 4.1 --phase 0.5,2.6415926535",
                                   "--shape bspline --region middle --control-points \"8,8,0,4,0,0,2\"",
                                   "--shape bspline --region middle --control-points \"4,6,2,5;2,3,7,4,6;5,5,1,2;3,3,3,3\"",
                                   "--shape sine --amplitude 4.1 --phase 0.5,2.6415926535 --load stretch"}) {
        const Result r = Run("simulate --model thesis " + args + " --iterations 300");
        ASSERT_EQ(r.exitCode, 0) << args << ": " << r.err;
        EXPECT_EQ(nlohmann::json::parse(r.out)["status"], "ok") << args;
    }
    std::string offsets;
    for (int i = 0; i < 900; ++i) offsets += "0.1 -0.05\n";
    Write("offsets.txt", offsets);
    const Result r = Run("simulate --model thesis --shape free-xy --offsets " + Path("offsets.txt") + " --iterations 300");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["shape"]["name"], "free-xy");
    EXPECT_EQ(json["shape"]["dx"].size(), 900u);
    // A genome as evaluations.csv writes it (dx0,dy0,dx1,...) is accepted as it is, in a file or inline.
    std::string genome;
    for (int i = 0; i < 900; ++i) genome += std::string(i ? "," : "") + "0.1,-0.05";
    Write("genome.txt", genome);
    const auto fromGenome = nlohmann::json::parse(Run("simulate --model thesis --shape free-xy --offsets " + Path("genome.txt") + " --iterations 300").out);
    EXPECT_EQ(fromGenome["final_positions_hash"], json["final_positions_hash"]);
}

TEST_F(Cli, SavedMeshesRoundTripExactly) {
    const Result first = Run("simulate --model thesis --shape sine --amplitude 4.1 --iterations 800 --save-initial " + Path("initial.obj") + " --save-mesh " +
                             Path("final.obj"));
    ASSERT_EQ(first.exitCode, 0) << first.err;
    const auto a = nlohmann::json::parse(first.out);

    // The initial mesh read back evolves to the very same bits.
    const auto b = nlohmann::json::parse(Run("simulate --model thesis --mesh " + Path("initial.obj") + " --iterations 800").out);
    EXPECT_EQ(b["final_positions_hash"], a["final_positions_hash"]);
    EXPECT_EQ(b["fitness"], a["fitness"]);

    // The final mesh read back is the same positions (zero iterations leave it as read).
    const auto c = nlohmann::json::parse(Run("simulate --model thesis --mesh " + Path("final.obj") + " --iterations 0").out);
    EXPECT_EQ(c["final_positions_hash"], a["final_positions_hash"]);

    // And it is a real OBJ: 900 vertices and the model's triangles, wound outward.
    const std::string obj = Slurp(Path("final.obj"));
    int vertexLines = 0, faceLines = 0;
    std::istringstream lines(obj);
    for (std::string line; std::getline(lines, line);) {
        vertexLines += line.rfind("v ", 0) == 0;
        faceLines += line.rfind("f ", 0) == 0;
    }
    EXPECT_EQ(vertexLines, 900);
    EXPECT_EQ(faceLines, 2 * (900 - 31));
    EXPECT_THAT(obj, HasSubstr("\nf 1 32 2\n"));
}

// A saved mesh is a result: the same command again is refused (exit 2) and leaves it as it was;
// --overwrite replaces it.
TEST_F(Cli, SavedMeshesAreWrittenOverOnlyWhenAsked) {
    const std::string save = "simulate --model thesis --shape sine --iterations 300 --save-initial " + Path("initial.obj") + " --save-mesh " + Path("final.obj");
    ASSERT_EQ(Run(save + " --amplitude 4.1").exitCode, 0);
    const std::string initial = Slurp(Path("initial.obj")), final = Slurp(Path("final.obj"));
    for (const std::string other : {std::string(" --amplitude 2"), " --amplitude 2 --save-vtu " + Path("wall.vtu")}) {
        const Result again = Run(save + other);
        EXPECT_EQ(again.exitCode, 2) << other;
        EXPECT_THAT(again.err, HasSubstr("already exists"));
        EXPECT_THAT(again.err, HasSubstr("--overwrite"));
        EXPECT_EQ(again.out, "");
        EXPECT_EQ(Slurp(Path("initial.obj")), initial);
        EXPECT_EQ(Slurp(Path("final.obj")), final);
        EXPECT_FALSE(std::filesystem::exists(Path("wall.vtu"))) << "nothing of a refused command is written";
    }
    ExpectRefused("simulate --model thesis --iterations 300 --overwrite", "--overwrite");  // nothing to write over
    ExpectRefused("simulate --model membrane --save-pvd " + Path("steps") + " --overwrite", "--overwrite");
    const Result replaced = Run(save + " --amplitude 2 --overwrite");
    ASSERT_EQ(replaced.exitCode, 0) << replaced.err;
    EXPECT_NE(Slurp(Path("initial.obj")), initial);
    EXPECT_NE(Slurp(Path("final.obj")), final);
}

TEST_F(Cli, BadInputIsRefusedWithOneLineAndExitCode2) {
    ExpectRefused("simulate --model thesis --shape banana", "banana");
    ExpectRefused("simulate --model thesis --shape bspline --control-points 1,2,3", "at least 4");
    ExpectRefused("simulate --model thesis --shape bspline --control-points \"1,2,3,4;1,2\"", "spline 2");
    ExpectRefused("simulate --model thesis --shape sine --amplitude abc", "--amplitude");
    ExpectRefused("simulate --model thesis --shape sine --amplitude nan", "--amplitude");
    ExpectRefused("simulate --model thesis --shape sine --amplitude inf", "--amplitude");
    ExpectRefused("simulate --model thesis --shape sine --phase 1", "--phase");
    ExpectRefused("simulate --model thesis --iterations -5", "--iterations");
    ExpectRefused("simulate --model thesis --iterations 1e3", "--iterations");
    ExpectRefused("simulate --model thesis --mesh " + Path("missing.obj"), "missing.obj");
    ExpectRefused("simulate --model thesis --shape cylinder --amplitude 3", "does not apply");
    ExpectRefused("simulate --model thesis --bogus 1", "--bogus");
    ExpectRefused("simulate --model thesis --amplitude", "--amplitude");
    ExpectRefused("simulate --model thesis --amplitude 1 --amplitude 2", "--amplitude");
    ExpectRefused("simulate --model thesis --turns 4", "--turns");
    ExpectRefused("simulate --model thesis --load squeeze", "choose inflate, stretch or none");
    ExpectRefused("simulate --index 3", "--from");
    ExpectRefused("frobnicate", "frobnicate");

    Write("short.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    ExpectRefused("simulate --model thesis --mesh " + Path("short.obj"), "3 vertices; the model's mesh has 900");
    Write("garbage.obj", std::string("\x7f" "ELF\x02\x01\x01\0\0\0garbage", 18));
    ExpectRefused("simulate --model thesis --mesh " + Path("garbage.obj"), "garbage.obj");
    Write("text.obj", "hello world\n");
    ExpectRefused("simulate --model thesis --mesh " + Path("text.obj"), "text.obj:1");
    Write("nan.obj", "v 0 nan 0\n");
    ExpectRefused("simulate --model thesis --mesh " + Path("nan.obj"), "nan.obj:1");
    Write("offsets.txt", "0.1 0.2\n");
    ExpectRefused("simulate --model thesis --shape free-xy --offsets " + Path("offsets.txt"), "expected 1800");
}

TEST_F(Cli, OutputsFollowTheirExtensionAndNeverReplaceWhatIsNotOurs) {
    ExpectRefused("simulate --model thesis --save-mesh " + Path("out.stl"), "must end in .obj");
    fs::create_symlink(Path("target.obj"), Path("link.obj"));
    ExpectRefused("simulate --model thesis --save-mesh " + Path("link.obj"), "symbolic link");
    EXPECT_FALSE(fs::exists(Path("target.obj")));
    ExpectRefused("simulate --model thesis --save-mesh /dev/null", "not a regular file");
    ASSERT_EQ(Run("simulate --model thesis --iterations 10 --save-initial " + Path("in.obj")).exitCode, 0);
    const std::string before = Slurp(Path("in.obj"));
    ExpectRefused("simulate --model thesis --mesh " + Path("in.obj") + " --save-mesh " + Path("in.obj"), "also an input");
    EXPECT_EQ(Slurp(Path("in.obj")), before);
}

TEST_F(Cli, RefusedRunsWriteNoFile) {
    ExpectRefused("simulate --model thesis --shape sine --amplitude x --save-mesh " + Path("out.obj"), "--amplitude");
    ExpectRefused("simulate --model thesis --save-mesh " + Path("no/such/folder/out.obj"), "does not exist");
    EXPECT_FALSE(fs::exists(Path("out.obj")));
    for (const auto& entry : fs::directory_iterator(dir_)) EXPECT_THAT(entry.path().filename().string(), ::testing::Not(HasSubstr(".tmp")));
}

TEST_F(Cli, OutputThatCannotBeWrittenIsAnError) {
    const Result r = Run("simulate --model thesis --iterations 10 > /dev/full");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_THAT(r.err, HasSubstr("could not write the output"));
}

TEST_F(Cli, HelpExplainsEveryOptionWithItsDefault) {
    const Result main = Run("--help");
    EXPECT_EQ(main.exitCode, 0);
    EXPECT_THAT(main.out, HasSubstr("simulate"));
    const Result version = Run("--version");
    EXPECT_EQ(version.exitCode, 0);
    EXPECT_THAT(version.out, ::testing::StartsWith("actuator "));
    const Result help = Run("simulate --model thesis --help");
    EXPECT_EQ(help.exitCode, 0);
    for (const char* option : {"--shape", "--amplitude", "--phase", "--region", "--control-points", "--offsets", "--mesh", "--resolution",
                               "--turns", "--load", "--iterations", "--precision", "--save-mesh", "--from", "--pressure-scale"})
        EXPECT_THAT(help.out, HasSubstr(option));
    EXPECT_THAT(help.out, HasSubstr("N=10000"));
    EXPECT_THAT(help.out, HasSubstr("=inflate"));
    EXPECT_THAT(help.out, HasSubstr("X=0.005"));
}

TEST_F(Cli, NumericalFailureIsAStatusNotAnError) {
    const Result r = Run("simulate --model thesis --shape sine --amplitude 4.1 --iterations 40000");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_NE(json["status"], "ok");
    EXPECT_TRUE(json["fitness"].is_null());
}
