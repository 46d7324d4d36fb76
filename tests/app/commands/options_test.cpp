// No option is accepted without effect. For simulate, render and export, every option their --help
// lists (the command definitions, not a list kept here) is given, with values derived from its type
// and default, in every mode of the command (model, load, shape, picture kind). Each must either
// change what the command writes (its JSON, less the settings it echoes and its timings, and every
// file) or be refused with exit code 2 and a message naming it. The commands run in this process
// (as `actuator` runs them, stdout captured) so that the thousands of runs take seconds.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "commands/registry.h"
#include "support/errors.h"
#include "process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;

namespace {

struct Option {
    std::string name;
    std::string type;                  // X, N, an enum's a|b|c, a placeholder (FILE, DIR, ...), or "" (a flag)
    std::string fallback;              // the default --help shows
    std::vector<std::string> choices;  // an enum's
};

// The options of `actuator COMMAND --help`, in order.
std::vector<Option> OptionsOf(const std::string& command, const fs::path& scratch) {
    const auto help = testing_support::RunShell(std::string(ACTUATOR_BIN) + " " + command + " --help", scratch);
    std::vector<Option> options;
    const std::regex line(R"(^\s+(?:-\w,)?(--[a-z0-9-]+)(?: (\S+))?)");
    std::istringstream lines(help.out);
    for (std::string text; std::getline(lines, text);) {
        if (text.rfind("Examples:", 0) == 0) break;
        std::smatch m;
        if (!std::regex_search(text, m, line)) continue;
        Option o{m[1], m[2], ""};
        if (const size_t equals = o.type.find('='); equals != std::string::npos) {
            o.fallback = o.type.substr(equals + 1);
            o.type = o.type.substr(0, equals);
        }
        if (o.type.find('|') != std::string::npos) {
            std::stringstream names(o.type);
            for (std::string name; std::getline(names, name, '|');) o.choices.push_back(name);
        }
        if (o.name != "--help") options.push_back(o);
    }
    return options;
}

// What a command wrote: its JSON without the settings it echoes and its timings, and each file's
// bytes (a manifest without its echo of the design).
struct Outcome {
    bool refused = false;
    std::string message;
    std::string written;
};

void Strip(nlohmann::json& j) {
    if (!j.is_object()) return;
    for (const char* echo : {"model", "shape", "design", "from", "elapsed_ms", "simulate_ms", "render_ms", "seconds", "renderer", "files", "out", "image"})
        j.erase(echo);
    for (auto& [key, value] : j.items()) Strip(value);
}

std::string Digest(const fs::path& folder) {
    std::string all;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return all;
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(folder))
        if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
        std::string bytes = testing_support::Slurp(f);
        if (f.filename() == "manifest.json") {
            auto j = nlohmann::json::parse(bytes);
            Strip(j);
            bytes = j.dump();
        }
        all += fs::relative(f, folder).string() + ":" + std::to_string(std::hash<std::string>{}(bytes)) + "\n";
    }
    return all;
}

using Command = int (*)(int, char**, int);

// A command as main() finds it: through the registry.
Command Registered(const char* name) {
    const app::Command* command = app::FindCommand(name);
    if (command == nullptr) throw std::logic_error(std::string("no registered command ") + name);
    return command->run;
}

// Runs `command args` in this process, as main() would, into a fresh `out` folder.
Outcome RunHere(Command command, const std::vector<std::string>& args, const fs::path& out) {
    fs::remove_all(out);
    fs::create_directories(out);  // empty, as export needs it; simulate writes its meshes there
    std::vector<std::string> argv{"actuator", "command"};
    for (const auto& a : args) argv.push_back(a);
    std::vector<char*> pointers;
    for (auto& a : argv) pointers.push_back(a.data());
    std::ostringstream captured;
    auto* saved = std::cout.rdbuf(captured.rdbuf());
    Outcome outcome;
    try {
        command(static_cast<int>(pointers.size()), pointers.data(), 2);
    } catch (const app::UsageError& error) {
        outcome.refused = true;
        outcome.message = error.what();
    }
    std::cout.rdbuf(saved);
    if (!outcome.refused) {
        auto j = nlohmann::json::parse(captured.str(), nullptr, false);
        Strip(j);
        outcome.written = j.dump() + "\n" + Digest(out);
    }
    return outcome;
}

