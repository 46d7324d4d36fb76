// A pagmo optimizer (the experiment's "optimizer" block) behind the search loop: sim's
// RunOptimizer around an evaluation callback. No optimizer state is serialised: a resume replays
// the run from its seed with the archive's results as answers (no design is simulated twice), up to
// its checkpoint, and continues from there.
#include <fmt/format.h>

#include <chrono>
#include <iostream>

#include "experiments/checkpoint.h"
#include "experiments/search_loop.h"
#include "formats/csv.h"
#include "formats/files.h"
#include "formats/table.h"
#include "pictures/plots.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// The job a genome vector describes under the experiment's model.
sim::EvalJob JobOfVector(const Experiment& e, const std::vector<double>& x) {
    const sim::VectorDesign d = sim::DesignOfVector(e.optimizer.genome, x, DesignMesh(e));
    sim::EvalJob job = JobOf(e, d.shape);
    if (e.ga.genome.HasFibreGenes()) job.Shell().fibres = sim::FibresOfGenome(d.genome, e.ga.genome, job.Shell().fibres);
    return job;
}

// A design as text, fibre genes included: the key under which it is simulated once per run.
std::string DesignKey(const Experiment& e, const sim::EvalJob& job) {
    std::string key = DesignText(job.shape);
    if (e.ga.genome.HasFibreGenes()) key += " | fibres " + sim::GenomeText(sim::GenomeOfDesign(sim::CylinderShape{}, job.Shell().fibres, e.ga.genome));
    return key;
}

// [SECTION] Each def's second evaluation, the one its objectives may ask for (a new def adds its
// overloads; ObjectiveError keeps each objective to the model that has its evaluation): the
// thesis's stretch test; the membrane and shell models' inflation to twice the target in as many
// steps again.
void MakeSecond(sim::ThesisDef& def) { def.params.load = sim::Load::Stretch; }
void MakeSecond(sim::ShellDef& def) {
    def.load.pressureKpa *= 2;
    def.load.steps *= 2;
}
bool IsSecondOf(const sim::ThesisDef& job, const sim::ThesisDef&) { return job.params.load == sim::Load::Stretch; }
bool IsSecondOf(const sim::ShellDef& job, const sim::ShellDef& first) { return job.load.pressureKpa != first.load.pressureKpa; }
bool IsSecondOf(const sim::ThesisDef&, const sim::ShellDef&) { return false; }
bool IsSecondOf(const sim::ShellDef&, const sim::ThesisDef&) { return false; }

sim::EvalJob SecondJob(sim::EvalJob job) {
    std::visit([](auto& def) { MakeSecond(def); }, job.def);
    return job;
}
bool IsSecond(const Experiment& e, sim::SecondEvaluation second, const sim::EvalJob& job) {
    return second != sim::SecondEvaluation::None && std::visit([](const auto& def, const auto& first) { return IsSecondOf(def, first); }, job.def, e.def);
}

// The objectives of a design from its inflation and, when an objective asks for one, its second
// evaluation. A failed stretch test fails the design; an inflation to twice the target may well
// end at a limit point (that is what it measures), and only leaves the margin unknown otherwise.
sim::DesignScore ScoreOf(const Experiment& e, const DesignCache::Design& d) {
    const sim::SimResult* second = d.second ? &*d.second : nullptr;
    sim::DesignScore s;
    const bool stretchTest = sim::SecondEvaluationOf(e.optimizer.objectives) == sim::SecondEvaluation::StretchTest;
    s.status = d.result.status == sim::Status::Ok && second && stretchTest ? second->status : d.result.status;
    for (const sim::Objective& o : e.optimizer.objectives) s.values.push_back(sim::ObjectiveValue(o.kind, d.result, second));
    return s;
}

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
        // The optimizers' "evaluations" column counts the run's so far.
        table.AddRow({std::to_string(r.generation), std::to_string(r.evaluationsSoFar), CsvNumber(r.best), CsvNumber(r.worst), CsvNumber(r.mean),
                      CsvNumber(r.stddev), CsvNumber(r.q1), CsvNumber(r.median), CsvNumber(r.q3), CsvNumber(r.bestSoFar), std::to_string(r.invalid),
                      CsvNumber(r.hypervolume), std::to_string(r.frontSize), k + 1 == run.logbook.size() ? run.stopReason : ""});
    }
    return table.Csv();
}

