#include "evaluation/recorder.h"

#include <cmath>
#include <fmt/format.h>
#include <map>
#include <set>

#include "support/errors.h"
#include "formats/files.h"
#include "formats/results_folder.h"
#include "sim/search.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// The membrane and shell models' outputs follow the common columns; empty under the thesis model.
const std::vector<std::string> kLogHeader{"evaluation",       "role",         "run",         "generation",         "label",
                                          "shape",            "model",        "status",      "fitness",            "contraction_percent",
                                          "iterations",       "thumbnail",    "design",      "pressure_kpa",       "limit_pressure_kpa",
                                          "blocking_force_n", "axial_stiffness_n_per_mm", "volume_mm3", "max_stretch", "max_stress_kpa",
                                          "fibres",           "max_fibre_strain", "fibre_angle_deg"};

std::string Optional(double value) { return std::isfinite(value) ? CsvNumber(value) : ""; }

}  // namespace

std::string DesignText(const sim::Shape& shape) {
    if (const auto* s = std::get_if<sim::SineShape>(&shape)) return fmt::format("amplitude={} phase={},{}", s->amplitude, s->phaseStart, s->phaseEnd);
    if (const auto* a = std::get_if<sim::AbsSineShape>(&shape)) return fmt::format("amplitude={} phase={},{}", a->amplitude, a->phaseStart, a->phaseEnd);
    if (std::holds_alternative<sim::BSplineShape>(shape) || std::holds_alternative<sim::FreeXYShape>(shape))
        return sim::GenomeText(sim::GenomeOfShape(shape));
    return "";
}

Recorder::Recorder(const fs::path& dir, const std::string& experimentId, Evaluator& evaluator, bool thumbnails, bool resume, ResultsFolder* folder)
    : dir_(dir), experimentId_(experimentId), evaluator_(evaluator), folder_(folder), thumbnails_(thumbnails) {
    const fs::path archive = dir_ / "evaluations.capnp";
    std::error_code ec;
    if (resume && fs::exists(archive, ec)) {
        const ArchiveContents contents = ReadArchive(archive.string(), false);
        if (contents.scan.corrupt) throw UsageError(Quote(archive.string()) + ": " + contents.scan.problem + "; it cannot be resumed");
        existing_ = contents.records;
        return;  // the runner decides where to resume from: RollBack
    }
    Open();
}

void Recorder::Open() {
    archive_ = std::make_unique<ArchiveWriter>((dir_ / "evaluations.capnp").string());
    count_ = archive_->Count();
    log_ = CsvLog((dir_ / "evaluations.csv").string(), kLogHeader);
    if (thumbnails_) thumbnailWriter_ = std::make_unique<ThumbnailWriter>(dir_ / "thumbnails");
}

void Recorder::RollBack(std::uint64_t keep) {
    if (keep > existing_.size())
        throw UsageError(Quote((dir_ / "evaluations.capnp").string()) + " holds " + std::to_string(existing_.size()) +
                         " evaluations, fewer than its checkpoint's " + std::to_string(keep) + "; it cannot be resumed");
    const fs::path archive = dir_ / "evaluations.capnp";
    std::error_code ec;
    if (fs::exists(archive, ec)) TruncateArchive(archive.string(), keep);
    existing_.resize(keep);
    // The log is rebuilt from the records it describes; thumbnails past the cut go.
    fs::remove(dir_ / "evaluations.csv", ec);
    for (fs::directory_iterator it(dir_ / "thumbnails", ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        unsigned long long id = 0;
        if (std::sscanf(name.c_str(), "evaluation_%llu.png", &id) == 1 && id >= keep) fs::remove(it->path(), ec);
    }
    Open();
    count_ = keep;
    for (const ArchiveRecord& r : existing_) Log(r);
}

void Recorder::Log(const ArchiveRecord& r) {
    const bool ok = r.result.status == sim::Status::Ok;
    const bool thesis = r.job.model == sim::ModelKind::Thesis;
    const sim::ShellOutputs& o = r.result.shell;
    // Iterations: relaxation steps (thesis) or Newton iterations over all load steps.
    std::vector<std::string> row{std::to_string(r.id), sim::Name(r.role), std::to_string(r.run), std::to_string(r.generation), CsvField(r.label),
                                 sim::ShapeName(r.job.shape), sim::Name(r.job.model), sim::Name(r.result.status), ok ? CsvNumber(r.result.fitness) : "",
                                 ok ? CsvNumber(r.result.contractionPercent) : "", std::to_string(thesis ? r.result.iterationsRun : o.newtonIterations),
                                 thumbnails_ ? ThumbnailWriter::Name(r.id) : "", CsvField(DesignText(r.job.shape))};
    if (thesis) row.resize(kLogHeader.size());
    else {
        for (double v : {r.job.shell.load.pressureKpa, o.limitPressureKpa, o.blockingForceN, o.axialStiffnessNPerMm, o.volumeMm3, o.maxStretch, o.maxStressKpa})
            row.push_back(Optional(v));
        row.push_back(sim::Name(r.job.shell.fibres.layout));
        row.push_back(Optional(o.maxFibreStrain));
        row.push_back(Optional(o.fibreAngleDeg));
    }
    log_.Append(row);
}

void Recorder::Evaluate(const std::vector<sim::EvalJob>& jobs, const std::vector<EvaluationTag>& tags, const Each& each) {
    if (!archive_) throw std::logic_error("Recorder::RollBack must come before Evaluate on a resume");
    evaluator_.Evaluate(jobs, [&](size_t index, sim::SimResult&& result) {
        ArchiveRecord record;
        record.experiment = experimentId_;
        record.run = tags[index].run;
        record.generation = tags[index].generation;
        record.role = tags[index].role;
        record.label = tags[index].label;
        record.job = jobs[index];
        record.result = std::move(result);
        if (thumbnailWriter_) thumbnailWriter_->Write(count_, record.result, record.job);
        const std::uint64_t id = archive_->Append(record);
        Log(record);
        ++count_;
        ++simulated_;
        if (folder_) folder_->FirstResultDone();
        if (each) each(id, index, std::move(record.result));
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
