// `actuator sweep`, `actuator evolve` and `actuator reproduce`: the thesis's experiments from their
// files, in-process and on all cores. The work itself is in experiment_runner.cpp.
#include <kj/exception.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli_options.h"
#include "commands.h"
#include "experiment_runner.h"
#include "mesh_io.h"
#include "remote.h"
#include "report.h"
#include "sim/batch.h"

namespace app {
namespace {

namespace fs = std::filesystem;

int ParseThreads(const ParsedArgs& args) {
    return args.Has("threads") ? ParseInt(args.Get("threads"), "--threads", 1, 1024) : sim::HardwareThreads();
}

std::vector<OptionSpec> WorkerSpecs() {
    return {
        {"workers", "LIST", "", "evaluate on these servers (actuator serve) instead of this machine: host:port,host:port; "
                                "add 'local' to use this machine's cores too. Results equal a local run's"},
        {"worker-timeout", "S", "300", "seconds a server may take for one batch before its shapes go to the others"},
    };
}

std::vector<OptionSpec> With(std::vector<OptionSpec> specs, const std::vector<OptionSpec>& more) {
    specs.insert(specs.end() - 1, more.begin(), more.end());  // before --help
    return specs;
}

// The servers named by --workers, or none.
std::unique_ptr<WorkerPool> MakeWorkerPool(const ParsedArgs& args, int threads) {
    if (!args.Has("workers")) {
        if (args.Has("worker-timeout")) throw UsageError("--worker-timeout goes with --workers");
        return nullptr;
    }
    WorkerPoolOptions options;
    options.workers = ParseWorkerList(args.Get("workers"));
    options.localThreads = threads;
    if (args.Has("worker-timeout")) {
        options.timeoutSeconds = ParseNumber(args.Get("worker-timeout"), "--worker-timeout");
        if (!(options.timeoutSeconds > 0)) throw UsageError("--worker-timeout: must be positive");
    }
    return std::make_unique<WorkerPool>(options);
}


std::vector<OptionSpec> SweepSpecs() {
    return {
        {"out", "DIR", "", "output folder (created if missing); required"},
        {"threads", "N", "all cores", "evaluation threads; results do not depend on it"},
        {"help", "", "", "show this help"},
    };
}

std::vector<OptionSpec> EvolveSpecs() {
    return {
        {"out", "DIR", "", "output folder (created if missing); required unless --resume"},
        {"resume", "DIR", "", "continue an interrupted evolve in DIR from its checkpoints"},
        {"threads", "N", "all cores", "evaluation threads; results do not depend on it"},
        {"help", "", "", "show this help"},
    };
}

std::vector<OptionSpec> ReproduceSpecs() {
    return {
        {"out", "DIR", "", "output folder (created if missing); required"},
        {"experiments", "DIR", "assets/experiments", "folder of experiment files to run, in name order"},
        {"quick", "", "", "reduced grids and generations: a smoke test of everything in seconds"},
        {"threads", "N", "all cores", "evaluation threads; results do not depend on it"},
        {"help", "", "", "show this help"},
    };
}

}  // namespace

std::string SweepHelp() {
    return "usage: actuator sweep EXPERIMENT.json --out DIR [--threads N]\n\n"
           "Evaluates every point of an experiment's 1-D or 2-D grid of sine shapes (see assets/experiments/),\n"
           "or every shape of an experiment that lists them ('evaluate'), and writes\n"
           "  DIR/results.csv          one row per grid point or shape: parameters, fitness, contraction, status\n"
           "  DIR/landscape.png        the fitness landscape: a line plot (1-D) or a heatmap (2-D), best marked\n"
           "  DIR/contact_sheet.png    every grid point's inflated mesh with its fitness\n"
           "  DIR/best_inflation.png, DIR/best_stretch.png   the best shape before and after\n"
           "  DIR/shape_K.png          (lists) each shape before and after\n"
           "  DIR/summary.json         our numbers beside the thesis's, timings (also printed)\n\nOptions:\n" +
           FormatOptions(With(SweepSpecs(), WorkerSpecs()));
}

std::string EvolveHelp() {
    return "usage: actuator evolve EXPERIMENT.json --out DIR [--threads N]\n"
           "       actuator evolve --resume DIR [--threads N]\n\n"
           "Runs an experiment's genetic algorithm (see assets/experiments/): tournament selection among valid\n"
           "individuals, elitism, the thesis's mutation, optional two-point crossover, as many independent runs\n"
           "as the file asks, each with a seed derived from the experiment's seed. Same seed, same bytes,\n"
           "whatever --threads. Writes, per run, DIR/run_K/{logbook.csv, best_per_generation.csv,\n"
           "halloffame.csv, checkpoint.json} and DIR/run_K/sheets/generation_NNN.png (rewritten or added after\n"
           "every generation), then DIR/evolution.png, DIR/best_inflation.png, DIR/best_stretch.png and\n"
           "DIR/summary.json. An interrupted run continues with --resume DIR and ends as if never stopped.\n\n"
           "Options:\n" + FormatOptions(With(EvolveSpecs(), WorkerSpecs()));
}

std::string ReproduceHelp() {
    return "usage: actuator reproduce --out DIR [--quick] [--threads N]\n\n"
           "Runs every experiment file in assets/experiments/ (the thesis's chapters 4 to 6) into DIR/<id>/ and\n"
           "writes DIR/report.md: one section per experiment with its figures and our numbers beside the\n"
           "thesis's. --quick shrinks every experiment to a smoke test.\n\nOptions:\n" + FormatOptions(With(ReproduceSpecs(), WorkerSpecs()));
}

namespace {
std::vector<OptionSpec> ServeSpecs() {
    return {
        {"listen", "ADDRESS:PORT", "127.0.0.1:7300", "where to listen; a bare port means 127.0.0.1:PORT; port 0 picks a free one"},
        {"threads", "N", "all cores", "evaluation threads per batch"},
        {"help", "", "", "show this help"},
    };
}
}  // namespace

std::string ServeHelp() {
    return "usage: actuator serve [--listen ADDRESS:PORT] [--threads N]\n\n"
           "Runs an evaluation server: Cap'n Proto RPC, interface Evaluator in sim/actuator.capnp (see README).\n"
           "It takes batches of shapes with parameters and returns results and meshes, evaluating on all its\n"
           "cores, until it is killed. Bad or hostile requests get an error reply or a closed connection; the\n"
           "server keeps serving. Use it from sweep, evolve or reproduce with --workers host:port,...\n\nOptions:\n" +
           FormatOptions(ServeSpecs());
}

int RunServe(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, ServeSpecs(), 0);
    if (args.Has("help")) {
        std::cout << ServeHelp();
        return 0;
    }
    ServeOptions options;
    if (args.Has("listen")) options.listen = args.Get("listen");
    const std::string port = options.listen.substr(options.listen.rfind(':') + 1);
    ParseInt(port, "--listen port", 0, 65535);
    options.threads = args.Has("threads") ? ParseInt(args.Get("threads"), "--threads", 1, 1024) : 0;
    try {
        Serve(options);
    } catch (const kj::Exception& error) {
        throw UsageError("--listen " + options.listen + ": " + error.getDescription().cStr());
    }
    return 0;
}