// The objectives' values under a design's picture, "/"-separated, or its status.
std::string Caption(const sim::DesignScore& s) {
    if (s.status != sim::Status::Ok) return sim::Name(s.status);
    std::string text;
    for (double v : s.values) text += (text.empty() ? "" : " / ") + fmt::format("{:.3g}", v);
    return text;
}

bool Multi(const Experiment& e) { return e.optimizer.objectives.size() > 1; }

class PagmoRun final : public SearchRun {
public:
    PagmoRun(RunContext& c, int run)
        : c_(c),
          run_(run),
          second_(sim::SecondEvaluationOf(c.e.optimizer.objectives)),
          cache_(
              c.recorder, run, [&e = c.e](const sim::EvalJob& job) { return DesignKey(e, job); },
              [&e = c.e, second = second_](const sim::EvalJob& job) { return IsSecond(e, second, job); }, c.e.render.figures) {}

    std::uint64_t Resume(const std::string& text, const std::string& path) override {
        before_ = ParseOptimizerCheckpoint(text, path, c_.e);
        return before_->archiveCount;
    }
    bool Ended() const override { return before_ && !before_->stopReason.empty(); }

    void Run(const std::function<void()>& generationDone) override {
        const Experiment& e = c_.e;
        const sim::OptimizerDef& def = e.optimizer;
        seed_ = before_ ? before_->seed : sim::DeriveSeed(e.seed, static_cast<std::uint64_t>(run_ - 1));
        const double secondsBefore = before_ ? before_->seconds : 0;
        seconds_ = def.stop.seconds > 0 ? secondsBefore : 0.0;
        const auto started = std::chrono::steady_clock::now();
        const sim::VectorEvaluator evaluate = [&](const std::vector<std::vector<double>>& xs) {
            std::vector<DesignCache::Request> requests;
            const std::string secondLabel = second_ == sim::SecondEvaluation::StretchTest ? " stretch test" : " to twice the pressure";
            for (const auto& x : xs) {
                sim::EvalJob job = JobOfVector(e, x);
                std::string key = DesignKey(e, job);
                std::optional<sim::EvalJob> second;
                if (second_ != sim::SecondEvaluation::None) second = SecondJob(job);
                requests.push_back({std::move(key), std::move(job), std::move(second), secondLabel});
            }
            std::vector<sim::DesignScore> out;
            for (const DesignCache::Design* d : cache_.Evaluate(requests)) out.push_back(ScoreOf(e, *d));
            return out;
        };
        const sim::GenerationHook onGeneration = [&](const sim::OptimizerRun& run) {
            const int generation = run.logbook.back().generation;
            cache_.SetGeneration(generation + 1);
            // Generations the checkpoint already holds are replayed from the archive: their files
            // exist. A run that had ended replays up to its end only.
            if (before_ && generation <= before_->generation) return !(generation == before_->generation && Ended());
            current_ = &run;
            // Wall time is kept only when it can stop the run: otherwise checkpoints stay reproducible.
            seconds_ = def.stop.seconds > 0 ? secondsBefore + std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() : 0.0;
            generationDone();
            current_ = nullptr;
            return !(def.stop.seconds > 0 && seconds_ >= def.stop.seconds);
        };
        run_state_ = sim::RunOptimizer(def, DesignMesh(e), seed_, evaluate, onGeneration);
        // The hook stops a live run only for wall time; a replayed one where it had ended.
        if (Ended()) run_state_.stopReason = before_->stopReason;
        else if (run_state_.stopReason == "stopped") run_state_.stopReason = "seconds";
        finished_ = true;
        if (!Ended() && run_state_.stopReason == "no valid design")
            std::cerr << "run " << run_ << ": no design of the initial population is valid; the run stops here. The status column of evaluations.csv says why for each.\n";
    }

