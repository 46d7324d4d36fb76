// A sweep: every point of a 1-D or 2-D grid of sine parameters (thesis chapter 4), then the designs
// the thesis names in its tables, then the figures. Resumable: grid points are archived in order, so
// a resume continues after the last archived one and redoes only what follows the grid.
#include <fmt/format.h>

#include "csv.h"
#include "errors.h"
#include "experiment_runner.h"
#include "files.h"
#include "plots.h"
#include "progress.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// A grid point's parameters, e.g. "amplitude=3.48 cycles=6" (names) or "3.48 6" (values only).
std::string PointLabel(const sim::EvalJob& job, const std::vector<sim::SweepAxis>& axes, bool withNames) {
    std::string label;
    for (const auto& axis : axes)
        label += (label.empty() ? "" : " ") + (withNames ? std::string(sim::Name(axis.parameter)) + "=" : std::string()) +
                 fmt::format("{:.4g}", sim::SweepValue(job, axis.parameter));
    return label;
}

// The design's title, with the pressure when the sweep varies it.
std::string PointTitle(const sim::EvalJob& job, const std::vector<sim::SweepAxis>& axes) {
    std::string title = ShapeTitle(job.shape);
    for (const auto& axis : axes)
        if (axis.parameter == sim::SweepParameter::PressureKpa) title += fmt::format(",  {:.4g} kPa", job.shell.load.pressureKpa);
        else if (axis.parameter == sim::SweepParameter::FibreAngleDeg) title += fmt::format(",  fibres at {:.4g} deg", job.shell.fibres.angleDeg);
    return title;
}

// At most this many cells on a contact sheet: a 100,000-point sweep shows an even subsample.
constexpr size_t kMaxSheetCells = 400;

}  // namespace

