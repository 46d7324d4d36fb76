// `actuator compare`: optimizers side by side on one problem (optimizer_comparison.h).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "formats/json_out.h"
#include "commands/registry.h"
#include "support/errors.h"
#include "formats/files.h"
#include "formats/json_out.h"
#include "report/optimizer_comparison.h"
#include "commands/run_options.h"

namespace app {

static int RunCompare(int argc, char** argv, int first) {
    namespace fs = std::filesystem;
    Cli cli("compare", "Runs two or more 'evolve' or 'optimizer' experiments on one problem with the same seeds (1 to --seeds) to the same "
                       "evaluation budget, each run into DIR/<id>/seed_<k>/, and draws the best so far against evaluations: the median "
                       "of the seeds as a line, their range shaded (DIR/comparison.png, DIR/comparison.csv, DIR/report.md).");
    RunCommandOptions o;
    std::vector<std::string> files;
    ComparisonDef def;
    cli.App().add_option("experiments", files, "experiment files, one per contender")->type_name("EXPERIMENT.json ...");
    AddRunOptions(cli, o);
    cli.Group("Comparison");
    cli.Integer("--seeds", def.seeds, "runs per contender, seeded 1, 2, ...", 1, 100);
    cli.App()
        .add_option("--evaluations", def.budget, "evaluations per run: each stops at the first generation that reaches them")
        ->check(CLI::Range(1ll, 10'000'000ll))
        ->default_str(std::to_string(def.budget))
        ->group("Comparison");
    cli.App().footer("Examples:\n  actuator compare assets/experiments/optimizers/compare/*.json --out runs/compare\n"
                     "  actuator compare --resume runs/compare\n");
    if (!cli.Parse(argc, argv, first)) return 0;
    const std::string dir = ResultsDir(cli, o);
    const FolderMode mode = ResultsMode(cli, o);
    // What the comparison was started with: a resume continues it, and refuses other files, seeds,
    // budget or --set.
    std::vector<std::string> absolute;
    for (const auto& file : files) absolute.push_back(fs::absolute(file).lexically_normal().string());
    const fs::path saved = fs::path(dir) / "contenders.json";
    const auto record = RunRecord(saved, mode,
                                  {{"files", "the experiment files", !files.empty(), absolute},
                                   {"sets", "--set", !o.sets.empty(), o.sets},
                                   {"seeds", "--seeds", cli.Given("--seeds"), def.seeds},
                                   {"evaluations", "--evaluations", cli.Given("--evaluations"), def.budget}});
    try {
        files = record["files"].get<std::vector<std::string>>();
        o.sets = record["sets"].get<std::vector<std::string>>();
        def.seeds = record["seeds"].get<int>();
        def.budget = record["evaluations"].get<long long>();
    } catch (const Json::exception&) {
        throw UsageError(Quote(saved.string()) + " is damaged; start afresh with --overwrite");
    }
    std::vector<Experiment> contenders;
    for (const auto& file : files) contenders.push_back(LoadExperiment(file, Overrides(o)));
    CheckContenders(contenders);
    const auto evaluator = MakeEvaluator(cli, o);
    ResultsFolder folder(dir, mode, "compare");
    if (mode != FolderMode::Resume) WriteFileAtomically(saved.string(), record.dump(2) + "\n");
    const ComparisonResult result = CompareOptimizers(contenders, def, dir, *evaluator, &folder, mode == FolderMode::Resume, true);
    WriteFileAtomically((fs::path(dir) / "report.md").string(), "# Optimizers compared\n\n" + result.markdown);
    folder.FirstResultDone();
    nlohmann::ordered_json summary{{"report", (fs::path(dir) / "report.md").string()}, {"seconds", result.seconds}};
    for (const auto& c : result.contenders) summary["contenders"].push_back({{"label", c.label}, {"best", c.finalBest}, {"evaluations", c.evaluations}});
    std::cout << summary.dump() << "\n";
    return 0;
}

static const RegisterCommand kCompareCommand{{"compare", "optimizers side by side: same seeds, same budget, best so far against evaluations", 70, RunCompare}};

}  // namespace app
