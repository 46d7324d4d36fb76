// The reproduce command's second chapter: the thesis's experiments re-run under a physical model
// (experiment files with "compare": "<thesis id>"), set beside the thesis model's results. For each
// pair: how the designs fared (statuses), the thesis model's best design evaluated under the
// physical model, the physical model's own best, and that best meshed twice as finely in both
// directions (the mesh-convergence study of docs/models/shell.md section 2). The finding is stated from the
// numbers, whatever they are.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <optional>

#include "evaluation/characterize.h"
#include "evaluation/evaluator.h"
#include "report/report.h"

namespace app {

struct ChapterRow {
    const ReportEntry* physical = nullptr;  // the re-run
    const ReportEntry* thesis = nullptr;    // its thesis-model experiment (null when not run)
    std::map<std::string, int> statuses;    // of the re-run's evaluations, by status name
    sim::SimResult thesisBestHere;          // the thesis model's best design under the physical model
    sim::EvalJob thesisBestJob;             // and its job (the study's model, load and fibres)
    sim::SimResult fine;                    // the re-run's best at twice the mesh in both directions
    bool fineEvaluated = false;             // false when there was no best to re-run
    std::string thesisBestFigure, bestFigure;  // pictures under `folder`, relative to the report
};

// The best fibre-reinforced design's characteristic curves, as `actuator characterize` gives them.
struct ChapterCurves {
    std::string experiment;         // where the design comes from
    sim::EvalJob job;               // its evaluation under the study's model, ends and load
    CharacteristicCurves curves;
    std::string figure, table;      // force_contraction picture and characteristic table, relative to the report
};

struct Chapter {
    std::vector<ChapterRow> rows;
    std::string folder;  // relative to the report: pictures and comparison.csv
    std::optional<ChapterCurves> bestCurves;  // none without a valid fibre-reinforced design
    double seconds = 0;
};

// Evaluates the comparisons on `evaluator`, draws the side-by-side pictures and writes
// `dir / folder / comparison.csv`. `entries` holds both chapters' experiments. A quick run does not
// re-run vacuum studies' best designs at twice the mesh: a collapsed design there costs more than
// the rest of the quick run (25 of its 67 s); the text says it was not re-run.
Chapter CompareChapters(const std::vector<ReportEntry>& entries, const std::filesystem::path& dir, Evaluator& evaluator, bool quick = false);

// What part 3's searches under the chapter's model found: the finding cites it beside the studies'.
struct SearchEvidence {
    int runs = 0;
    long long evaluations = 0;
    double bestContractionPercent = NAN;
    std::string bestLabel;  // the contender that found it
    int bestSeed = 0;
};

// The chapter as markdown: a table, the mesh study, the finding (with part 3's search when given),
// the pictures.
std::string ChapterMarkdown(const Chapter& chapter, bool quick, const std::optional<SearchEvidence>& search = std::nullopt);

}  // namespace app