void RunSweep(RunContext& c) {
    const Experiment& e = c.e;
    const std::vector<sim::EvalJob> grid = sim::SweepJobs(e.sweep, JobOf(e, e.sweep.base));
    const size_t n = grid.size();
    const auto& axes = e.sweep.axes;

    // Resume after the grid points already archived; what follows the grid is redone.
    std::vector<double> fitness(n, NAN), contraction(n, NAN);
    std::vector<sim::Status> status(n, sim::Status::Ok);
    std::vector<int> iterations(n, 0);
    size_t done = 0;
    for (const ArchiveRecord& r : c.recorder.Existing()) {
        if (done >= n || r.role != Role::Grid || r.id != done) break;
        fitness[done] = r.result.fitness;
        contraction[done] = r.result.contractionPercent;
        status[done] = r.result.status;
        iterations[done] = r.result.iterationsRun;
        ++done;
    }
    if (c.options.resume) c.recorder.RollBack(done);

    Progress progress("sweep " + ExperimentTitle(e), c.options.progress);
    double bestSoFar = NAN;
    for (size_t j = 0; j < done; ++j)
        if (status[j] == sim::Status::Ok && !(fitness[j] <= bestSoFar)) bestSoFar = fitness[j];
    std::vector<sim::EvalJob> jobs;
    std::vector<EvaluationTag> tags;
    for (size_t j = done; j < n; ++j) {
        jobs.push_back(grid[j]);
        tags.push_back({Role::Grid, 0, -1, PointLabel(grid[j], axes, true)});
    }
    c.recorder.Evaluate(jobs, tags, [&](std::uint64_t, size_t k, sim::SimResult&& r) {
        const size_t j = done + k;
        fitness[j] = r.status == sim::Status::Ok ? r.fitness : NAN;
        contraction[j] = r.contractionPercent;
        status[j] = r.status;
        iterations[j] = r.iterationsRun;
        if (r.status == sim::Status::Ok && !(r.fitness <= bestSoFar)) bestSoFar = r.fitness;
        progress.Update(static_cast<long long>(j + 1), static_cast<long long>(n), static_cast<long long>(k + 1),
                        fmt::format("best so far {:.4f}, grid points", bestSoFar));
    });

    std::vector<std::string> header{"evaluation"};
    for (const auto& axis : axes) header.push_back(sim::Name(axis.parameter));
    for (const char* h : {"fitness", "contraction_percent", "status", "iterations"}) header.push_back(h);
    std::string csv = CsvRow(header);
    int best = -1;
    for (size_t j = 0; j < n; ++j) {
        std::vector<std::string> row{std::to_string(j)};
        for (const auto& axis : axes) row.push_back(CsvNumber(sim::SweepValue(grid[j], axis.parameter)));
        const bool ok = status[j] == sim::Status::Ok;
        row.insert(row.end(), {ok ? CsvNumber(fitness[j]) : "", ok ? CsvNumber(contraction[j]) : "", sim::Name(status[j]), std::to_string(iterations[j])});
        csv += CsvRow(row);
        if (ok && (best < 0 || fitness[j] > fitness[static_cast<size_t>(best)])) best = static_cast<int>(j);
    }
    WriteFileAtomically((c.dir / "results.csv").string(), csv);

    std::string bestText = "no grid point evaluated successfully";
    if (best >= 0) {
        bestText = "best: ";
        for (size_t a = 0; a < axes.size(); ++a)
            bestText += fmt::format("{}{} {:.4g}", a ? ", " : "", sim::Name(axes[a].parameter), sim::SweepValue(grid[best], axes[a].parameter));
        bestText += fmt::format(",  fitness {:.4f}", fitness[static_cast<size_t>(best)]);
        c.outcome.rows.push_back({"best fitness", fitness[static_cast<size_t>(best)], e.thesisResult.bestFitness});
        c.outcome.bestJob = grid[static_cast<size_t>(best)];
        c.outcome.bestFitness = fitness[static_cast<size_t>(best)];
        for (const auto& axis : axes) {
            double thesis = NAN;
            for (const auto& [parameter, value] : e.thesisResult.best)
                if (parameter == axis.parameter) thesis = value;
            c.outcome.rows.push_back({std::string("best ") + sim::Name(axis.parameter), sim::SweepValue(grid[best], axis.parameter), thesis});
        }
    }

    // Designs the thesis names in a table (e.g. Table 4.4), evaluated as it states them.
    if (!e.thesisResult.points.empty()) {
        std::vector<sim::EvalJob> pointJobs;
        std::vector<EvaluationTag> pointTags;
        for (const auto& point : e.thesisResult.points) {
            sim::EvalJob job = JobOf(e, e.sweep.base);
            std::string name;
            for (const auto& [parameter, value] : point.at) {
                job = sim::WithSweepValue(job, parameter, value);
                name += fmt::format("{}{} {:g}", name.empty() ? "" : ", ", sim::Name(parameter), value);
            }
            pointJobs.push_back(job);
            pointTags.push_back({Role::ThesisPoint, 0, -1, "thesis table: " + name});
        }
        c.recorder.Evaluate(pointJobs, pointTags, [&](std::uint64_t, size_t k, sim::SimResult&& r) {
            c.outcome.rows.push_back({"fitness at " + pointTags[k].label.substr(14), r.status == sim::Status::Ok ? r.fitness : NAN,
                                      e.thesisResult.points[k].fitness});
        });
    }

    if (!e.render.figures) return;
    WritePng((c.dir / "landscape.png").string(), LandscapeImage(e, fitness, best, bestText), 6);
    c.outcome.figures.push_back("landscape.png");

    // Every grid point's inflated mesh (an even subsample of large grids), read back from the archive.
    const size_t step = (n + kMaxSheetCells - 1) / kMaxSheetCells;
    std::vector<std::uint64_t> ids;
    for (size_t j = 0; j < n; j += step) ids.push_back(j);
    const std::vector<ArchiveRecord> records = c.recorder.ReadBack(ids);
    std::vector<SheetEntry> entries;
    for (const ArchiveRecord& r : records)
        entries.push_back({&r.result, PointLabel(grid[r.id], axes, false) + ": " + FitnessCaption(r.result)});
    std::unique_ptr<render::MeshRenderer> sheetRenderer;
    WriteContactSheet(c.dir / "contact_sheet.png",
                      ExperimentTitle(e) + (step > 1 ? fmt::format("  -  every {}th grid point, inflated", step) : std::string("  -  every grid point, inflated")),
                      entries, grid.front(), sheetRenderer);
    c.outcome.figures.push_back("contact_sheet.png");

    if (best >= 0) {
        const int frames = e.render.turntable == TurntablePlan::None ? 0 : e.render.turntableFrames;
        const ArchiveRecord bestRecord = c.recorder.ReadBack({static_cast<std::uint64_t>(best)}).at(0);
        WriteBestFigures(c, c.dir, grid[best], bestRecord.result, PointTitle(grid[best], axes), frames, true);
    }
    if (e.render.turntable == TurntablePlan::All) {
        // Every grid point turning: heavy, so only on request. Read back first: the figures append
        // stretch tests to the archive being read.
        std::vector<ArchiveRecord> records;
        c.recorder.ForEachRecord(0, n, [&](ArchiveRecord&& r) { records.push_back(std::move(r)); });
        for (const ArchiveRecord& r : records) {
            const fs::path folder = c.dir / fmt::format("point_{:06}", r.id);
            std::error_code ec;
            fs::create_directories(folder, ec);
            WriteBestFigures(c, folder, grid[r.id], r.result, PointTitle(grid[r.id], axes), e.render.turntableFrames, false);
        }
    }
}

}  // namespace app