// Values to try for an option, derived from its type and default: the first that the command
// accepts and that changes its output shows the option's effect.
std::vector<std::string> Probes(const Option& o, const std::map<std::string, std::vector<std::string>>& given) {
    if (auto it = given.find(o.name); it != given.end()) return it->second;
    if (o.type.empty()) return {""};  // a flag
    if (!o.choices.empty()) {
        std::vector<std::string> others;
        for (const auto& c : o.choices)
            if (c != o.fallback) others.push_back(c);
        return others;
    }
    double d = 0;
    try {
        d = std::stod(o.fallback);
    } catch (...) {
    }
    auto text = [](double v) {
        std::ostringstream s;
        s.precision(6);
        s << v;
        return s.str();
    };
    if (o.type == "N") {
        const long n = std::lround(d);
        return {std::to_string(n + 1), std::to_string(2 * n + 2), "1", "2", "0"};
    }
    if (o.type == "X") return {text(d == 0 ? 1 : 1.5 * d), text(d == 0 ? 0.5 : 0.5 * d), "1", "0.01", "100", "0"};
    return {};  // a placeholder the test does not know: listed in `given`
}

struct Mode {
    std::string name;
    Command command;
    std::vector<std::string> args;        // beside --out
    std::set<std::string> fixed;          // options that make the mode, not probed in it
};

// Replaces `option`'s value in `args` (or adds the option).
std::vector<std::string> With(std::vector<std::string> args, const Option& option, const std::string& value) {
    for (size_t k = 0; k < args.size(); ++k)
        if (args[k] == option.name) {
            const bool hasValue = k + 1 < args.size() && args[k + 1].rfind("--", 0) != 0;
            args.erase(args.begin() + static_cast<long>(k), args.begin() + static_cast<long>(k + (hasValue ? 2 : 1)));
            break;
        }
    args.push_back(option.name);
    if (!value.empty()) args.push_back(value);
    return args;
}

const std::vector<std::string> kSmallShell{"--ring-vertices", "12", "--rings", "16", "--edge-spacing-mm", "0", "--steps", "1", "--pressure-kpa", "1"};

std::vector<std::string> Joined(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

class OptionsHaveAnEffectOrAreRefused : public ::testing::Test {
protected:
    OptionsHaveAnEffectOrAreRefused() : folder_("options"), dir_(folder_.Path()) {}

    // Every option of `command` in every mode; failures name the option, the value and the mode.
    void Check(const std::string& commandName, const std::vector<Mode>& modes, const std::map<std::string, std::vector<std::string>>& given,
               const std::map<std::string, std::string>& exempt, bool writesFolder,
               const std::map<std::string, std::vector<std::string>>& companions = {}) {
        const std::vector<Option> options = OptionsOf(commandName, dir_);
        ASSERT_GT(options.size(), 10u) << commandName;
        int effects = 0, refusals = 0;
        for (const Mode& mode : modes) {
            const fs::path out = dir_ / "out";
            auto withOut = [&](std::vector<std::string> args) {
                if (writesFolder && std::find(args.begin(), args.end(), "--out") == args.end()) args.insert(args.end(), {"--out", out.string()});
                return args;
            };
            const Outcome plain = RunHere(mode.command, withOut(mode.args), out);
            ASSERT_FALSE(plain.refused) << commandName << " in mode " << mode.name << ": " << plain.message;
            for (const Option& option : options) {
                if (mode.fixed.count(option.name) || exempt.count(option.name) || option.name == "--out") continue;
                // A budget shows only where it binds: with its companions (a tighter budget beside it)
                // the option is compared against the mode with those companions alone.
                Mode m = mode;
                Outcome baseline = plain;
                if (auto c = companions.find(option.name); c != companions.end()) {
                    m.args = Joined(m.args, c->second);
                    baseline = RunHere(m.command, withOut(m.args), out);
                    if (baseline.refused) continue;  // the companions do not apply in this mode: neither does the budget's case
                }
                const std::vector<std::string> probes = Probes(option, given);
                ASSERT_FALSE(probes.empty()) << option.name << " (" << option.type << "): give the test a value for it";
                std::string tried;
                bool shown = false;
                for (const auto& value : probes) {
                    const Outcome o = RunHere(m.command, withOut(With(m.args, option, value)), out);
                    if (o.refused && o.message.find(option.name) != std::string::npos) {
                        ++refusals;
                        shown = true;
                        break;
                    }
                    if (!o.refused && o.written != baseline.written) {
                        ++effects;
                        shown = true;
                        break;
                    }
                    tried += "\n    " + option.name + (value.empty() ? "" : " " + value) + ": " + (o.refused ? "refused: " + o.message : "accepted, no effect");
                }
                EXPECT_TRUE(shown) << "actuator " << commandName << ", mode " << mode.name << " (" << ::testing::PrintToString(mode.args) << "):" << tried;
            }
        }
        EXPECT_GT(effects, 20) << commandName;
        EXPECT_GT(refusals, 10) << commandName;
    }

    testing_support::TempFolder folder_;
    fs::path dir_;
};

}  // namespace

