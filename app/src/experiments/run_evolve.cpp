// The thesis's genetic algorithm (chapter 5) for as many independent runs as the experiment asks:
// sim's pure GA steps around an evaluation callback, every evaluation recorded, the run's tables,
// a contact sheet of every generation and a checkpoint written after each generation. A resume
// cuts the archive back to the newest checkpoint and continues from it: every output then equals
// an uninterrupted run's.
#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <map>
#include <optional>
#include <unordered_map>

#include "experiments/checkpoint.h"
#include "support/errors.h"
#include "experiments/experiment_runner.h"
#include "formats/files.h"
#include "pictures/plots.h"
#include "support/progress.h"
#include "experiments/thesis_check.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// Evaluates genomes through the recorder, each distinct genome once per run (the simulation is
// deterministic, so this changes speed only), and keeps the meshes of the current population for
// its contact sheet.
class GenomeCache {
public:
    GenomeCache(RunContext& c, int run) : c_(c), run_(run) {}

    // After a resume: what this run had evaluated up to its checkpoint.
    void Restore(const std::vector<ArchiveRecord>& records) {
        for (const ArchiveRecord& r : records) {
            if (r.role != Role::Individual || r.run != run_) continue;
            const std::string key = sim::GenomeText(GenomeOfJob(c_.e, r.job));
            fitness_.emplace(key, std::pair{r.result.fitness, r.result.status});
            ids_.emplace(key, r.id);
        }
    }

    void SetGeneration(int generation) { generation_ = generation; }

    std::vector<std::pair<double, sim::Status>> operator()(const std::vector<const sim::Genome*>& genomes) {
        std::vector<std::pair<double, sim::Status>> out(genomes.size());
        std::vector<sim::EvalJob> jobs;
        std::vector<EvaluationTag> tags;
        std::vector<size_t> slots;
        std::vector<std::string> keys;
        for (size_t j = 0; j < genomes.size(); ++j) {
            std::string key = sim::GenomeText(*genomes[j]);
            if (auto hit = fitness_.find(key); hit != fitness_.end()) {
                out[j] = hit->second;
                continue;
            }
            // The same new genome twice in one batch is simulated once.
            if (std::find(keys.begin(), keys.end(), key) != keys.end()) {
                slots.push_back(j);
                continue;
            }
            jobs.push_back(JobOfGenome(c_.e, *genomes[j]));
            tags.push_back({Role::Individual, run_, generation_, fmt::format("run {} generation {}", run_, generation_)});
            slots.push_back(j);
            keys.push_back(std::move(key));
        }
        c_.recorder.Evaluate(jobs, tags, [&](std::uint64_t id, size_t k, sim::SimResult&& r) {
            fitness_.emplace(keys[k], std::pair{r.fitness, r.status});
            ids_.emplace(keys[k], id);
            meshes_[keys[k]] = std::move(r);
        });
        for (size_t slot : slots) out[slot] = fitness_.at(sim::GenomeText(*genomes[slot]));
        return out;
    }

    // The simulated meshes of a population: kept from this session, else read back from the archive
    // (after a resume). The kept meshes are then trimmed to this population.
    std::vector<const sim::SimResult*> MeshesOf(const std::vector<sim::Individual>& population) {
        std::vector<std::uint64_t> missing;
        std::vector<std::string> keys;
        for (const auto& individual : population) {
            keys.push_back(sim::GenomeText(individual.genome));
            if (!meshes_.count(keys.back())) missing.push_back(ids_.at(keys.back()));
        }
        for (ArchiveRecord& r : c_.recorder.ReadBack(missing)) meshes_[sim::GenomeText(GenomeOfJob(c_.e, r.job))] = std::move(r.result);
        std::unordered_map<std::string, sim::SimResult> kept;
        for (const auto& key : keys)
            if (!kept.count(key)) kept.emplace(key, std::move(meshes_.at(key)));
        meshes_ = std::move(kept);
        std::vector<const sim::SimResult*> out;
        for (const auto& key : keys) out.push_back(&meshes_.at(key));
        return out;
    }

