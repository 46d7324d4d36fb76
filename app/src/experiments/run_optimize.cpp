// A pagmo optimizer (the "optimizer" block) for as many independent runs as the experiment asks:
// sim's RunOptimizer around an evaluation callback that records every new design, the run's
// tables, a contact sheet of every generation and a checkpoint after each. Resume replays the run
// from its seed with the archive's results as answers (no design is simulated twice), after
// cutting the archive back to the newest checkpoint: every output then equals an uninterrupted
// run's, and no optimizer state has to be serialised.
#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <map>
#include <optional>
#include <unordered_map>

#include "experiments/checkpoint.h"
#include "formats/csv.h"
#include "formats/table.h"
#include "support/errors.h"
#include "experiments/experiment_runner.h"
#include "formats/files.h"
#include "pictures/plots.h"
#include "support/progress.h"

namespace app {
namespace {

namespace fs = std::filesystem;
// The job a genome vector describes under the experiment's model.
sim::EvalJob JobOfVector(const Experiment& e, const std::vector<double>& x) {
    const sim::VectorDesign d = sim::DesignOfVector(e.optimizer.genome, x, DesignMesh(e));
    sim::EvalJob job = JobOf(e, d.shape);
    if (e.ga.genome.HasFibreGenes()) job.Shell().fibres = sim::FibresOfGenome(d.genome, e.ga.genome, e.shell.fibres);
    return job;
}

// A design as text, fibre genes included: the key under which it is simulated once per run.
std::string DesignKey(const Experiment& e, const sim::EvalJob& job) {
    std::string key = DesignText(job.shape);
    if (e.ga.genome.HasFibreGenes()) key += " | fibres " + sim::GenomeText(sim::GenomeOfDesign(sim::CylinderShape{}, job.Shell().fibres, e.ga.genome));
    return key;
}

// The objectives of a design from its inflation and, when an objective asks for one, its second
// evaluation. A failed stretch test fails the design; an inflation to twice the target may well
// end at a limit point (that is what it measures), and only leaves the margin unknown otherwise.
sim::DesignScore ScoreOf(const Experiment& e, const sim::SimResult& inflated, const sim::SimResult* second) {
    sim::DesignScore s;
    const bool stretchTest = sim::SecondEvaluationOf(e.optimizer.objectives) == sim::SecondEvaluation::StretchTest;
    s.status = inflated.status == sim::Status::Ok && second && stretchTest ? second->status : inflated.status;
    for (const sim::Objective& o : e.optimizer.objectives) s.values.push_back(sim::ObjectiveValue(o.kind, inflated, second));
    return s;
}

// A result without its meshes: what scores need.
sim::SimResult WithoutMeshes(sim::SimResult r) {
    r.initial = {};
    r.final = {};
    r.shell.steps.clear();
    return r;
}

// Evaluates genome vectors through the recorder, each distinct design once per run (with its
// second evaluation when an objective needs one: two evaluations, one id each).
class DesignCache {
public:
    DesignCache(RunContext& c, int run) : c_(c), run_(run), second_(sim::SecondEvaluationOf(c.e.optimizer.objectives)) {}

    void Restore(const std::vector<ArchiveRecord>& records) {
        for (const ArchiveRecord& r : records) {
            if (r.role != Role::Individual || r.run != run_) continue;
            const std::string key = DesignKey(c_.e, r.job);
            if (IsSecond(r.job)) {
                seconds_.emplace(key, WithoutMeshes(r.result));
                continue;
            }
            inflated_.emplace(key, WithoutMeshes(r.result));
            ids_.emplace(key, r.id);
        }
    }
    void SetGeneration(int generation) { generation_ = generation; }