    const std::vector<sim::LogbookRow>& Logbook() const override { return Current().logbook; }
    std::vector<SheetMember> Population() const override {
        std::vector<SheetMember> members;
        for (const auto& x : Current().population) {
            std::string key = DesignKey(c_.e, JobOfVector(c_.e, x));
            const std::string caption = Caption(ScoreOf(c_.e, cache_.Of(key)));
            members.push_back({std::move(key), caption});
        }
        return members;
    }
    void WriteFiles(const fs::path& dir, std::uint64_t archiveCount) override {
        const sim::OptimizerRun& run = Current();
        WriteFileAtomically((dir / "logbook.csv").string(), LogbookText(run));
        if (Multi(c_.e)) WriteFileAtomically((dir / "pareto_front.csv").string(), DesignsText(run.front, "front"));
        else WriteFileAtomically((dir / "halloffame.csv").string(), DesignsText(run.hallOfFame, "rank"));
        const OptimizerCheckpoint checkpoint{seed_, run.logbook.back().generation, archiveCount, finished_ ? run.stopReason : "", seconds_};
        WriteFileAtomically((dir / "checkpoint.json").string(), FormatOptimizerCheckpoint(checkpoint, c_.e));
    }
    std::optional<RunBest> Best() const override {
        const std::optional<size_t> k = BestIndex();
        if (!k) return std::nullopt;
        const auto& d = run_state_.evaluated[*k];
        sim::EvalJob job = JobOfVector(c_.e, d.x);
        std::string key = DesignKey(c_.e, job);
        return RunBest{d.score.values[0], std::move(key), std::move(job)};
    }
    DesignCache& Cache() override { return cache_; }

    const sim::OptimizerRun& Result() const { return run_state_; }
    std::uint64_t Seed() const { return seed_; }
    const DesignCache::Design& DesignOf(const std::vector<double>& x) const { return cache_.Of(DesignKey(c_.e, JobOfVector(c_.e, x))); }

private:
    const sim::OptimizerRun& Current() const { return current_ ? *current_ : run_state_; }

    // The best of the hall of fame (one objective) or of the front's first objective (several).
    std::optional<size_t> BestIndex() const {
        const bool maximise = c_.e.optimizer.objectives[0].maximise;
        const auto& candidates = Multi(c_.e) ? run_state_.front : run_state_.hallOfFame;
        std::optional<size_t> index;
        for (size_t k : candidates) {
            const double v = run_state_.evaluated[k].score.values[0];
            if (std::isnan(v)) continue;
            if (!index || (maximise ? v > run_state_.evaluated[*index].score.values[0] : v < run_state_.evaluated[*index].score.values[0])) index = k;
        }
        return index;
    }

    // The hall of fame (one objective) or the Pareto front (several): evaluation id, objectives, genes.
    std::string DesignsText(const std::vector<size_t>& designs, const char* rankName) const {
        const Experiment& e = c_.e;
        const sim::OptimizerRun& run = Current();
        std::vector<std::string> header{rankName, "evaluation", "generation", "status"};
        for (const auto& column : ObjectiveColumns(e)) header.push_back(column);
        header.push_back("design");
        for (const auto& name : sim::VectorGeneNames(e.optimizer.genome, DesignMesh(e))) header.push_back("gene_" + name);
        Table table(header);
        for (size_t k = 0; k < designs.size(); ++k) {
            const sim::EvaluatedDesign& d = run.evaluated[designs[k]];
            const std::string key = DesignKey(e, JobOfVector(e, d.x));
            std::vector<std::string> row{std::to_string(k + 1), std::to_string(cache_.Of(key).id), std::to_string(d.generation), sim::Name(d.score.status)};
            for (double v : d.score.values) row.push_back(CsvNumber(v));
            row.push_back(key);
            for (double g : d.x) row.push_back(CsvNumber(g));
            table.AddRow(row);
        }
        return table.Csv();
    }

    RunContext& c_;
    int run_;
    sim::SecondEvaluation second_;
    DesignCache cache_;
    std::optional<OptimizerCheckpoint> before_;
    std::uint64_t seed_ = 0;
    double seconds_ = 0;
    const sim::OptimizerRun* current_ = nullptr;  // during a generation's hook
    sim::OptimizerRun run_state_;
    bool finished_ = false;
};

class PagmoEngine final : public SearchEngine {
public:
    explicit PagmoEngine(RunContext& c) : c_(c), def_(c.e.optimizer) {}

    std::string Name() const override { return sim::Name(def_.algorithm); }
    std::string RunLabel(int run) const override { return fmt::format("{} run {}", sim::Name(def_.algorithm), run); }
    std::unique_ptr<SearchRun> MakeRun(int run) override {
        auto made = std::make_unique<PagmoRun>(c_, run);
        runs_.push_back(made.get());
        return made;
    }
    bool Maximise() const override { return def_.objectives[0].maximise; }
    bool MultiObjective() const override { return Multi(c_.e); }
    bool KeepsItsBest() const override { return false; }
    int Generations() const override { return def_.generations; }
    int Population() const override { return def_.population; }
    long long EvaluationBudget() const override { return def_.stop.evaluations; }