    std::uint64_t IdOf(const sim::Genome& genome) const { return ids_.at(sim::GenomeText(genome)); }

private:
    RunContext& c_;
    int run_;
    int generation_ = 0;
    std::unordered_map<std::string, std::pair<double, sim::Status>> fitness_;
    std::unordered_map<std::string, std::uint64_t> ids_;
    std::unordered_map<std::string, sim::SimResult> meshes_;
};

void WriteRunFiles(const fs::path& dir, const RunCheckpoint& checkpoint) {
    WriteFileAtomically((dir / "logbook.csv").string(), LogbookCsv(checkpoint.state));
    WriteFileAtomically((dir / "best_per_generation.csv").string(), BestPerGenerationCsv(checkpoint.state));
    WriteFileAtomically((dir / "halloffame.csv").string(), HallOfFameCsv(checkpoint.state));
    // Last: a checkpoint always describes files that are already complete.
    WriteFileAtomically((dir / "checkpoint.json").string(), FormatCheckpoint(checkpoint));
}


void WriteGenerationSheet(RunContext& c, const fs::path& runDir, int run, GenomeCache& cache, const sim::GaState& state,
                          std::unique_ptr<render::MeshRenderer>& renderer) {
    if (!c.e.render.figures) return;
    std::error_code ec;
    fs::create_directories(runDir / "sheets", ec);
    const auto meshes = cache.MeshesOf(state.population);
    std::vector<SheetEntry> entries;
    for (const sim::SimResult* mesh : meshes) entries.push_back({mesh, FitnessCaption(*mesh)});
    WriteContactSheet(runDir / SheetName(state.generation),
                      fmt::format("{}  -  run {}, generation {}", ExperimentTitle(c.e), run, state.generation), entries, JobOf(c.e, c.e.sweep.base), renderer);
}

std::string GenomeSummary(const Experiment& e, const sim::Genome& genome) {
    return e.ga.genome.kind == sim::GenomeKind::BSpline ? "[" + sim::GenomeText(genome) + "]" : "of " + std::to_string(genome[0].size()) + " offsets";
}

}  // namespace

