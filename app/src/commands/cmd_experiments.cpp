// `actuator sweep` and `actuator evolve`: one experiment file into one results folder, on this
// machine's cores or on evaluation servers. The work itself is in experiment_runner.cpp.
#include <filesystem>
#include <iostream>

#include "commands/registry.h"
#include "experiments/experiment_runner.h"
#include "formats/files.h"
#include "report/report.h"
#include "commands/run_options.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// The experiment to run: the file given, or on --resume without one, the folder's own copy.
Experiment ExperimentToRun(const Cli& cli, const std::string& file, const std::string& dir, const RunCommandOptions& o) {
    const auto overrides = Overrides(o);
    if (!file.empty()) return LoadExperiment(file, overrides);
    if (!cli.Given("--resume")) throw UsageError("expected an experiment file: actuator " + cli.Command() + " EXPERIMENT.json --out DIR");
    const fs::path saved = fs::path(dir) / "experiment.json";
    std::error_code ec;
    if (!fs::exists(saved, ec)) throw UsageError("--resume: " + Quote(dir) + " holds no experiment.json; is it a results folder of 'actuator " + cli.Command() + "'?");
    return LoadExperiment(saved.string(), overrides);
}

int RunExperimentCommand(int argc, char** argv, int first, bool evolve) {
    const char* command = evolve ? "evolve" : "sweep";
    Cli cli(command, evolve ? "Runs an experiment's genetic algorithm (thesis chapter 5, DEAP's eaSimple plus elitism; the 'evolve' block) or optimizer "
                              "(pagmo's " + sim::Choices<sim::Algorithm>() + "; the 'optimizer' block): as many independent runs as the file asks, "
                              "each seeded from the experiment's seed. Same seed, same bytes, whatever --threads or --workers."
                            : "Evaluates every point of an experiment's 1-D or 2-D grid of sine shapes, or every shape of an experiment that lists them "
                              "('evaluate'), and draws the fitness landscape.");
    std::string file;
    RunCommandOptions o;
    cli.App().add_option("experiment", file, "experiment file, or the name of a shipped one (4.1_amplitude_sweep, SF1_fibre_angle_sweep: found in share/actuator/experiments)")->type_name("EXPERIMENT.json");
    AddRunOptions(cli, o);
    bool meshCheck = false;
    cli.Flag("--mesh-check", meshCheck,
             "membrane and shell: evaluate the best design again meshed twice as finely (the clamps keep their length) and report how far its "
             "contraction moved against the 5 % rule (summary.json's mesh_check, a line of the report)");
    cli.App().footer(evolve ? "Writes, per run, DIR/run_K/{logbook.csv, best_per_generation.csv, halloffame.csv, checkpoint.json} and\n"
                              "DIR/run_K/sheets/generation_NNN.png after every generation; then DIR/evolution.png, DIR/best_inflation.png,\n"
                              "DIR/best_stretch.png, DIR/report.md and DIR/summary.json. Every evaluation is in DIR/evaluations.capnp, DIR/evaluations.csv\n"
                              "and DIR/thumbnails/ under one id. An interrupted run continues with --resume and ends as if never stopped.\n"
                              "An optimizer with several objectives also writes DIR/run_K/pareto_front.csv, DIR/pareto_front.png (numbered front designs),\n"
                              "DIR/pareto_designs.png (their contact sheet) and DIR/hypervolume.png.\n\n"
                              "Examples:\n  actuator evolve assets/experiments/5.2_bspline_middle.json --out runs/5.2\n"
                              "  actuator evolve --resume runs/5.2\n"
                              "  actuator evolve assets/experiments/optimizers/O5.2_cmaes_shell.json --out runs/cmaes\n"
                              "  actuator evolve assets/experiments/5.2_bspline_middle.json --out runs/quick --set evolve.generations=3 --set seed=7\n"
                            : "Writes DIR/results.csv (one row per grid point or shape), DIR/landscape.png, DIR/contact_sheet.png,\n"
                              "DIR/best_inflation.png, DIR/best_stretch.png, DIR/report.md, DIR/summary.json, and every evaluation in DIR/evaluations.capnp,\n"
                              "DIR/evaluations.csv and DIR/thumbnails/ under one id. An interrupted sweep continues with --resume.\n\n"
                              "Examples:\n  actuator sweep assets/experiments/4.1_amplitude_sweep.json --out runs/4.1\n"
                              "  actuator sweep assets/experiments/4.1_amplitude_sweep.json --out runs/4.1b --set sim.iterations=20000\n");
    if (!cli.Parse(argc, argv, first)) return 0;
    const std::string dir = ResultsDir(cli, o);
    const Experiment e = ExperimentToRun(cli, file, dir, o);
    const bool searches = e.kind == ExperimentKind::Evolve || e.kind == ExperimentKind::Optimize;
    if (evolve && !searches) throw UsageError(e.path + " describes no genetic algorithm or optimizer: run it with 'actuator sweep'");
    if (!evolve && searches) throw UsageError(e.path + " describes a genetic algorithm or optimizer: run it with 'actuator evolve'");
    if (meshCheck && !sim::ModelOf(e.model).physical)
        throw UsageError("--mesh-check: " + e.path + " is under the thesis model, whose 30 x 30 helix is part of its definition; the check is for membrane and shell");
    const auto evaluator = MakeEvaluator(cli, o);
    ResultsFolder folder(dir, ResultsMode(cli, o), command);
    RunOptions options;
    options.evaluator = evaluator.get();
    options.resume = folder.Mode() == FolderMode::Resume;
    options.folder = &folder;
    options.meshCheck = meshCheck;
    ReportEntry entry{e, RunExperiment(e, dir, options), "."};
    WriteFileAtomically((fs::path(dir) / "report.md").string(), ReportMarkdown({entry}, false, entry.outcome.seconds, evaluator->Describe()));
    std::cout << entry.outcome.summaryJson << "\n";
    folder.FirstResultDone();
    return 0;
}

}  // namespace

static int RunSweepCommand(int argc, char** argv, int first) { return RunExperimentCommand(argc, argv, first, false); }
static int RunEvolveCommand(int argc, char** argv, int first) { return RunExperimentCommand(argc, argv, first, true); }

static const RegisterCommand kSweepCommand{{"sweep", "evaluate an experiment's grid of sine shapes or its list of shapes; landscape figure", 30, RunSweepCommand}};
static const RegisterCommand kEvolveCommand{{"evolve", "run an experiment's genetic algorithm; logbooks, checkpoints, figures", 40, RunEvolveCommand}};

}  // namespace app