TEST_F(OptionsHaveAnEffectOrAreRefused, Simulate) {
    // An archive for --from and a deformed mesh for --mesh.
    ASSERT_EQ(testing_support::RunShell(std::string(ACTUATOR_BIN) + " simulate --model thesis --shape sine --iterations 300 --save-mesh " + (dir_ / "m.obj").string(), dir_).exitCode, 0);
    std::ofstream(dir_ / "s.json") << R"({"model": {"name": "thesis"}, "id": "s", "sim": {"iterations": 200}, "render": {"figures": false, "thumbnails": false},
        "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [2]}]}})";
    ASSERT_EQ(testing_support::RunShell(std::string(ACTUATOR_BIN) + " sweep " + (dir_ / "s.json").string() + " --out " + (dir_ / "a").string(), dir_).exitCode, 0);
    const std::string archive = (dir_ / "a" / "evaluations.capnp").string(), out = (dir_ / "out").string();
    const std::map<std::string, std::vector<std::string>> given{
        {"--phase", {"0.3,2"}},
        {"--control-points", {"2,1,2,1,2"}},
        {"--offsets", {"0 0"}},
        {"--mesh", {(dir_ / "m.obj").string()}},
        {"--amplitude", {"2.5", "1.5"}},
        {"--from", {archive}},
        {"--index", {"0"}},
        {"--save-mesh", {out + "/final.obj"}},
        {"--save-initial", {out + "/initial.obj"}},
        {"--save-vtu", {out + "/wall.vtu"}},
        {"--save-pvd", {out + "/steps"}},
        {"--load", {"inflate", "stretch", "none", "gas", "volume", "force", "blocked"}},
        // Not the probe's 1 kPa: 0.5 N then stretches the tube 16-fold, thin enough for its walls to
        // touch in thousands of pairs, and Newton spends its budget (27 s) before not-converged.
        {"--mu-kpa", {"10"}},
    };
    // The output folder exists for the OBJ files; the options of the modes are what make them.
    const std::set<std::string> thesisMode{"--iterations", "--model", "--load", "--shape"};
    std::vector<Mode> modes;
    for (const std::string load : {"inflate", "stretch", "none"})
        modes.push_back({"thesis " + load, Registered("simulate"), {"--model", "thesis", "--load", load, "--iterations", "200"}, thesisMode});
    for (const std::string shape : {"sine", "bspline"})
        modes.push_back({"thesis " + shape, Registered("simulate"),
                         {"--model", "thesis", "--shape", shape, "--iterations", "200", shape == "sine" ? "--amplitude" : "--control-points", shape == "sine" ? "2" : "1,2,1,2,1"},
                         {"--model", "--iterations", "--shape"}});
    for (const std::string load : {"inflate", "gas", "volume", "force", "blocked"})
        modes.push_back({"shell " + load, Registered("simulate"),
                         Joined({"--model", "shell", "--load", load},
                                load == "force"    ? std::vector<std::string>{"--ring-vertices", "12", "--rings", "16", "--edge-spacing-mm", "0", "--steps", "1", "--force-n", "0.5"}
                                : load == "volume" ? std::vector<std::string>{"--ring-vertices", "12", "--rings", "16", "--edge-spacing-mm", "0", "--steps", "1"}
                                                   : kSmallShell),
                         {"--model", "--load"}});
    modes.push_back({"membrane braid", Registered("simulate"), Joined({"--model", "membrane", "--fibres", "braid"}, kSmallShell), {"--model"}});
    modes.push_back({"from an archive", Registered("simulate"), {"--from", archive, "--index", "0"}, {"--from", "--index"}});
    // Newton's bisections of a failed load step: they bind when a step fails, here for want of iterations.
    Check("simulate", modes, given, {}, false, {{"--max-bisections", {"--max-iterations", "1"}}});
}