void RunEvolution(RunContext& c) {
    const Experiment& e = c.e;
    auto runDir = [&](int r) { return RunFolder(c, r); };

    // Resume: every run up to the newest checkpoint; the archive is cut back to that checkpoint.
    std::vector<std::optional<RunCheckpoint>> saved =
        ResumeRuns<RunCheckpoint>(c, e.runs, [&](const std::string& text, const std::string& path) { return ParseCheckpoint(text, path, e); });

    std::vector<RunCheckpoint> runs;
    std::vector<std::unique_ptr<GenomeCache>> caches;
    for (int r = 1; r <= e.runs; ++r) {
        const fs::path dir = runDir(r);
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (!fs::is_directory(dir, ec)) throw UsageError("cannot create folder " + Quote(dir.string()));
        caches.push_back(std::make_unique<GenomeCache>(c, r));
        GenomeCache& cache = *caches.back();
        const sim::GenomeEvaluator evaluator = [&](const std::vector<const sim::Genome*>& genomes) { return cache(genomes); };
        std::unique_ptr<render::MeshRenderer> sheetRenderer;
        Progress progress(fmt::format("evolve {} run {}/{}", ExperimentTitle(e), r, e.runs), c.options.progress);
        RunCheckpoint checkpoint;
        if (saved[r - 1]) {
            checkpoint = std::move(*saved[r - 1]);
            cache.Restore(c.recorder.Existing());
        } else {
            checkpoint.seed = sim::DeriveSeed(e.seed, static_cast<std::uint64_t>(r - 1));
            checkpoint.experimentHash = ExperimentHash(e);
            checkpoint.experiment = e.document;
            cache.SetGeneration(0);
            checkpoint.state = sim::StartEvolution(e.ga, DesignMesh(e), checkpoint.seed, evaluator);
            WriteGenerationSheet(c, dir, r, cache, checkpoint.state, sheetRenderer);
            checkpoint.archiveCount = c.recorder.Count();
            WriteRunFiles(dir, checkpoint);
        }
        const auto started = std::chrono::steady_clock::now();
        while (checkpoint.state.stopReason.empty()) {
            // The stop criteria, after each generation; wall time counts this session's.
            std::string reason = sim::GaStopReason(e.ga, checkpoint.state);
            if (reason.empty() && e.ga.stop.seconds > 0 &&
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >= e.ga.stop.seconds)
                reason = "seconds";
            if (!reason.empty()) {
                checkpoint.state.stopReason = reason;
                WriteRunFiles(dir, checkpoint);
                break;
            }
            cache.SetGeneration(checkpoint.state.generation + 1);
            if (!sim::EvolveOneGeneration(e.ga, DesignMesh(e), checkpoint.state, evaluator)) {
                std::map<std::string, int> statuses;
                for (const sim::SimResult* result : cache.MeshesOf(checkpoint.state.population)) ++statuses[sim::Name(result->status)];
                std::string tally;
                for (const auto& [status, count] : statuses) tally += (tally.empty() ? "" : ", ") + std::to_string(count) + " " + status;
                std::cerr << "run " << r << ": every individual of generation " << checkpoint.state.generation << " failed (" << tally
                          << "); the run stops here. The status column of evaluations.csv says why for each.\n";
                checkpoint.state.stopReason = "no valid design";
                WriteRunFiles(dir, checkpoint);
                break;
            }
            WriteGenerationSheet(c, dir, r, cache, checkpoint.state, sheetRenderer);
            checkpoint.archiveCount = c.recorder.Count();
            WriteRunFiles(dir, checkpoint);
            // Progress by evaluations when an evaluation budget ends the run first (compare's runs).
            long long evaluated = 0;
            for (const auto& row : checkpoint.state.logbook) evaluated += row.evaluations;
            const long long budget = e.ga.stop.evaluations;
            const bool byBudget = budget > 0 && budget < static_cast<long long>(e.ga.generations + 1) * e.ga.population;
            progress.Update(byBudget ? std::min(evaluated, budget) : checkpoint.state.generation, byBudget ? budget : e.ga.generations,
                            c.recorder.Simulated(), fmt::format("best {:.4f}, {}", checkpoint.state.logbook.back().best, byBudget ? "evaluations" : "generation"));
        }
        runs.push_back(std::move(checkpoint));
    }

    // The thesis's own designs (its tables' genomes), evaluated here like any other design.
    const auto& specimens = e.thesisResult.specimens;
    std::vector<sim::SimResult> specimenResults(specimens.size());
    std::vector<sim::EvalJob> specimenJobs;
    {
        std::vector<EvaluationTag> tags;
        for (const auto& specimen : specimens) {
            specimenJobs.push_back(JobOf(e, specimen.design.shape));
            tags.push_back({Role::ThesisPoint, specimen.run, -1, "thesis specimen: " + specimen.design.label});
        }
        c.recorder.Evaluate(specimenJobs, tags, [&](std::uint64_t, size_t k, sim::SimResult&& r) { specimenResults[k] = std::move(r); });
    }
    auto specimenOfRun = [&](int run) -> int {
        for (size_t k = 0; k < specimens.size(); ++k)
            if (specimens[k].run == run) return static_cast<int>(k);
        return -1;
    };
    auto fitnessOf = [](const sim::SimResult& r) { return r.status == sim::Status::Ok ? r.fitness : NAN; };

    int bestRun = -1;
    double sumBest = 0, sumThesisHere = 0;
    int thesisHere = 0;
    std::string table;
    for (int r = 0; r < e.runs; ++r) {
        const auto& s = runs[r].state;
        const double best = s.hallOfFame.empty() ? NAN : s.hallOfFame.front().fitness;
        const double thesis = r < static_cast<int>(e.thesisResult.runBest.size()) ? e.thesisResult.runBest[r] : NAN;
        ComparisonRow row{fmt::format("run {} best fitness", r + 1), best, thesis};
        sumBest += best;
        // Which holds for this run: does the model give the thesis's number for the thesis's own design?
        const int k = specimenOfRun(r + 1);
        if (k >= 0) {
            const double here = fitnessOf(specimenResults[k]), reported = specimens[k].design.thesisFitness;
            const double tolerance = DefaultTolerance(reported);
            row.explained = WithinTolerance(here, reported, tolerance);
            row.why = row.explained ? fmt::format("their genome evaluated here: {}; the model agrees on their design, and our GA's best ({}) is another design",
                                                  CompareSentence(here, reported, tolerance), OrderSentence(best, reported))
                                    : fmt::format("their genome evaluated here: {}; this model does not give the thesis's number for its own design, "
                                                  "and our GA's best against their design here: {}",
                                                  CompareSentence(here, reported, tolerance), OrderSentence(best, here));
            c.outcome.rows.push_back(row);
            c.outcome.rows.push_back({fmt::format("run {} thesis genome", r + 1), here, reported});
            sumThesisHere += here;
            ++thesisHere;
            const bool splines = e.ga.genome.kind == sim::GenomeKind::BSpline && !s.hallOfFame.empty();
            table += fmt::format("| {} | {:.4g} | {:.4g} | {:.4g} | {} | {} |\n", r + 1, reported, here, best, ControlPointCount(specimens[k].design.shape),
                                 splines ? std::to_string(ControlPointCount(JobOfGenome(e, s.hallOfFame.front().genome).shape)) : std::string("-"));
        } else {
            c.outcome.rows.push_back(row);
        }
        if (r == 0 && !s.logbook.empty()) c.outcome.rows.push_back({"run 1 generation 0 best", s.logbook.front().best, NAN});
        if (s.hallOfFame.empty()) continue;
        c.outcome.details.push_back(fmt::format("run {} (seed {}): best genome {}, stopped by {} after generation {}", r + 1, runs[r].seed,
                                                GenomeSummary(e, s.hallOfFame.front().genome), s.stopReason, s.generation));
        if (bestRun < 0 || best > runs[bestRun].state.hallOfFame.front().fitness) bestRun = r;
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
        c.outcome.rows.push_back(row);
    }
    if (!table.empty())
        c.outcome.tables = "Each run of the thesis's table against its genome evaluated here and our GA's best (fitness; genome lengths in control points):\n\n"
                           "| run | thesis reported | their genome here | our GA's best | their length | our best's length |\n|---:|---:|---:|---:|---:|---:|\n" + table + "\n";
    if (bestRun >= 0) {
        const auto& best = runs[bestRun].state.hallOfFame.front();
        c.outcome.bestJob = JobOfGenome(e, best.genome);
        c.outcome.bestFitness = best.fitness;
    }
    if (!e.render.figures) return;

    std::vector<RunCurve> curves;
    for (int r = 0; r < e.runs; ++r) {
        curves.push_back({fmt::format("run {}", r + 1), runs[r].state.logbook});
        if (r < static_cast<int>(e.thesisResult.runBest.size())) {
            curves.back().reference = e.thesisResult.runBest[r];
            curves.back().referenceLabel = fmt::format("thesis's best: {:g}", e.thesisResult.runBest[r]);
        }
    }
    WritePng((c.dir / "evolution.png").string(), EvolutionImage(PlotContextOf(e), curves), 6);
    c.outcome.figures.push_back("evolution.png");
    // The best of each run before and after, beside the thesis's own design for that run where its
    // table prints one (evaluated here): Figures 5.4, 5.6 and 5.8 and the tables' specimens.
    {
        std::vector<ArchiveRecord> bests;
        std::vector<int> bestRuns;
        for (int r = 0; r < e.runs; ++r) {
            if (runs[r].state.hallOfFame.empty()) continue;
            bests.push_back(c.recorder.ReadBack({caches[r]->IdOf(runs[r].state.hallOfFame.front().genome)}).at(0));
            bestRuns.push_back(r + 1);
        }
        std::vector<DesignPair> pairs;
        for (size_t b = 0; b < bests.size(); ++b) {
            pairs.push_back({&bests[b].result, &bests[b].job, fmt::format("run {}, ours", bestRuns[b])});
            if (const int k = specimenOfRun(bestRuns[b]); k >= 0)
                pairs.push_back({&specimenResults[k], &specimenJobs[k], fmt::format("{} (thesis {:g})", specimens[k].design.label, specimens[k].design.thesisFitness)});
        }
        if (!pairs.empty()) {
            const std::vector<std::string> lines{specimens.empty() ? "the best design of each run" : "each run's best (left) beside the thesis's design for that run, evaluated here (right)"};
            WritePng((c.dir / "run_bests.png").string(),
                     PairsImage(PairsScene(ExperimentTitle(e) + "  -  best of each run", lines, pairs, specimens.empty() ? std::min<int>(3, pairs.size()) : 2)),
                     6);
            c.outcome.figures.push_back("run_bests.png");
        }
    }
    // Under the thesis model, the best after a hundred iterations beside the full run (Figure 5.2).
    if (bestRun >= 0 && e.model == sim::ModelKind::Thesis) {
        const ArchiveRecord full = c.recorder.ReadBack({caches[bestRun]->IdOf(runs[bestRun].state.hallOfFame.front().genome)}).at(0);
        sim::EvalJob early = full.job;
        early.Thesis().params.iterations = std::min(100, full.job.Thesis().params.iterations);
        const sim::SimResult first = c.recorder.EvaluateOne(early, {Role::Figure, bestRun + 1, -1, "time lapse of the best"});
        WritePng((c.dir / "best_time_lapse.png").string(),
                 PairsImage(StagesScene(fmt::format("{}  -  best of run {}", ExperimentTitle(e), bestRun + 1), {"the same design after 100 and after the full run"},
                                        {&first, &full.result}, full.job)),
                 6);
        c.outcome.figures.push_back("best_time_lapse.png");
    }
    for (int r = 0; r < e.runs; ++r) {
        const std::string sheet = "run_" + std::to_string(r + 1) + "/" + SheetName(runs[r].state.generation);
        std::error_code ec;
        if (fs::exists(c.dir / sheet, ec)) c.outcome.figures.push_back(sheet);
    }
    if (e.render.turntable == TurntablePlan::All) {
        // Every member of each run's final population turning (all evaluations would be thousands).
        for (int r = 0; r < e.runs; ++r) {
            const auto& population = runs[r].state.population;
            for (size_t k = 0; k < population.size(); ++k) {
                const fs::path folder = runDir(r + 1) / "final_population" / ("individual_" + std::to_string(k + 1));
                std::error_code ec;
                fs::create_directories(folder, ec);
                const ArchiveRecord record = c.recorder.ReadBack({caches[r]->IdOf(population[k].genome)}).at(0);
                WriteBestFigures(c, folder, record.job, record.result, fmt::format("run {}, individual {}", r + 1, k + 1), e.render.turntableFrames,
                                 false);
            }
        }
    }
    if (bestRun >= 0) {
        const auto& best = runs[bestRun].state.hallOfFame.front();
        const ArchiveRecord record = c.recorder.ReadBack({caches[bestRun]->IdOf(best.genome)}).at(0);
        std::string title = fmt::format("best of run {}: {}", bestRun + 1,
                                              e.ga.genome.kind == sim::GenomeKind::BSpline ? ShapeTitle(record.job.shape) : std::string("free-xy offsets"));
        const std::string fibres = record.job.model == sim::ModelKind::Thesis ? "" : FibreTitle(record.job.Shell().fibres);
        if (!fibres.empty()) title += ",  " + fibres;
        WriteBestFigures(c, c.dir, record.job, record.result, title, e.render.turntable == TurntablePlan::None ? 0 : e.render.turntableFrames, true);
    }
}

}  // namespace app