int RunSweep(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, With(SweepSpecs(), WorkerSpecs()), 1);
    if (args.Has("help")) {
        std::cout << SweepHelp();
        return 0;
    }
    if (args.positionals.size() != 1) throw UsageError("expected one experiment file: actuator sweep EXPERIMENT.json --out DIR");
    if (!args.Has("out")) throw UsageError("--out DIR is required");
    const Experiment e = LoadExperiment(args.positionals[0]);
    if (e.kind == ExperimentKind::Evolve) throw UsageError(e.path + " describes a genetic algorithm: run it with 'actuator evolve'");
    const int threads = ParseThreads(args);
    const auto pool = MakeWorkerPool(args, threads);
    std::cout << RunExperiment(e, args.Get("out"), RunOptions{threads, false, true, pool.get()}).summaryJson << "\n";
    return 0;
}

int RunEvolve(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, With(EvolveSpecs(), WorkerSpecs()), 1);
    if (args.Has("help")) {
        std::cout << EvolveHelp();
        return 0;
    }
    const bool resume = args.Has("resume");
    if (resume && (args.Has("out") || !args.positionals.empty()))
        throw UsageError("--resume DIR takes the experiment and output folder from DIR; give no file or --out with it");
    if (!resume && args.positionals.size() != 1) throw UsageError("expected one experiment file: actuator evolve EXPERIMENT.json --out DIR");
    if (!resume && !args.Has("out")) throw UsageError("--out DIR is required");
    const fs::path out = resume ? fs::path(args.Get("resume")) : fs::path(args.Get("out"));
    if (resume && !fs::exists(out / "experiment.json"))
        throw UsageError("--resume: '" + out.string() + "' holds no experiment.json; is it an evolve output folder?");
    const Experiment e = resume ? ParseExperiment(ReadTextFile((out / "experiment.json").string()), (out / "experiment.json").string())
                                : LoadExperiment(args.positionals[0]);
    if (e.kind != ExperimentKind::Evolve) throw UsageError(e.path + " describes no genetic algorithm: run it with 'actuator sweep'");
    const int threads = ParseThreads(args);
    const auto pool = MakeWorkerPool(args, threads);
    std::cout << RunExperiment(e, out, RunOptions{threads, resume, true, pool.get()}).summaryJson << "\n";
    return 0;
}