TEST_F(OptionsHaveAnEffectOrAreRefused, RenderAndExport) {
    ASSERT_EQ(testing_support::RunShell(std::string(ACTUATOR_BIN) + " simulate --model thesis --shape sine --iterations 300 --save-mesh " + (dir_ / "m.obj").string(), dir_).exitCode, 0);
    std::ofstream(dir_ / "s.json") << R"({"model": {"name": "thesis"}, "id": "s", "sim": {"iterations": 200}, "render": {"figures": false, "thumbnails": false},
        "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]}, "axes": [{"parameter": "amplitude", "values": [1.3]}]}})";
    ASSERT_EQ(testing_support::RunShell(std::string(ACTUATOR_BIN) + " sweep " + (dir_ / "s.json").string() + " --out " + (dir_ / "a").string(), dir_).exitCode, 0);
    const std::string archive = (dir_ / "a" / "evaluations.capnp").string();
    std::map<std::string, std::vector<std::string>> given{
        {"--phase", {"0.3,2"}},
        {"--control-points", {"2,1,2,1,2"}},
        {"--offsets", {"0 0"}},
        {"--mesh", {(dir_ / "m.obj").string()}},
        {"--amplitude", {"1.5", "1.2"}},
        {"--from", {archive}},
        {"--index", {"0"}},
        {"--load", {"inflate", "stretch", "none", "gas", "volume", "force", "blocked"}},
        {"--size", {"80x64"}},
        {"--turntable", {"2"}},
        {"--timelapse", {"2", "3"}},
        {"--solid", {"cutaway", "mold"}},
        {"--printer-mm", {"100x100x100"}},
    };
    // --gl-backend chooses the renderer, not the picture: both backends draw the same (Visual tests).
    const std::map<std::string, std::string> exempt{{"--gl-backend", "the same picture from either backend"}};
    const std::vector<std::string> small{"--size", "64x64", "--supersample", "1"};
    const std::vector<std::string> sine{"--shape", "sine", "--amplitude", "1.3", "--phase", "0.5,pi-0.5"};
    std::vector<Mode> render{
        {"thesis", Registered("render"), Joined(Joined(sine, small), {"--model", "thesis", "--iterations", "200"}), {"--shape", "--model", "--iterations", "--solid"}},
        {"shell", Registered("render"), Joined(Joined(Joined(sine, small), {"--model", "shell"}), kSmallShell), {"--shape", "--model", "--solid"}},
        {"solid cutaway", Registered("render"), Joined(Joined(sine, small), {"--model", "thesis", "--solid", "cutaway", "--sampling", "1"}), {"--shape", "--model", "--solid"}},
        {"solid mold", Registered("render"), Joined(Joined(sine, small), {"--model", "thesis", "--solid", "mold", "--sampling", "1"}), {"--shape", "--model", "--solid"}},
        {"from an archive", Registered("render"), Joined({"--from", archive, "--index", "0"}, small), {"--from", "--index", "--solid"}},
    };
    Check("render", render, given, exempt, true, {{"--max-bisections", {"--max-iterations", "1"}}, {"--port-mm", {"--fittings"}}});
    given.erase("--solid");
    std::vector<Mode> exports{
        {"thesis", Registered("export"), Joined(sine, {"--model", "thesis", "--sampling", "1"}), {"--shape", "--model"}},
        {"shell", Registered("export"), Joined(sine, {"--model", "shell", "--sampling", "1", "--ring-vertices", "16", "--rings", "24"}), {"--shape", "--model"}},
        {"from an archive", Registered("export"), {"--from", archive, "--index", "0", "--sampling", "1"}, {"--from", "--index"}},
    };
    Check("export", exports, given, {}, true, {{"--port-mm", {"--fittings"}}});
}

// A stored membrane design re-simulated with a preset given: the preset replaces the stored
// silicone (its fields given over it), never silently ignored; export takes the stored one.
TEST_F(OptionsHaveAnEffectOrAreRefused, MaterialOverAStoredDesign) {
    std::ofstream(dir_ / "m.json") << R"({"model": {"name": "membrane", "geometry": {"ring_vertices": 12, "rings": 12}, "load": {"pressure_kpa": 0.4, "steps": 2}}, "id": "m",
        "render": {"figures": false, "thumbnails": false}, "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]}, "axes": [{"parameter": "amplitude", "values": [1.1]}]}})";
    const std::string bin = "cd '" + dir_.string() + "' && " + std::string(ACTUATOR_BIN);
    ASSERT_EQ(testing_support::RunShell(bin + " sweep m.json --out a", dir_).exitCode, 0);
    const auto stored = testing_support::RunShell(bin + " simulate --from a/evaluations.capnp --index 0", dir_);
    const auto given = testing_support::RunShell(bin + " simulate --from a/evaluations.capnp --index 0 --material dragon-skin-30", dir_);
    ASSERT_EQ(stored.exitCode, 0);
    ASSERT_EQ(given.exitCode, 0) << given.err;
    const auto before = nlohmann::json::parse(stored.out), after = nlohmann::json::parse(given.out);
    EXPECT_EQ(before["model"]["material"], "ecoflex-00-30");
    EXPECT_EQ(after["model"]["material"], "dragon-skin-30");
    EXPECT_GT(after["model"]["shear_modulus_kpa"].get<double>(), 5 * before["model"]["shear_modulus_kpa"].get<double>());
    EXPECT_LT(std::abs(after["contraction_percent"].get<double>()), std::abs(before["contraction_percent"].get<double>()));  // stiffer: moves less
    const auto exported = testing_support::RunShell(bin + " export --from a/evaluations.capnp --index 0 --material dragon-skin-30 --sampling 1 --out p", dir_);
    EXPECT_EQ(exported.exitCode, 2);
    EXPECT_NE(exported.err.find("--material does not go with --from"), std::string::npos) << exported.err;
    EXPECT_FALSE(fs::exists(dir_ / "p"));
}
