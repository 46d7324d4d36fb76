#include "formats/evaluation_log.h"

#include <cmath>
#include <map>
#include <fmt/format.h>

#include "sim/model.h"
#include "sim/search.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// Who and what, every model's outputs by name (empty where a row's model has none), the fibre
// layout, the picture and the design.
std::vector<std::string> LogHeader() {
    std::vector<std::string> header{"evaluation", "role", "run", "generation", "label", "shape", "model", "status"};
    for (std::string& name : sim::OutputNames(false)) header.push_back(std::move(name));
    header.push_back("fibres");  // the layout each design was evaluated with (a GA's genes may switch families)
    header.push_back("thumbnail");
    header.push_back("design");
    return header;
}

std::string ThumbnailName(std::uint64_t id) { return fmt::format("evaluation_{:06}.png", id); }

}  // namespace

std::map<std::string, std::string> OutputCells(const sim::SimResult& result, const sim::EvalJob& job) {
    struct Cells final : sim::OutputVisitor {
        std::map<std::string, std::string> cells;
        void Number(const char* name, const char*, double value) override { cells[name] = std::isfinite(value) ? CsvNumber(value) : ""; }
        void Count(const char* name, long long value) override { cells[name] = std::to_string(value); }
        void Curve(const char*, const char*, const std::vector<double>&) override {}
    } outputs;
    sim::VisitOutputs(result, job, outputs);
    return std::move(outputs.cells);
}

std::string DesignText(const sim::Shape& shape) {
    if (const auto* s = std::get_if<sim::SineShape>(&shape)) return fmt::format("amplitude={} phase={},{}", s->amplitude, s->phaseStart, s->phaseEnd);
    if (const auto* a = std::get_if<sim::AbsSineShape>(&shape)) return fmt::format("amplitude={} phase={},{}", a->amplitude, a->phaseStart, a->phaseEnd);
    if (std::holds_alternative<sim::BSplineShape>(shape) || std::holds_alternative<sim::FreeXYShape>(shape))
        return sim::GenomeText(sim::GenomeOfShape(shape));
    return "";
}

EvaluationLog::EvaluationLog(fs::path path, bool thumbnails) : path_(std::move(path)), thumbnails_(thumbnails), header_(LogHeader()), log_(path_.string(), header_) {}

namespace {

// A record's row under LogHeader, each field as it reads back (not yet quoted for CSV).
std::vector<std::string> LogRow(const ArchiveRecord& r, bool thumbnails, const std::vector<std::string>& header) {
    std::map<std::string, std::string> cells = OutputCells(r.result, r.job);
    cells["evaluation"] = std::to_string(r.id);
    cells["role"] = sim::Name(r.role);
    cells["run"] = std::to_string(r.run);
    cells["generation"] = std::to_string(r.generation);
    cells["label"] = r.label;
    cells["shape"] = sim::ShapeName(r.job.shape);
    cells["model"] = sim::Name(r.job.model);
    cells["status"] = sim::Name(r.result.status);
    if (const auto* shell = std::get_if<sim::ShellDef>(&r.job.def)) cells["fibres"] = sim::Name(shell->fibres.layout);
    cells["thumbnail"] = thumbnails ? ThumbnailName(r.id) : "";
    cells["design"] = DesignText(r.job.shape);
    std::vector<std::string> row;
    for (const std::string& column : header) row.push_back(cells[column]);
    return row;
}

}  // namespace

Table EvaluationTable(const std::vector<ArchiveRecord>& records) {
    Table table(LogHeader());
    for (const ArchiveRecord& r : records) table.AddRow(LogRow(r, false, table.Columns()));
    return table;
}

void EvaluationLog::Append(const ArchiveRecord& r) {
    std::vector<std::string> row = LogRow(r, thumbnails_, header_);
    for (std::string& field : row) field = CsvField(field);
    log_.Append(row);
}

void EvaluationLog::RollBack(std::uint64_t, const std::vector<ArchiveRecord>& kept) {
    // Rebuilt from the records it describes: a run killed between its archive's append and the
    // log's leaves the log a row short, and the archive is the record of what was evaluated.
    log_ = CsvLog();
    std::error_code ec;
    fs::remove(path_, ec);
    log_ = CsvLog(path_.string(), header_);
    for (const ArchiveRecord& r : kept) Append(r);
}

}  // namespace app
