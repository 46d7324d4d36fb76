// Every evaluation an experiment makes goes through a Recorder: evaluated by the Evaluator, then, in
// job order and under one evaluation id (its place in the archive), handed to each record sink:
// DIR/thumbnails/evaluation_NNNNNN.png, DIR/evaluations.capnp and a row of DIR/evaluations.csv (in
// that order: an archived record has its picture, a logged one is archived). On --resume the
// recorder reads what the archive holds, and RollBack() cuts every sink back to the point the run
// resumes from, so that the resumed run's outputs equal an uninterrupted run's.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "evaluation/evaluator.h"
#include "formats/archive.h"
#include "formats/evaluation_log.h"
#include "formats/record_sink.h"

namespace app {

class ResultsFolder;

struct EvaluationTag {
    Role role = Role::Grid;
    int run = 0;          // GA run, 1-based
    int generation = -1;  // GA generation
    std::string label;
};

class Recorder {
public:
    // Opens DIR's archive and evaluation log. With `resume`, reads the records already there (see
    // Existing) and leaves the files untouched until RollBack. `folder` is told of the first result.
    Recorder(const std::filesystem::path& dir, const std::string& experimentId, Evaluator& evaluator, bool thumbnails, bool resume,
             ResultsFolder* folder);

    // Evaluates the jobs and records each result in order; then `each(id, index, result)`.
    using Each = std::function<void(std::uint64_t id, size_t index, sim::SimResult&& result)>;
    void Evaluate(const std::vector<sim::EvalJob>& jobs, const std::vector<EvaluationTag>& tags, const Each& each = {});
    // One job, its result returned.
    sim::SimResult EvaluateOne(const sim::EvalJob& job, const EvaluationTag& tag);

    std::uint64_t Count() const { return count_; }
    long long Simulated() const { return simulated_; }  // this session's simulations

    // Resume: the records the archive held when opened (without meshes).
    const std::vector<ArchiveRecord>& Existing() const { return existing_; }
    // Cuts every sink back to the first `keep` records, then opens them for appending. Called once
    // on resume, before any Evaluate.
    void RollBack(std::uint64_t keep);

    // Records with their meshes, read back from the archive in one pass: those with these ids (in
    // the order given; ids past the end are left out), or each of [first, last) in turn.
    std::vector<ArchiveRecord> ReadBack(const std::vector<std::uint64_t>& ids) const;
    void ForEachRecord(std::uint64_t first, std::uint64_t last, const std::function<void(ArchiveRecord&&)>& visit) const;

    const std::filesystem::path& Dir() const { return dir_; }

private:
    std::filesystem::path dir_;
    std::string experimentId_;
    Evaluator& evaluator_;
    ResultsFolder* folder_;
    bool resuming_;
    std::vector<ArchiveRecord> existing_;
    ArchiveSink* archive_ = nullptr;                    // one of the sinks: where ids come from
    std::vector<std::unique_ptr<RecordSink>> sinks_;   // thumbnails, archive, log
    std::uint64_t count_ = 0;
    long long simulated_ = 0;
};

}  // namespace app
