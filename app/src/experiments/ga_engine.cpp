// The thesis's genetic algorithm (chapter 5) behind the search loop: sim's pure GA steps around an
// evaluation callback, its state checkpointed whole after every generation (a resume continues from
// it), and the thesis's own designs (its tables' genomes) evaluated beside each run's best.
#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <map>

#include "experiments/checkpoint.h"
#include "experiments/search_loop.h"
#include "experiments/thesis_check.h"
#include "formats/files.h"
#include "pictures/plots.h"

namespace app {
namespace {

namespace fs = std::filesystem;

std::string GenomeSummary(const Experiment& e, const sim::Genome& genome) {
    return e.ga.genome.kind == sim::GenomeKind::BSpline ? "[" + sim::GenomeText(genome) + "]" : "of " + std::to_string(genome[0].size()) + " offsets";
}

class GaRun final : public SearchRun {
public:
    GaRun(RunContext& c, int run)
        : c_(c),
          run_(run),
          cache_(
              c.recorder, run, [&e = c.e](const sim::EvalJob& job) { return sim::GenomeText(GenomeOfJob(e, job)); },
              [](const sim::EvalJob&) { return false; }, c.e.render.figures) {}

    std::uint64_t Resume(const std::string& text, const std::string& path) override {
        checkpoint_ = ParseCheckpoint(text, path, c_.e);
        resumed_ = true;
        return checkpoint_.archiveCount;
    }
    bool Ended() const override { return resumed_ && !checkpoint_.state.stopReason.empty(); }

    void Run(const std::function<void()>& generationDone) override {
        const Experiment& e = c_.e;
        const sim::GenomeEvaluator evaluator = [&](const std::vector<const sim::Genome*>& genomes) {
            std::vector<DesignCache::Request> requests;
            for (const sim::Genome* genome : genomes) requests.push_back({sim::GenomeText(*genome), JobOfGenome(e, *genome)});
            std::vector<std::pair<double, sim::Status>> out;
            for (const DesignCache::Design* d : cache_.Evaluate(requests)) out.push_back({d->result.fitness, d->result.status});
            return out;
        };
        sim::GaState& state = checkpoint_.state;
        if (!resumed_) {
            checkpoint_.seed = sim::DeriveSeed(e.seed, static_cast<std::uint64_t>(run_ - 1));
            checkpoint_.experimentHash = ExperimentHash(e);
            checkpoint_.experiment = e.document;
            cache_.SetGeneration(0);
            state = sim::StartEvolution(e.ga, DesignMesh(e), checkpoint_.seed, evaluator);
            generationDone();
        }
        const auto started = std::chrono::steady_clock::now();
        while (state.stopReason.empty()) {
            // The stop criteria, after each generation; wall time counts this session's.
            std::string reason = sim::GaStopReason(e.ga, state);
            if (reason.empty() && e.ga.stop.seconds > 0 &&
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >= e.ga.stop.seconds)
                reason = "seconds";
            if (!reason.empty()) {
                state.stopReason = reason;
                return;
            }
            cache_.SetGeneration(state.generation + 1);
            if (!sim::EvolveOneGeneration(e.ga, DesignMesh(e), state, evaluator)) {
                std::map<std::string, int> statuses;
                for (const sim::Individual& individual : state.population) ++statuses[sim::Name(cache_.Of(sim::GenomeText(individual.genome)).result.status)];
                std::string tally;
                for (const auto& [status, count] : statuses) tally += (tally.empty() ? "" : ", ") + std::to_string(count) + " " + status;
                std::cerr << "run " << run_ << ": every individual of generation " << state.generation << " failed (" << tally
                          << "); the run stops here. The status column of evaluations.csv says why for each.\n";
                state.stopReason = "no valid design";
                return;
            }
            generationDone();
        }
    }

    const std::vector<sim::LogbookRow>& Logbook() const override { return checkpoint_.state.logbook; }
    std::vector<SheetMember> Population() const override {
        std::vector<SheetMember> members;
        for (const sim::Individual& individual : checkpoint_.state.population) {
            const std::string key = sim::GenomeText(individual.genome);
            members.push_back({key, FitnessCaption(cache_.Of(key).result)});
        }
        return members;
    }
    void WriteFiles(const fs::path& dir, std::uint64_t archiveCount) override {
        checkpoint_.archiveCount = archiveCount;
        WriteFileAtomically((dir / "logbook.csv").string(), LogbookCsv(checkpoint_.state));
        WriteFileAtomically((dir / "best_per_generation.csv").string(), BestPerGenerationCsv(checkpoint_.state));
        WriteFileAtomically((dir / "halloffame.csv").string(), HallOfFameCsv(checkpoint_.state));
        WriteFileAtomically((dir / "checkpoint.json").string(), FormatCheckpoint(checkpoint_));
    }
    std::optional<RunBest> Best() const override {
        if (checkpoint_.state.hallOfFame.empty()) return std::nullopt;
        const sim::Individual& best = checkpoint_.state.hallOfFame.front();
        return RunBest{best.fitness, sim::GenomeText(best.genome), JobOfGenome(c_.e, best.genome)};
    }
    DesignCache& Cache() override { return cache_; }

