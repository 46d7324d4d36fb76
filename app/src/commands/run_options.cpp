#include "commands/run_options.h"

#include "evaluation/remote.h"

#include <algorithm>

namespace app {

void AddRunOptions(Cli& cli, RunCommandOptions& o) {
    cli.Group("Results");
    cli.Text("--out", o.out, "results folder (created if missing); a folder that already holds results needs --resume or --overwrite")->type_name("DIR");
    cli.App()
        .add_option("--resume", o.resume, "continue the run in the results folder (the experiment comes from DIR/experiment.json when no file is given)")
        ->expected(0, 1)
        ->type_name("[DIR]")
        ->default_str("")
        ->group("Results");
    cli.Flag("--overwrite", o.overwrite, "replace the results folder's contents; the old results are removed once the new run has its first result");
    cli.List("--set", o.sets, "override an experiment key, checked like the file: evolve.generations=5, sim.pressure_scale=0.01, seed=7 (repeatable)")
        ->type_name("KEY.PATH=VALUE");
    cli.Group("Evaluation");
    cli.Integer("--threads", o.threads, "evaluation threads on this machine (0: every core); results do not depend on it", 0, 1024)->default_str("0 (every core)");
    cli.Text("--workers", o.workers, "evaluate on these servers (actuator serve): host:port,host:port; add 'local' to use this machine's cores too. Results equal a local run's")
        ->type_name("LIST");
    cli.Number("--worker-timeout", o.workerTimeoutSeconds, "seconds a server may take for one call before its shapes go to the others", 1e-3,
               kMaxWorkerTimeoutSeconds);
}

std::string ResultsDir(const Cli& cli, const RunCommandOptions& o) {
    const bool resumeFolder = cli.Given("--resume") && !o.resume.empty();
    if (cli.Given("--resume") && o.overwrite) throw UsageError("--resume and --overwrite exclude each other: continue the run, or replace it");
    if (resumeFolder && cli.Given("--out") && o.resume != o.out)
        throw UsageError("--resume " + Quote(o.resume) + " and --out " + Quote(o.out) + " name different folders");
    if (resumeFolder) return o.resume;
    if (!cli.Given("--out")) throw UsageError("--out DIR is required (where the results go)");
    return o.out;
}

FolderMode ResultsMode(const Cli& cli, const RunCommandOptions& o) {
    if (cli.Given("--resume")) return FolderMode::Resume;
    return o.overwrite ? FolderMode::Overwrite : FolderMode::Fresh;
}

std::vector<Override> Overrides(const RunCommandOptions& o) {
    std::vector<Override> overrides;
    for (const auto& text : o.sets) overrides.push_back(ParseOverride(text));
    return overrides;
}

std::unique_ptr<Evaluator> MakeEvaluator(const Cli& cli, const RunCommandOptions& o) {
    if (!cli.Given("--workers")) {
        cli.RefuseIfGiven("--worker-timeout", "goes with --workers");
        return MakeLocalEvaluator(o.threads);
    }
    WorkerPoolOptions pool;
    pool.workers = ParseWorkerList(o.workers);
    if (std::find(pool.workers.begin(), pool.workers.end(), "local") == pool.workers.end())
        cli.RefuseIfGiven("--threads", "counts this machine's threads: with --workers it applies when 'local' is one of them");
    pool.localThreads = o.threads;
    pool.timeoutSeconds = o.workerTimeoutSeconds;
    return MakeWorkerPool(pool);
}

}  // namespace app
