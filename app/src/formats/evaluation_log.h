// DIR/evaluations.csv: one row per evaluation (id, role, run, generation, label, shape, model,
// status, every model's outputs by the names `actuator simulate` gives them, thumbnail, design),
// appended as each is recorded; a record sink.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "formats/csv.h"
#include "formats/record_sink.h"
#include "formats/table.h"
#include "sim/model.h"
#include "sim/shape.h"

namespace app {

// A design as one line of text: a GA genome as its genes (splines ';'-separated, as --control-points
// takes them; free-xy offsets as dx,dy,... as --offsets takes them), a sine by its parameters.
std::string DesignText(const sim::Shape& shape);

// A result's one-number outputs as table cells by name (empty where it has none: NaN, or not
// ok), as every table of evaluations writes them; curves are left to the archive and JSON.
std::map<std::string, std::string> OutputCells(const sim::SimResult& result, const sim::EvalJob& job);

// The rows the log would hold for these records (ids as given, no thumbnails), for a command that
// writes its evaluations once.
Table EvaluationTable(const std::vector<ArchiveRecord>& records);

class EvaluationLog final : public RecordSink {
public:
    // `thumbnails`: whether the run pictures each evaluation (the thumbnail column names its file).
    EvaluationLog(std::filesystem::path path, bool thumbnails);
    void Append(const ArchiveRecord& record) override;
    void RollBack(std::uint64_t keep, const std::vector<ArchiveRecord>& kept) override;

private:
    std::filesystem::path path_;
    bool thumbnails_;
    std::vector<std::string> header_;
    CsvLog log_;
};

}  // namespace app