    const RunCheckpoint& Checkpoint() const { return checkpoint_; }

private:
    RunContext& c_;
    int run_;
    DesignCache cache_;
    RunCheckpoint checkpoint_;
    bool resumed_ = false;
};

class GaEngine final : public SearchEngine {
public:
    explicit GaEngine(RunContext& c) : c_(c) {}

    std::string Name() const override { return "evolve"; }
    std::string RunLabel(int run) const override { return fmt::format("run {}", run); }
    std::unique_ptr<SearchRun> MakeRun(int run) override {
        auto made = std::make_unique<GaRun>(c_, run);
        runs_.push_back(made.get());
        return made;
    }
    bool Maximise() const override { return true; }
    bool MultiObjective() const override { return false; }
    bool KeepsItsBest() const override { return true; }
    int Generations() const override { return c_.e.ga.generations; }
    int Population() const override { return c_.e.ga.population; }
    long long EvaluationBudget() const override { return c_.e.ga.stop.evaluations; }

    void Judge() override;
    void EndFigures(int bestRun) override;
    std::string BestTitle(int run, const sim::EvalJob& job) const override {
        return fmt::format("best of run {}: {}", run, c_.e.ga.genome.kind == sim::GenomeKind::BSpline ? ShapeTitle(job.shape) : std::string("free-xy offsets"));
    }

private:
    // The thesis's specimen of a run (1-based), or -1.
    int SpecimenOfRun(int run) const {
        const auto& specimens = c_.e.thesisResult.specimens;
        for (size_t k = 0; k < specimens.size(); ++k)
            if (specimens[k].run == run) return static_cast<int>(k);
        return -1;
    }