    std::vector<sim::DesignScore> operator()(const std::vector<std::vector<double>>& xs) {
        std::vector<sim::EvalJob> jobs;
        std::vector<EvaluationTag> tags;
        std::vector<std::string> keys, jobKeys;
        for (const auto& x : xs) {
            sim::EvalJob job = JobOfVector(c_.e, x);
            const std::string key = DesignKey(c_.e, job);
            keys.push_back(key);
            // Two vectors that round to one design are simulated once.
            if (inflated_.count(key) || std::find(jobKeys.begin(), jobKeys.end(), key) != jobKeys.end()) continue;
            const std::string label = fmt::format("run {} generation {}", run_, generation_);
            if (second_ != sim::SecondEvaluation::None) {
                sim::EvalJob second = SecondJob(job);
                jobs.push_back(std::move(job));
                jobs.push_back(std::move(second));
                tags.push_back({Role::Individual, run_, generation_, label});
                tags.push_back({Role::Individual, run_, generation_,
                                label + (second_ == sim::SecondEvaluation::StretchTest ? " stretch test" : " to twice the pressure")});
                jobKeys.insert(jobKeys.end(), {key, key});
                continue;
            }
            jobs.push_back(std::move(job));
            tags.push_back({Role::Individual, run_, generation_, label});
            jobKeys.push_back(key);
        }
        c_.recorder.Evaluate(jobs, tags, [&](std::uint64_t id, size_t k, sim::SimResult&& r) {
            if (IsSecond(jobs[k])) {
                seconds_.emplace(jobKeys[k], WithoutMeshes(std::move(r)));
                return;
            }
            inflated_.emplace(jobKeys[k], WithoutMeshes(std::move(r)));
            ids_.emplace(jobKeys[k], id);
        });
        std::vector<sim::DesignScore> out;
        for (const auto& key : keys)
            out.push_back(ScoreOf(c_.e, inflated_.at(key), second_ != sim::SecondEvaluation::None ? &seconds_.at(key) : nullptr));
        return out;
    }

    // The design's inflation's evaluation id.
    std::uint64_t IdOf(const std::vector<double>& x) const { return ids_.at(DesignKey(c_.e, JobOfVector(c_.e, x))); }

private:
    // The stretch test (thesis model), or the inflation to twice the target in as many steps again.
    sim::EvalJob SecondJob(sim::EvalJob job) const {
        if (second_ == sim::SecondEvaluation::StretchTest) job.Thesis().params.load = sim::Load::Stretch;
        else {
            job.Shell().load.pressureKpa *= 2;
            job.Shell().load.steps *= 2;
        }
        return job;
    }
    bool IsSecond(const sim::EvalJob& job) const {
        if (second_ == sim::SecondEvaluation::StretchTest) return job.model == sim::ModelKind::Thesis && job.Thesis().params.load == sim::Load::Stretch;
        return second_ == sim::SecondEvaluation::TwiceThePressure && job.Shell().load.pressureKpa != c_.e.shell.load.pressureKpa;
    }

