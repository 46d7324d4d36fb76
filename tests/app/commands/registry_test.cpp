// Commands register themselves; `actuator --help` lists what is registered and every one of them
// answers --help. Experiment files are found by name from any folder.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "commands/registry.h"

namespace {

using ::testing::HasSubstr;

using Registry = CliTest;

TEST_F(Registry, MainHelpListsEveryRegisteredCommandInItsPlaceAndEachAnswersHelp) {
    const auto& commands = app::Commands();
    ASSERT_GE(commands.size(), 10u) << "the registrations of commands/cmd_*.cpp were dropped at link time";
    const Result main = Run("--help");
    ASSERT_EQ(main.exitCode, 0);
    size_t last = 0;
    for (const app::Command& c : commands) {
        const size_t at = main.out.find("  " + std::string(c.name) + " ");
        ASSERT_NE(at, std::string::npos) << c.name << " is registered but not listed";
        EXPECT_GT(at, last) << c.name << " is listed out of its place";
        last = at;
        EXPECT_THAT(main.out, HasSubstr(c.summary));
        const Result help = Run(std::string(c.name) + " --help");
        EXPECT_EQ(help.exitCode, 0) << c.name;
        EXPECT_THAT(help.out, HasSubstr("actuator " + std::string(c.name))) << c.name;
        EXPECT_EQ(app::FindCommand(c.name), &c);
    }
    EXPECT_EQ(app::FindCommand("simulat"), nullptr);
    const Result unknown = Run("simulat");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_THAT(unknown.err, HasSubstr("unknown command 'simulat'"));
}

TEST_F(Registry, ShippedExperimentsAreFoundByNameFromAnyFolder) {
    // From the test's own folder, which holds no experiment: the name with or without .json.
    const std::string here = "cd '" + dir_.string() + "' &&";
    const Result byName = Run("sweep 4.1_amplitude_sweep --out " + Path("a") + " --set sim.iterations=20 --set render.figures=false --set render.thumbnails=false", here);
    ASSERT_EQ(byName.exitCode, 0) << byName.err;
    EXPECT_THAT(nlohmann::json::parse(byName.out)["experiment"].get<std::string>(), ::testing::StartsWith("4.1 "));
    const Result withJson = Run("sweep 4.1_amplitude_sweep.json --out " + Path("b") + " --set sim.iterations=20 --set render.figures=false --set render.thumbnails=false", here);
    ASSERT_EQ(withJson.exitCode, 0) << withJson.err;
    // A subfolder's file by its name alone; an evolve file through sweep is told apart as before.
    const Result shell = Run("sweep S5.2_bspline_middle --out " + Path("c"), here);
    EXPECT_EQ(shell.exitCode, 2);
    EXPECT_THAT(shell.err, HasSubstr("shell/S5.2_bspline_middle.json describes a genetic algorithm"));
    // A name that is nowhere: the message says where it looked.
    const Result missing = Run("sweep no_such_experiment --out " + Path("d"), here);
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_THAT(missing.err, HasSubstr("no_such_experiment"));
    EXPECT_THAT(missing.err, HasSubstr(dir_.string()));
    EXPECT_THAT(missing.err, HasSubstr("assets/experiments"));
    // A path is a path: not looked up by its name elsewhere.
    const Result path = Run("sweep sub/4.1_amplitude_sweep.json --out " + Path("e"), here);
    EXPECT_EQ(path.exitCode, 2);
    EXPECT_THAT(path.err, HasSubstr("looked for " + (dir_ / "sub" / "4.1_amplitude_sweep.json").string()));
    EXPECT_THAT(path.err, ::testing::Not(HasSubstr("shipped")));
}

}  // namespace