    RunContext& c_;
    std::vector<GaRun*> runs_;
    std::vector<sim::SimResult> specimenResults_;
    std::vector<sim::EvalJob> specimenJobs_;
};

void GaEngine::Judge() {
    const Experiment& e = c_.e;
    // The thesis's own designs (its tables' genomes), evaluated here like any other design.
    const auto& specimens = e.thesisResult.specimens;
    specimenResults_.assign(specimens.size(), {});
    {
        std::vector<EvaluationTag> tags;
        for (const auto& specimen : specimens) {
            specimenJobs_.push_back(JobOf(e, specimen.design.shape));
            tags.push_back({Role::ThesisPoint, specimen.run, -1, "thesis specimen: " + specimen.design.label});
        }
        c_.recorder.Evaluate(specimenJobs_, tags, [&](std::uint64_t, size_t k, sim::SimResult&& r) { specimenResults_[k] = std::move(r); });
    }
    auto fitnessOf = [](const sim::SimResult& r) { return r.status == sim::Status::Ok ? r.fitness : NAN; };

    double sumBest = 0, sumThesisHere = 0;
    int thesisHere = 0;
    std::string table;
    for (int r = 0; r < e.runs; ++r) {
        const RunCheckpoint& run = runs_[r]->Checkpoint();
        const sim::GaState& s = run.state;
        const double best = s.hallOfFame.empty() ? NAN : s.hallOfFame.front().fitness;
        const double thesis = r < static_cast<int>(e.thesisResult.runBest.size()) ? e.thesisResult.runBest[r] : NAN;
        ComparisonRow row{fmt::format("run {} best fitness", r + 1), best, thesis};
        sumBest += best;
        // Which holds for this run: does the model give the thesis's number for the thesis's own design?
        const int k = SpecimenOfRun(r + 1);
        if (k >= 0) {
            const double here = fitnessOf(specimenResults_[k]), reported = specimens[k].design.thesisFitness;
            const double tolerance = DefaultTolerance(reported);
            row.explained = WithinTolerance(here, reported, tolerance);
            row.why = row.explained ? fmt::format("their genome evaluated here: {}; the model agrees on their design, and our GA's best ({}) is another design",
                                                  CompareSentence(here, reported, tolerance), OrderSentence(best, reported))
                                    : fmt::format("their genome evaluated here: {}; this model does not give the thesis's number for its own design, "
                                                  "and our GA's best against their design here: {}",
                                                  CompareSentence(here, reported, tolerance), OrderSentence(best, here));
            c_.outcome.rows.push_back(row);
            c_.outcome.rows.push_back({fmt::format("run {} thesis genome", r + 1), here, reported});
            sumThesisHere += here;
            ++thesisHere;
            const bool splines = e.ga.genome.kind == sim::GenomeKind::BSpline && !s.hallOfFame.empty();
            table += fmt::format("| {} | {:.4g} | {:.4g} | {:.4g} | {} | {} |\n", r + 1, reported, here, best, ControlPointCount(specimens[k].design.shape),
                                 splines ? std::to_string(ControlPointCount(JobOfGenome(e, s.hallOfFame.front().genome).shape)) : std::string("-"));
        } else {
            c_.outcome.rows.push_back(row);
        }
        if (r == 0 && !s.logbook.empty()) c_.outcome.rows.push_back({"run 1 generation 0 best", s.logbook.front().best, NAN});
        if (s.hallOfFame.empty()) continue;
        c_.outcome.details.push_back(fmt::format("run {} (seed {}): best genome {}, stopped by {} after generation {}", r + 1, run.seed,
                                                 GenomeSummary(e, s.hallOfFame.front().genome), s.stopReason, s.generation));
    }
    if (std::isfinite(e.thesisResult.meanBest)) {
        // Against the mean of the thesis's table (its text's number is beside it in the report; for
        // 5.4 the two disagree).
        double thesisMean = e.thesisResult.meanBest;
        if (!e.thesisResult.runBest.empty()) {
            thesisMean = 0;
            for (double v : e.thesisResult.runBest) thesisMean += v / static_cast<double>(e.thesisResult.runBest.size());
        }
        ComparisonRow row{"mean best fitness", sumBest / e.runs, thesisMean};
        if (thesisHere == e.runs) {
            const double here = sumThesisHere / thesisHere, tolerance = DefaultTolerance(thesisMean);
            row.explained = WithinTolerance(here, thesisMean, tolerance);
            row.why = fmt::format("their genomes' mean here: {}{}", CompareSentence(here, thesisMean, tolerance),
                                  row.explained ? "; the model agrees on their designs and our GA found others" : "; the model does not give their numbers for their designs");
        }
        c_.outcome.rows.push_back(row);
    }
    if (!table.empty())
        c_.outcome.tables = "Each run of the thesis's table against its genome evaluated here and our GA's best (fitness; genome lengths in control points):\n\n"
                            "| run | thesis reported | their genome here | our GA's best | their length | our best's length |\n|---:|---:|---:|---:|---:|---:|\n" + table + "\n";
}

void GaEngine::EndFigures(int bestRun) {
    const Experiment& e = c_.e;
    const auto& specimens = e.thesisResult.specimens;
    // The best of each run before and after, beside the thesis's own design for that run where its
    // table prints one (evaluated here): Figures 5.4, 5.6 and 5.8 and the tables' specimens.
    std::vector<ArchiveRecord> bests;
    std::vector<int> bestRuns;
    for (int r = 0; r < e.runs; ++r) {
        const std::optional<RunBest> best = runs_[r]->Best();
        if (!best) continue;
        bests.push_back(c_.recorder.ReadBack({runs_[r]->Cache().Of(best->key).id}).at(0));
        bestRuns.push_back(r + 1);
    }
    std::vector<DesignPair> pairs;
    for (size_t b = 0; b < bests.size(); ++b) {
        pairs.push_back({&bests[b].result, &bests[b].job, fmt::format("run {}, ours", bestRuns[b])});
        if (const int k = SpecimenOfRun(bestRuns[b]); k >= 0)
            pairs.push_back({&specimenResults_[k], &specimenJobs_[k], fmt::format("{} (thesis {:g})", specimens[k].design.label, specimens[k].design.thesisFitness)});
    }
    if (!pairs.empty()) {
        const std::vector<std::string> lines{specimens.empty() ? "the best design of each run" : "each run's best (left) beside the thesis's design for that run, evaluated here (right)"};
        WritePng((c_.dir / "run_bests.png").string(),
                 PairsImage(PairsScene(ExperimentTitle(e) + "  -  best of each run", lines, pairs, specimens.empty() ? std::min<int>(3, pairs.size()) : 2)), 6);
        c_.outcome.figures.push_back("run_bests.png");
    }
    // Under the thesis model, the best after a hundred iterations beside the full run (Figure 5.2).
    if (bestRun >= 0 && e.model == sim::ModelKind::Thesis) {
        const ArchiveRecord full = c_.recorder.ReadBack({runs_[bestRun]->Cache().Of(runs_[bestRun]->Best()->key).id}).at(0);
        sim::EvalJob early = full.job;
        early.Thesis().params.iterations = std::min(100, full.job.Thesis().params.iterations);
        const sim::SimResult first = c_.recorder.EvaluateOne(early, {Role::Figure, bestRun + 1, -1, "time lapse of the best"});
        WritePng((c_.dir / "best_time_lapse.png").string(),
                 PairsImage(StagesScene(fmt::format("{}  -  best of run {}", ExperimentTitle(e), bestRun + 1), {"the same design after 100 and after the full run"},
                                        {&first, &full.result}, full.job)),
                 6);
        c_.outcome.figures.push_back("best_time_lapse.png");
    }
}

}  // namespace

std::unique_ptr<SearchEngine> MakeGaEngine(RunContext& c) { return std::make_unique<GaEngine>(c); }

}  // namespace app
