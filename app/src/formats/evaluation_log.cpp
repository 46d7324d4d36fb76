#include "formats/evaluation_log.h"

#include <cmath>
#include <fmt/format.h>

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

std::string ThumbnailName(std::uint64_t id) { return fmt::format("evaluation_{:06}.png", id); }

}  // namespace

std::string DesignText(const sim::Shape& shape) {
    if (const auto* s = std::get_if<sim::SineShape>(&shape)) return fmt::format("amplitude={} phase={},{}", s->amplitude, s->phaseStart, s->phaseEnd);
    if (const auto* a = std::get_if<sim::AbsSineShape>(&shape)) return fmt::format("amplitude={} phase={},{}", a->amplitude, a->phaseStart, a->phaseEnd);
    if (std::holds_alternative<sim::BSplineShape>(shape) || std::holds_alternative<sim::FreeXYShape>(shape))
        return sim::GenomeText(sim::GenomeOfShape(shape));
    return "";
}

EvaluationLog::EvaluationLog(fs::path path, bool thumbnails) : path_(std::move(path)), thumbnails_(thumbnails), log_(path_.string(), kLogHeader) {}

void EvaluationLog::Append(const ArchiveRecord& r) {
    const bool ok = r.result.status == sim::Status::Ok;
    const bool thesis = r.job.model == sim::ModelKind::Thesis;
    const sim::ShellOutputs& o = r.result.shell;
    // Iterations: relaxation steps (thesis) or Newton iterations over all load steps.
    std::vector<std::string> row{std::to_string(r.id), sim::Name(r.role), std::to_string(r.run), std::to_string(r.generation), CsvField(r.label),
                                 sim::ShapeName(r.job.shape), sim::Name(r.job.model), sim::Name(r.result.status), ok ? CsvNumber(r.result.fitness) : "",
                                 ok ? CsvNumber(r.result.contractionPercent) : "", std::to_string(thesis ? r.result.iterationsRun : o.newtonIterations),
                                 thumbnails_ ? ThumbnailName(r.id) : "", CsvField(DesignText(r.job.shape))};
    if (thesis) row.resize(kLogHeader.size());
    else {
        for (double v : {r.job.Shell().load.pressureKpa, o.limitPressureKpa, o.blockingForceN, o.axialStiffnessNPerMm, o.volumeMm3, o.maxStretch, o.maxStressKpa})
            row.push_back(Optional(v));
        row.push_back(sim::Name(r.job.Shell().fibres.layout));
        row.push_back(Optional(o.maxFibreStrain));
        row.push_back(Optional(o.fibreAngleDeg));
    }
    log_.Append(row);
}

void EvaluationLog::RollBack(std::uint64_t, const std::vector<ArchiveRecord>& kept) {
    // Rebuilt from the records it describes: a run killed between its archive's append and the
    // log's leaves the log a row short, and the archive is the record of what was evaluated.
    log_ = CsvLog();
    std::error_code ec;
    fs::remove(path_, ec);
    log_ = CsvLog(path_.string(), kLogHeader);
    for (const ArchiveRecord& r : kept) Append(r);
}

}  // namespace app