    RunContext& c_;
    int run_;
    sim::SecondEvaluation second_;
    int generation_ = 0;
    std::unordered_map<std::string, sim::SimResult> inflated_, seconds_;
    std::unordered_map<std::string, std::uint64_t> ids_;
};

std::vector<std::string> ObjectiveColumns(const Experiment& e) {
    std::vector<std::string> columns;
    for (const sim::Objective& o : e.optimizer.objectives) {
        std::string unit = sim::ObjectiveUnit(o.kind);
        for (char& ch : unit)
            if (ch == ',' || ch == ' ' || ch == '/') ch = '_';
        std::string name = unit;
        name.erase(std::unique(name.begin(), name.end(), [](char a, char b) { return a == '_' && b == '_'; }), name.end());
        if (name.back() == '%') name = name.substr(0, name.size() - 1) + "percent";
        columns.push_back(name);
    }
    return columns;
}

std::string LogbookText(const sim::OptimizerRun& run) {
    Table table(std::vector<std::string>
        {"generation", "evaluations", "best", "worst", "mean", "stddev", "q1", "median", "q3", "best_so_far", "invalid", "hypervolume", "front_size", "stopped_by"});
    for (size_t k = 0; k < run.logbook.size(); ++k) {
        const auto& r = run.logbook[k];
        table.AddRow({std::to_string(r.generation), std::to_string(r.evaluations), CsvNumber(r.best), CsvNumber(r.worst), CsvNumber(r.mean),
                       CsvNumber(r.stddev), CsvNumber(r.q1), CsvNumber(r.median), CsvNumber(r.q3), CsvNumber(r.bestSoFar), std::to_string(r.invalid), CsvNumber(r.hypervolume), std::to_string(r.frontSize),
                       k + 1 == run.logbook.size() ? run.stopReason : ""});
    }
    return table.Csv();
}

// The hall of fame (one objective) or the Pareto front (several): evaluation id, objectives, genes.
std::string DesignsText(const Experiment& e, const sim::OptimizerRun& run, const std::vector<size_t>& designs, const DesignCache& cache,
                        const char* rankName) {
    std::vector<std::string> header{rankName, "evaluation", "generation", "status"};
    for (const auto& column : ObjectiveColumns(e)) header.push_back(column);
    header.push_back("design");
    for (const auto& name : sim::VectorGeneNames(e.optimizer.genome, DesignMesh(e))) header.push_back("gene_" + name);
    Table table(header);
    for (size_t k = 0; k < designs.size(); ++k) {
        const sim::EvaluatedDesign& d = run.evaluated[designs[k]];
        std::vector<std::string> row{std::to_string(k + 1), std::to_string(cache.IdOf(d.x)), std::to_string(d.generation), sim::Name(d.score.status)};
        for (double v : d.score.values) row.push_back(CsvNumber(v));
        row.push_back(DesignKey(e, JobOfVector(e, d.x)));
        for (double g : d.x) row.push_back(CsvNumber(g));
        table.AddRow(row);
    }
    return table.Csv();
}


bool Multi(const Experiment& e) { return e.optimizer.objectives.size() > 1; }

struct RunState {
    sim::OptimizerRun run;
    OptimizerCheckpoint checkpoint;
    std::unique_ptr<DesignCache> cache;
};

// The objectives' values under a design's picture, "/"-separated, or its status.
std::string Caption(const sim::DesignScore& s) {
    if (s.status != sim::Status::Ok) return sim::Name(s.status);
    std::string text;
    for (double v : s.values) text += (text.empty() ? "" : " / ") + fmt::format("{:.3g}", v);
    return text;
}

}  // namespace

void RunOptimization(RunContext& c) {
    const Experiment& e = c.e;
    const sim::OptimizerDef& def = e.optimizer;
    auto runDir = [&](int r) { return RunFolder(c, r); };

    // Resume: the newest checkpoint of each run; the archive is cut back to the newest of all.
    const std::vector<std::optional<OptimizerCheckpoint>> saved = ResumeRuns<OptimizerCheckpoint>(
        c, e.runs, [&](const std::string& text, const std::string& path) { return ParseOptimizerCheckpoint(text, path, e); });

    std::vector<RunState> runs;
    std::unique_ptr<render::MeshRenderer> sheetRenderer;
    for (int r = 1; r <= e.runs; ++r) {
        const fs::path dir = runDir(r);
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (!fs::is_directory(dir, ec)) throw UsageError("cannot create folder " + Quote(dir.string()));
        RunState state;
        state.cache = std::make_unique<DesignCache>(c, r);
        DesignCache& cache = *state.cache;
        const std::optional<OptimizerCheckpoint> before = saved[r - 1];
        if (before) cache.Restore(c.recorder.Existing());
        state.checkpoint.seed = before ? before->seed : sim::DeriveSeed(e.seed, static_cast<std::uint64_t>(r - 1));
        const double secondsBefore = before ? before->seconds : 0;
        const auto started = std::chrono::steady_clock::now();
        Progress progress(fmt::format("{} {} run {}/{}", sim::Name(def.algorithm), ExperimentTitle(e), r, e.runs), c.options.progress);

        const sim::VectorEvaluator evaluate = [&](const std::vector<std::vector<double>>& xs) { return cache(xs); };
        const sim::GenerationHook onGeneration = [&](const sim::OptimizerRun& run) {
            const int generation = run.logbook.back().generation;
            cache.SetGeneration(generation + 1);
            const double seconds = secondsBefore + std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            // Generations the checkpoint already holds are replayed from the archive: their files exist.
            const bool replayed = before && generation <= before->generation;
            if (replayed) return !(generation == before->generation && before->stopReason == "stopped");
            if (e.render.figures) {
                fs::create_directories(dir / "sheets", ec);
                std::vector<std::uint64_t> ids;
                std::vector<std::string> captions;
                std::map<std::vector<double>, size_t> index;
                for (size_t k = 0; k < run.evaluated.size(); ++k) index.emplace(run.evaluated[k].x, k);
                for (const auto& x : run.population) {
                    ids.push_back(cache.IdOf(x));
                    captions.push_back(Caption(run.evaluated[index.at(x)].score));
                }
                const std::vector<ArchiveRecord> records = c.recorder.ReadBack(ids);
                std::vector<SheetEntry> entries;
                for (size_t k = 0; k < records.size(); ++k) entries.push_back({&records[k].result, captions[k]});
                WriteContactSheet(dir / SheetName(generation), fmt::format("{}  -  {} run {}, generation {}", ExperimentTitle(e), sim::Name(def.algorithm), r, generation),
                                  entries, JobOf(e, sim::CylinderShape{}), sheetRenderer);
            }
            WriteFileAtomically((dir / "logbook.csv").string(), LogbookText(run));
            if (Multi(e)) WriteFileAtomically((dir / "pareto_front.csv").string(), DesignsText(e, run, run.front, cache, "front"));
            else WriteFileAtomically((dir / "halloffame.csv").string(), DesignsText(e, run, run.hallOfFame, cache, "rank"));
            // Wall time is kept only when it can stop the run: otherwise checkpoints stay reproducible.
            OptimizerCheckpoint checkpoint{state.checkpoint.seed, generation, c.recorder.Count(), "", def.stop.seconds > 0 ? seconds : 0.0};
            const bool timeLeft = !(def.stop.seconds > 0 && seconds >= def.stop.seconds);
            // Last: a checkpoint always describes files that are already complete.
            WriteFileAtomically((dir / "checkpoint.json").string(), FormatOptimizerCheckpoint(checkpoint, e));
            state.checkpoint = checkpoint;
            const auto& row = run.logbook.back();
            // Progress by evaluations when an evaluation budget ends the run first (compare's runs).
            const long long budget = def.stop.evaluations;
            const bool byBudget = budget > 0 && budget < static_cast<long long>(def.generations + 1) * def.population;
            const std::string unit = byBudget ? "evaluations" : "generation";
            progress.Update(byBudget ? std::min(row.evaluations, budget) : generation, byBudget ? budget : def.generations, c.recorder.Simulated(),
                            Multi(e) ? fmt::format("hypervolume {:.4g}, front {}, {}", row.hypervolume, row.frontSize, unit)
                                     : fmt::format("best {:.4f}, {}", row.bestSoFar, unit));
            return timeLeft;
        };
        state.run = sim::RunOptimizer(def, DesignMesh(e), state.checkpoint.seed, evaluate, onGeneration);
        if (state.run.stopReason == "stopped") state.run.stopReason = "seconds";  // the hook stops only for wall time
        WriteFileAtomically((dir / "logbook.csv").string(), LogbookText(state.run));
        // The final checkpoint says why the run ended (a resume then only redraws); a run that had
        // ended before a resume keeps its own.
        if (before && !before->stopReason.empty()) state.checkpoint = *before;
        else {
            state.checkpoint.generation = state.run.logbook.back().generation;
            state.checkpoint.stopReason = state.run.stopReason;
            state.checkpoint.archiveCount = c.recorder.Count();
            WriteFileAtomically((dir / "checkpoint.json").string(), FormatOptimizerCheckpoint(state.checkpoint, e));
        }
        if (state.run.stopReason == "no valid design")
            std::cerr << "run " << r << ": no design of the initial population is valid; the run stops here. The status column of evaluations.csv says why for each.\n";
        runs.push_back(std::move(state));
    }

    // The outcome: the best of all runs (one objective), or of the first objective on the fronts.
    int bestRun = -1;
    size_t bestIndex = 0;
    double bestValue = NAN;
    const bool maximise = def.objectives[0].maximise;
    for (int r = 0; r < e.runs; ++r) {
        const sim::OptimizerRun& run = runs[r].run;
        const auto& candidates = Multi(e) ? run.front : run.hallOfFame;
        double best = NAN;
        size_t index = 0;
        for (size_t k : candidates) {
            const double v = run.evaluated[k].score.values[0];
            if (std::isnan(best) || (maximise ? v > best : v < best)) {
                best = v;
                index = k;
            }
        }
        c.outcome.rows.push_back({fmt::format("run {} best {}", r + 1, sim::Name(def.objectives[0].kind)), best,
                                  r < static_cast<int>(e.thesisResult.runBest.size()) ? e.thesisResult.runBest[r] : NAN});
        c.outcome.details.push_back(fmt::format("run {} (seed {}): {} generations, {} designs evaluated ({} not foreseen, so evaluated alone), stopped by {}{}",
                                                r + 1, runs[r].checkpoint.seed, run.logbook.back().generation, run.evaluated.size(), run.unforeseen, run.stopReason,
                                                Multi(e) ? fmt::format(", front of {} designs, hypervolume {:.4g}", run.front.size(), run.logbook.back().hypervolume)
                                                         : std::string()));
        if (std::isnan(best)) continue;
        if (bestRun < 0 || (maximise ? best > bestValue : best < bestValue)) {
            bestRun = r;
            bestIndex = index;
            bestValue = best;
        }
    }
    if (bestRun >= 0) {
        c.outcome.bestJob = JobOfVector(e, runs[bestRun].run.evaluated[bestIndex].x);
        c.outcome.bestFitness = bestValue;
    }
    if (!e.render.figures) return;

    if (!Multi(e)) {
        std::vector<RunCurve> curves;
        for (int r = 0; r < e.runs; ++r) {
            RunCurve curve{fmt::format("run {}", r + 1), {}, {}};
            for (const auto& row : runs[r].run.logbook) {
                curve.logbook.push_back({row.generation, static_cast<int>(row.evaluations), row.best, row.worst, row.mean, row.stddev, row.invalid,
                                         row.q1, row.median, row.q3});
                curve.bestSoFar.push_back(row.bestSoFar);
            }
            curves.push_back(std::move(curve));
        }
        WritePng((c.dir / "evolution.png").string(), EvolutionImage(PlotContextOf(e), curves), 6);
        c.outcome.figures.push_back("evolution.png");
    } else {
        // The front of the first run, numbered, with every design it saw behind it; its designs'
        // contact sheet under the same numbers; the hypervolume of every run.
        const sim::OptimizerRun& run = runs[0].run;
        std::vector<ParetoPoint> all, front;
        for (const auto& d : run.evaluated)
            if (d.score.status == sim::Status::Ok) all.push_back({d.score.values[0], d.score.values[1]});
        std::vector<std::uint64_t> ids;
        std::vector<std::string> captions;
        for (size_t k = 0; k < run.front.size(); ++k) {
            const auto& d = run.evaluated[run.front[k]];
            front.push_back({d.score.values[0], d.score.values[1]});
            ids.push_back(runs[0].cache->IdOf(d.x));
            captions.push_back(fmt::format("{}:  {}", k + 1, Caption(d.score)));
        }
        WritePng((c.dir / "pareto_front.png").string(), ParetoImage(PlotContextOf(e), all, front), 6);
        c.outcome.figures.push_back("pareto_front.png");
        if (!ids.empty()) {
            const std::vector<ArchiveRecord> records = c.recorder.ReadBack(ids);
            std::vector<SheetEntry> entries;
            for (size_t k = 0; k < records.size(); ++k) entries.push_back({&records[k].result, captions[k]});
            WriteContactSheet(c.dir / "pareto_designs.png", ExperimentTitle(e) + "  -  the Pareto front's designs, by number", entries,
                              JobOf(e, sim::CylinderShape{}), sheetRenderer);
            c.outcome.figures.push_back("pareto_designs.png");
        }
        std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>> curves;
        for (int r = 0; r < e.runs; ++r) {
            std::vector<std::pair<double, double>> points;
            for (const auto& row : runs[r].run.logbook) points.push_back({double(row.generation), row.hypervolume});
            curves.push_back({fmt::format("run {}", r + 1), points});
        }
        WritePng((c.dir / "hypervolume.png").string(), HypervolumeImage(PlotContextOf(e), curves), 6);
        c.outcome.figures.push_back("hypervolume.png");
    }
    for (int r = 0; r < e.runs; ++r) {
        const std::string sheet = "run_" + std::to_string(r + 1) + "/" + SheetName(runs[r].run.logbook.back().generation);
        std::error_code ec;
        if (fs::exists(c.dir / sheet, ec)) c.outcome.figures.push_back(sheet);
    }
    if (bestRun >= 0) {
        const ArchiveRecord record = c.recorder.ReadBack({runs[bestRun].cache->IdOf(runs[bestRun].run.evaluated[bestIndex].x)}).at(0);
        std::string title = fmt::format("best {} of {} run {}: {}", sim::Name(def.objectives[0].kind), sim::Name(def.algorithm), bestRun + 1,
                                        def.genome.family == sim::VectorFamily::FreeXY ? std::string("free-xy offsets") : ShapeTitle(record.job.shape));
        const std::string fibres = record.job.model == sim::ModelKind::Thesis ? "" : FibreTitle(record.job.Shell().fibres);
        if (!fibres.empty()) title += ",  " + fibres;
        WriteBestFigures(c, c.dir, record.job, record.result, title, e.render.turntable == TurntablePlan::None ? 0 : e.render.turntableFrames, true);
    }
}

}  // namespace app