int RunReproduce(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, With(ReproduceSpecs(), WorkerSpecs()), 0);
    if (args.Has("help")) {
        std::cout << ReproduceHelp();
        return 0;
    }
    if (!args.Has("out")) throw UsageError("--out DIR is required");
    const int threads = ParseThreads(args);
    const bool quick = args.Has("quick");
    fs::path folder = args.Has("experiments") ? fs::path(args.Get("experiments")) : fs::path(ACTUATOR_ASSETS_DIR) / "experiments";
    if (!args.Has("experiments") && !fs::is_directory(folder)) folder = "assets/experiments";  // a moved build tree
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw UsageError("--experiments: no folder '" + folder.string() + "'");
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    if (files.empty()) throw UsageError("--experiments: no .json files in '" + folder.string() + "'");

    // Read every file first: a bad one is refused before hours of work, not after.
    std::vector<ReportEntry> entries;
    for (const auto& file : files) {
        Experiment e = LoadExperiment(file.string());
        if (quick) e = QuickVersion(e);
        if (e.id.empty()) e.id = file.stem().string();
        entries.push_back({e, {}, file.stem().string()});
    }
    const fs::path out = args.Get("out");
    fs::create_directories(out, ec);
    if (!fs::is_directory(out, ec)) throw UsageError("--out: cannot create folder '" + out.string() + "'");
    CheckOutputPath((out / "report.md").string(), "--out");

    const auto pool = MakeWorkerPool(args, threads);
    const auto started = std::chrono::steady_clock::now();
    for (size_t k = 0; k < entries.size(); ++k) {
        std::cerr << "reproduce: " << k + 1 << "/" << entries.size() << " " << ExperimentTitle(entries[k].experiment) << "\n";
        entries[k].outcome = RunExperiment(entries[k].experiment, out / entries[k].folder, RunOptions{threads, false, true, pool.get()});
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    WriteFileAtomically((out / "report.md").string(), ReportMarkdown(entries, quick, seconds, threads));
    std::cout << "{\"report\":\"" << (out / "report.md").string() << "\",\"experiments\":" << entries.size() << ",\"seconds\":" << seconds << "}\n";
    return 0;
}

}  // namespace app