    void Judge() override {
        const Experiment& e = c_.e;
        for (int r = 0; r < e.runs; ++r) {
            const sim::OptimizerRun& run = runs_[r]->Result();
            const std::optional<RunBest> best = runs_[r]->Best();
            c_.outcome.rows.push_back({fmt::format("run {} best {}", r + 1, sim::Name(def_.objectives[0].kind)), best ? best->value : NAN,
                                       r < static_cast<int>(e.thesisResult.runBest.size()) ? e.thesisResult.runBest[r] : NAN});
            c_.outcome.details.push_back(fmt::format("run {} (seed {}): {} generations, {} designs evaluated ({} not foreseen, so evaluated alone), stopped by {}{}",
                                                     r + 1, runs_[r]->Seed(), run.logbook.back().generation, run.evaluated.size(), run.unforeseen, run.stopReason,
                                                     Multi(e) ? fmt::format(", front of {} designs, hypervolume {:.4g}", run.front.size(), run.logbook.back().hypervolume)
                                                              : std::string()));
        }
    }

    void EndFigures(int) override {
        if (!Multi(c_.e)) return;
        const Experiment& e = c_.e;
        // The front of the first run, numbered, with every design it saw behind it; its designs'
        // contact sheet under the same numbers; the hypervolume of every run.
        const sim::OptimizerRun& run = runs_[0]->Result();
        std::vector<ParetoPoint> all, front;
        for (const auto& d : run.evaluated)
            if (d.score.status == sim::Status::Ok) all.push_back({d.score.values[0], d.score.values[1]});
        std::vector<std::uint64_t> ids;
        std::vector<std::string> captions;
        for (size_t k = 0; k < run.front.size(); ++k) {
            const auto& d = run.evaluated[run.front[k]];
            front.push_back({d.score.values[0], d.score.values[1]});
            ids.push_back(runs_[0]->DesignOf(d.x).id);
            captions.push_back(fmt::format("{}:  {}", k + 1, Caption(d.score)));
        }
        WritePng((c_.dir / "pareto_front.png").string(), ParetoImage(PlotContextOf(e), all, front), 6);
        c_.outcome.figures.push_back("pareto_front.png");
        if (!ids.empty()) {
            const std::vector<ArchiveRecord> records = c_.recorder.ReadBack(ids);
            std::vector<SheetEntry> entries;
            for (size_t k = 0; k < records.size(); ++k) entries.push_back({&records[k].result, captions[k]});
            std::unique_ptr<render::MeshRenderer> renderer;
            WriteContactSheet(c_.dir / "pareto_designs.png", ExperimentTitle(e) + "  -  the Pareto front's designs, by number", entries,
                              JobOf(e, sim::CylinderShape{}), renderer);
            c_.outcome.figures.push_back("pareto_designs.png");
        }
        std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>> curves;
        for (int r = 0; r < e.runs; ++r) {
            std::vector<std::pair<double, double>> points;
            for (const auto& row : runs_[r]->Result().logbook) points.push_back({double(row.generation), row.hypervolume});
            curves.push_back({fmt::format("run {}", r + 1), points});
        }
        WritePng((c_.dir / "hypervolume.png").string(), HypervolumeImage(PlotContextOf(e), curves), 6);
        c_.outcome.figures.push_back("hypervolume.png");
    }

    std::string BestTitle(int run, const sim::EvalJob& job) const override {
        return fmt::format("best {} of {} run {}: {}", sim::Name(def_.objectives[0].kind), sim::Name(def_.algorithm), run,
                           def_.genome.family == sim::VectorFamily::FreeXY ? std::string("free-xy offsets") : ShapeTitle(job.shape));
    }

private:
    RunContext& c_;
    const sim::OptimizerDef& def_;
    std::vector<PagmoRun*> runs_;
};

}  // namespace

std::unique_ptr<SearchEngine> MakePagmoEngine(RunContext& c) { return std::make_unique<PagmoEngine>(c); }

}  // namespace app
