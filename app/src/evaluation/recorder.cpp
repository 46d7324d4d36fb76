#include "evaluation/recorder.h"

#include <cmath>
#include <fmt/format.h>
#include <map>
#include <set>

#include "pictures/figures.h"
#include "support/errors.h"
#include "formats/files.h"
#include "formats/results_folder.h"
#include "sim/search.h"

namespace app {

namespace fs = std::filesystem;

Recorder::Recorder(const fs::path& dir, const std::string& experimentId, Evaluator& evaluator, bool thumbnails, bool resume, ResultsFolder* folder)
    : dir_(dir), experimentId_(experimentId), evaluator_(evaluator), folder_(folder) {
    const fs::path archive = dir_ / "evaluations.capnp";
    std::error_code ec;
    resuming_ = resume && fs::exists(archive, ec);
    if (resuming_) {
        const ArchiveContents contents = ReadArchive(archive.string(), false);
        if (contents.scan.corrupt) throw UsageError(Quote(archive.string()) + ": " + contents.scan.problem + "; it cannot be resumed");
        existing_ = contents.records;  // the runner decides where to resume from: RollBack
    }
    if (thumbnails) sinks_.push_back(std::make_unique<Thumbnails>(dir_ / "thumbnails"));
    auto sink = std::make_unique<ArchiveSink>(archive.string(), resuming_);
    archive_ = sink.get();
    sinks_.push_back(std::move(sink));
    sinks_.push_back(std::make_unique<EvaluationLog>(dir_ / "evaluations.csv", thumbnails));
    count_ = archive_->Count();
}

void Recorder::RollBack(std::uint64_t keep) {
    if (keep > existing_.size())
        throw UsageError(Quote((dir_ / "evaluations.capnp").string()) + " holds " + std::to_string(existing_.size()) +
                         " evaluations, fewer than its checkpoint's " + std::to_string(keep) + "; it cannot be resumed");
    existing_.resize(keep);
    for (auto& sink : sinks_) sink->RollBack(keep, existing_);
    resuming_ = false;
    count_ = keep;
}

void Recorder::Evaluate(const std::vector<sim::EvalJob>& jobs, const std::vector<EvaluationTag>& tags, const Each& each) {
    if (resuming_) throw std::logic_error("Recorder::RollBack must come before Evaluate on a resume");
    evaluator_.Evaluate(jobs, [&](size_t index, sim::SimResult&& result) {
        ArchiveRecord record;
        record.id = count_;
        record.experiment = experimentId_;
        record.run = tags[index].run;
        record.generation = tags[index].generation;
        record.role = tags[index].role;
        record.label = tags[index].label;
        record.job = jobs[index];
        record.result = std::move(result);
        for (auto& sink : sinks_) sink->Append(record);
        ++count_;
        ++simulated_;
        if (folder_) folder_->FirstResultDone();
        if (each) each(record.id, index, std::move(record.result));
    });
}

sim::SimResult Recorder::EvaluateOne(const sim::EvalJob& job, const EvaluationTag& tag) {
    sim::SimResult out;
    Evaluate({job}, {tag}, [&](std::uint64_t, size_t, sim::SimResult&& r) { out = std::move(r); });
    return out;
}

void Recorder::ForEachRecord(std::uint64_t first, std::uint64_t last, const std::function<void(ArchiveRecord&&)>& visit) const {
    std::uint64_t id = 0;
    ScanArchive((dir_ / "evaluations.capnp").string(), true, [&](ArchiveRecord&& r) {
        r.id = id;
        if (id >= first && id < last) visit(std::move(r));
        return ++id < last;
    });
}

std::vector<ArchiveRecord> Recorder::ReadBack(const std::vector<std::uint64_t>& ids) const {
    if (ids.empty()) return {};
    std::map<std::uint64_t, ArchiveRecord> found;
    const std::uint64_t last = *std::max_element(ids.begin(), ids.end()) + 1;
    const std::set<std::uint64_t> wanted(ids.begin(), ids.end());
    ForEachRecord(0, last, [&](ArchiveRecord&& r) {
        if (wanted.count(r.id)) found.emplace(r.id, std::move(r));
    });
    std::vector<ArchiveRecord> records;
    for (std::uint64_t id : ids)
        if (auto it = found.find(id); it != found.end()) records.push_back(it->second);
    return records;
}

}  // namespace app
