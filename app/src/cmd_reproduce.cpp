// `actuator reproduce`: every experiment file of a folder (the thesis's chapters 4 to 6) into
// DIR/<id>/, then DIR/report.md with our numbers beside the thesis's.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "experiment_runner.h"
#include "files.h"
#include "report.h"
#include "run_options.h"

namespace app {

int RunReproduce(int argc, char** argv, int first) {
    namespace fs = std::filesystem;
    Cli cli("reproduce", "Runs every experiment file of a folder (by default the thesis's chapters 4 to 6 in assets/experiments/) into DIR/<name>/ "
                         "and writes DIR/report.md: one section per experiment with its figures and our numbers beside the thesis's.");
    RunCommandOptions o;
    std::string experiments;
    bool quick = false;
    AddRunOptions(cli, o);
    cli.Group("Experiments");
    cli.Text("--experiments", experiments, "folder of experiment files to run, in name order")->type_name("DIR")->default_str("assets/experiments");
    cli.Flag("--quick", quick, "shrink every experiment (3 values per axis, one GA run of 2 generations of 6): a smoke test in seconds");
    cli.App().footer("Examples:\n  actuator reproduce --out thesis/\n  actuator reproduce --out smoke/ --quick\n  actuator reproduce --resume thesis/\n");
    if (!cli.Parse(argc, argv, first)) return 0;
    const std::string dir = ResultsDir(cli, o);

    // The thesis's files: the source tree this was built from, else where `cmake --install` put them.
    fs::path folder = cli.Given("--experiments") ? fs::path(experiments) : fs::path(ACTUATOR_ASSETS_DIR) / "experiments";
    std::error_code ec;
    if (!cli.Given("--experiments") && !fs::is_directory(folder, ec)) folder = fs::path(ACTUATOR_INSTALLED_ASSETS_DIR) / "experiments";
    if (!fs::is_directory(folder, ec)) throw UsageError("--experiments: no folder " + Quote(folder.string()));
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    if (files.empty()) throw UsageError("--experiments: no .json files in " + Quote(folder.string()));

    // Read every file first: a bad one is refused before hours of work, not after.
    const auto overrides = Overrides(o);
    std::vector<ReportEntry> entries;
    for (const auto& file : files) {
        Experiment e = LoadExperiment(file.string(), overrides);
        if (quick) e = QuickVersion(e);
        if (e.id.empty()) e.id = file.stem().string();
        entries.push_back({e, {}, file.stem().string()});
    }
    const auto evaluator = MakeEvaluator(cli, o);
    ResultsFolder results(dir, ResultsMode(cli, o), "reproduce");
    const auto started = std::chrono::steady_clock::now();
    for (size_t k = 0; k < entries.size(); ++k) {
        const fs::path sub = fs::path(dir) / entries[k].folder;
        // On --resume an experiment not yet started begins afresh.
        const bool resume = results.Mode() == FolderMode::Resume && fs::exists(sub / "run.json", ec);
        fs::create_directories(sub, ec);
        if (!fs::is_directory(sub, ec)) throw UsageError("cannot create folder " + Quote(sub.string()));
        std::cerr << "reproduce: " << k + 1 << "/" << entries.size() << " " << ExperimentTitle(entries[k].experiment) << (resume ? " (resumed)" : "") << "\n";
        RunOptions options;
        options.evaluator = evaluator.get();
        options.resume = resume;
        options.folder = &results;
        entries[k].outcome = RunExperiment(entries[k].experiment, sub, options);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    WriteFileAtomically((fs::path(dir) / "report.md").string(), ReportMarkdown(entries, quick, seconds, evaluator->Describe()));
    results.FirstResultDone();
    std::cout << nlohmann::ordered_json{{"report", (fs::path(dir) / "report.md").string()}, {"experiments", entries.size()}, {"seconds", seconds}}.dump()
              << "\n";
    return 0;
}

}  // namespace app
