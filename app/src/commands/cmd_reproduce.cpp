// `actuator reproduce`: every experiment file of a folder (the thesis's chapters 4 to 6) into
// DIR/<id>/, then DIR/report.md with our numbers beside the thesis's.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "commands/registry.h"
#include "experiments/experiment_library.h"
#include "experiments/experiment_runner.h"
#include "formats/files.h"
#include "report/optimizer_comparison.h"
#include "report/report.h"
#include "report/shell_chapter.h"
#include "commands/run_options.h"

namespace app {

static int RunReproduce(int argc, char** argv, int first) {
    namespace fs = std::filesystem;
    Cli cli("reproduce", "Runs every experiment file of a folder (by default the thesis's chapters 4 to 6 in assets/experiments/) into DIR/<name>/, "
                         "then part 2: the files of its shell/ subfolder, the thesis's experiments re-run under the shell model, into "
                         "DIR/shell/<name>/, compared with part 1 in DIR/comparison/. Writes DIR/report.md: one section per experiment with its "
                         "figures and our numbers beside the thesis's, and part 2's table, mesh-convergence study and finding.");
    RunCommandOptions o;
    std::string experiments;
    bool quick = false;
    bool thumbnails = false;
    enum class Part { Both, Thesis, Physical } part = Part::Both;
    const std::map<std::string, Part> parts{{"both", Part::Both}, {"thesis", Part::Thesis}, {"physical", Part::Physical}};
    AddRunOptions(cli, o);
    cli.Group("Experiments");
    cli.Text("--experiments", experiments, "folder of experiment files to run, in name order")->type_name("DIR")->default_str("assets/experiments");
    cli.Flag("--quick", quick, "shrink every experiment (3 values per axis, one GA run of 2 generations of 6): a smoke test in seconds");
    cli.Flag("--thumbnails", thumbnails,
             "a small before/after picture of every evaluation, as evolve and sweep make (off: the report shows none, and in a full "
             "run they were 6,000 of its 7,200 pictures and most of its 890 MB)");
    cli.App()
        .add_option("--part", part, "both, thesis (part 1 only) or physical (part 2 only; its comparison needs part 1's results)")
        ->transform(CLI::CheckedTransformer(parts, CLI::ignore_case).description(""))
        ->default_str("both")
        ->group("Experiments");
    cli.App().footer("Examples:\n  actuator reproduce --out thesis/\n  actuator reproduce --out smoke/ --quick\n  actuator reproduce --resume thesis/\n");
    if (!cli.Parse(argc, argv, first)) return 0;
    const std::string dir = ResultsDir(cli, o);
    const FolderMode mode = ResultsMode(cli, o);

    // The thesis's files: the source tree this was built from, else where `cmake --install` put them.
    const std::vector<fs::path> shipped = ExperimentFolders();
    fs::path folder = cli.Given("--experiments") || shipped.empty() ? fs::path(experiments) : shipped.front();
    std::error_code ec;
    // What the reproduction was started with: a resume continues that one (its folder of experiments,
    // its part, --quick and --set) and refuses to mix another into it.
    const fs::path recordPath = fs::path(dir) / "reproduce.json";
    const auto record = RunRecord(recordPath, mode,
                                  {{"experiments", "--experiments", cli.Given("--experiments"), fs::absolute(folder).lexically_normal().string()},
                                   {"part", "--part", cli.Given("--part"), part == Part::Both ? "both" : part == Part::Thesis ? "thesis" : "physical"},
                                   {"quick", "--quick", cli.Given("--quick"), quick},
                                   {"thumbnails", "--thumbnails", cli.Given("--thumbnails"), thumbnails},
                                   {"sets", "--set", !o.sets.empty(), o.sets}});
    try {
        folder = record["experiments"].get<std::string>();
        part = parts.at(record["part"].get<std::string>());
        quick = record["quick"].get<bool>();
        thumbnails = record.value("thumbnails", true);  // a reproduction recorded before the option made them
        o.sets = record["sets"].get<std::vector<std::string>>();
    } catch (const std::exception&) {
        throw UsageError(Quote(recordPath.string()) + " is damaged; start afresh with --overwrite");
    }
    if (!fs::is_directory(folder, ec)) throw UsageError("--experiments: no folder " + Quote(folder.string()));
    // Part 1 from the folder, part 2 from its shell/ subfolder: (file, results folder relative to DIR).
    auto filesIn = [&](const fs::path& from, const std::string& prefix) {
        std::vector<std::pair<fs::path, std::string>> found;
        for (const auto& entry : fs::directory_iterator(from, ec))
            if (entry.path().extension() == ".json") found.push_back({entry.path(), prefix + entry.path().stem().string()});
        std::sort(found.begin(), found.end());
        return found;
    };
    std::vector<std::pair<fs::path, std::string>> files;
    if (part != Part::Physical) files = filesIn(folder, "");
    if (part != Part::Thesis && fs::is_directory(folder / "shell", ec))
        for (auto& file : filesIn(folder / "shell", "shell/")) files.push_back(std::move(file));
    if (files.empty()) throw UsageError("--experiments: no .json files in " + Quote(folder.string()) + (part == Part::Physical ? "/shell" : ""));

    // Read every file first: a bad one is refused before hours of work, not after.
    const auto overrides = Overrides(o);
    std::vector<ReportEntry> entries;
    for (const auto& [file, name] : files) {
        Experiment e = LoadExperiment(file.string(), overrides);
        if (quick) e = QuickVersion(e);
        e.render.thumbnails = e.render.thumbnails && thumbnails;
        if (e.id.empty()) e.id = file.stem().string();
        entries.push_back({e, {}, name});
    }
    const auto evaluator = MakeEvaluator(cli, o);
    ResultsFolder results(dir, mode, "reproduce");
    if (mode != FolderMode::Resume) WriteFileAtomically(recordPath.string(), record.dump(2) + "\n");
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
    // Part 2's comparison with part 1: the thesis model's best designs under the physical model, and
    // the physical model's best meshed twice as finely.
    if (std::any_of(entries.begin(), entries.end(), [](const ReportEntry& e) { return !e.experiment.compare.empty(); }))
        std::cerr << "reproduce: comparing part 2 with part 1\n";
    const Chapter chapter = CompareChapters(entries, dir, *evaluator, quick);
    // Part 3: optimizers side by side on one of the thesis's problems, under the thesis model
    // (optimizers/compare/) and the shell model (optimizers/compare_shell/, fewer seeds: it costs more).
    std::string optimizers;
    std::optional<SearchEvidence> shellSearch;  // the physical-model comparison's best, for part 2's finding
    const std::pair<const char*, ComparisonDef> comparisons[] = {{"compare", ComparisonDef{5, 300, ""}}, {"compare_shell", ComparisonDef{3, 120, ""}}};
    for (const auto& [name, given] : comparisons) {
        const fs::path compareFolder = folder / "optimizers" / name;
        // The shell model's comparison belongs to the physical part: `--part thesis` stays the thesis's.
        if (part == Part::Physical || (part == Part::Thesis && std::string(name) == "compare_shell") || !fs::is_directory(compareFolder, ec)) continue;
        std::vector<Experiment> contenders;
        for (const auto& [file, stem] : filesIn(compareFolder, "")) contenders.push_back(LoadExperiment(file.string(), overrides));
        if (contenders.size() < 2) continue;
        ComparisonDef def = given;
        if (quick) {
            def.seeds = 2;
            def.budget = 24;
            for (auto& contender : contenders) contender = QuickVersion(contender);
        }
        const std::string sub = std::string("optimizers/") + name;
        def.linkPrefix = sub + "/";
        std::cerr << "reproduce: optimizers compared (" << name << ")\n";
        const ComparisonResult compared = CompareOptimizers(contenders, def, fs::path(dir) / sub, *evaluator, &results, results.Mode() == FolderMode::Resume, true);
        optimizers += fmt::format("## Under the {} model\n\n", sim::Name(contenders.front().model)) + compared.markdown + "\n";
        if (contenders.front().model != sim::ModelKind::Thesis) {
            SearchEvidence evidence;
            for (const ContenderResult& c : compared.contenders)
                for (size_t seed = 0; seed < c.finalBest.size(); ++seed) {
                    ++evidence.runs;
                    evidence.evaluations += c.evaluations[seed];
                    if (std::isfinite(c.finalBest[seed]) && !(c.finalBest[seed] <= evidence.bestContractionPercent)) {
                        evidence.bestContractionPercent = c.finalBest[seed];
                        evidence.bestLabel = c.label;
                        evidence.bestSeed = static_cast<int>(seed) + 1;
                    }
                }
            if (std::isfinite(evidence.bestContractionPercent)) shellSearch = evidence;
        }
    }
    if (!optimizers.empty())
        optimizers = "<a id=\"optimizers\"></a>\n\n# Part 3: optimizers compared on 5.2's problem\n\n"
                     "The thesis GA, CMA-ES and DE on one B-spline over the middle with 8 control points (0-8), the same seeds and the same "
                     "evaluation budget each.\n\n" + optimizers;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    WriteFileAtomically((fs::path(dir) / "report.md").string(),
                        ReportMarkdown(entries, quick, seconds, evaluator->Describe(), ChapterMarkdown(chapter, quick, shellSearch), optimizers));
    results.FirstResultDone();
    std::cout << nlohmann::ordered_json{{"report", (fs::path(dir) / "report.md").string()}, {"experiments", entries.size()}, {"seconds", seconds}}.dump()
              << "\n";
    return 0;
}

static const RegisterCommand kReproduceCommand{{"reproduce", "run every thesis experiment and write report.md with figures", 50, RunReproduce}};

}  // namespace app
