// A sweep: every point of a 1-D or 2-D grid of sine parameters (thesis chapter 4), then the designs
// the thesis names in its tables, then the figures. Resumable: grid points are archived in order, so
// a resume continues after the last archived one and redoes only what follows the grid.
#include <algorithm>
#include <map>
#include <fmt/format.h>

#include "formats/csv.h"
#include "formats/evaluation_log.h"
#include "formats/table.h"
#include "support/errors.h"
#include "experiments/experiment_runner.h"
#include "formats/files.h"
#include "pictures/plots.h"
#include "support/progress.h"
#include "experiments/thesis_check.h"

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
        if (axis.parameter == sim::SweepParameter::PressureKpa) title += fmt::format(",  {:.4g} kPa", job.Shell().load.pressureKpa);
        else if (axis.parameter == sim::SweepParameter::FibreAngleDeg) title += fmt::format(",  fibres at {:.4g} deg", job.Shell().fibres.angleDeg);
    return title;
}

// At most this many cells on a contact sheet: a 100,000-point sweep shows an even subsample.
constexpr size_t kMaxSheetCells = 400;

// The best rows' reasons, from the thesis's own best point evaluated here (`atPoint`, in the order of
// the thesis's points): does the model give the thesis's number there, and how far below our best
// does that point lie?
void ExplainBest(RunContext& c, const std::vector<EvaluationTag>& pointTags, const std::vector<double>& atPoint, double ours) {
    const ThesisResult& t = c.e.thesisResult;
    size_t k = 0;
    while (k < t.points.size() && t.points[k].fitness != t.bestFitness) ++k;
    if (k == t.points.size()) return;
    const std::string where = pointTags[k].label.substr(14);
    const double there = atPoint[k], tolerance = DefaultTolerance(t.bestFitness);
    const bool modelAgrees = WithinTolerance(there, t.bestFitness, tolerance);
    const double flatTolerance = DefaultTolerance(ours);
    const bool flat = WithinTolerance(there, ours, flatTolerance);
    for (ComparisonRow& row : c.outcome.rows) {
        if (row.quantity == "best fitness") {
            row.explained = modelAgrees;
            row.why = modelAgrees ? fmt::format("at the thesis's best point ({}) this model's value: {}; the model agrees there, and our grid's best ({}) lies elsewhere",
                                                where, CompareSentence(there, t.bestFitness, tolerance), OrderSentence(ours, t.bestFitness))
                                  : fmt::format("at the thesis's best point ({}) this model's value: {}; the model does not give the thesis's number there",
                                                where, CompareSentence(there, t.bestFitness, tolerance));
        } else if (row.quantity.rfind("best ", 0) == 0) {
            row.explained = flat;
            row.why = flat ? fmt::format("the landscape is flat near its top: at the thesis's best point ({}) ours, {}, our best", where,
                                         CompareSentence(there, ours, flatTolerance))
                           : fmt::format("at the thesis's best point ({}) ours, {}, our best: the top is not flat enough to move", where,
                                         CompareSentence(there, ours, flatTolerance));
        }
    }
}

// The thesis's words on the landscape's shape (ThesisResult::claims), each a row: how many of the
// relations it states hold on this grid.
void AddLandscapeClaimRows(RunContext& c, const std::vector<sim::EvalJob>& grid, const std::vector<double>& fitness, const std::vector<sim::Status>& status) {
    using Kind = ThesisResult::LandscapeClaim::Kind;
    const auto& axes = c.e.sweep.axes;
    auto has = [&](sim::SweepParameter p) { return std::any_of(axes.begin(), axes.end(), [&](const auto& a) { return a.parameter == p; }); };
    // Each cycle count's landscape along amplitude: (amplitude, fitness; NaN when the point failed).
    std::map<double, std::vector<std::pair<double, double>>> byCycles;
    if (has(sim::SweepParameter::Cycles) && has(sim::SweepParameter::Amplitude))
        for (size_t j = 0; j < grid.size(); ++j)
            byCycles[sim::SweepValue(grid[j], sim::SweepParameter::Cycles)].push_back(
                {sim::SweepValue(grid[j], sim::SweepParameter::Amplitude), status[j] == sim::Status::Ok ? fitness[j] : NAN});
    for (auto& [cycles, line] : byCycles) std::sort(line.begin(), line.end());
    auto cyclesName = [](double cycles) { return fmt::format("{:g} cycles", cycles); };

    for (const auto& claim : c.e.thesisResult.claims) {
        switch (claim.kind) {
            case Kind::Peaks: {
                if (axes.size() != 1) break;
                std::vector<double> line;  // the successful points in grid order
                for (size_t j = 0; j < grid.size(); ++j)
                    if (status[j] == sim::Status::Ok) line.push_back(fitness[j]);
                int peaks = 0;
                for (size_t k = 0; k < line.size(); ++k)
                    peaks += (k == 0 || line[k] > line[k - 1]) && (k + 1 == line.size() || line[k] > line[k + 1]) && line.size() > 1;
                ComparisonRow row{"peaks of the landscape", static_cast<double>(peaks), static_cast<double>(claim.count)};
                if (peaks != claim.count) row.why = fmt::format("the landscape has {} local maxima over {} successful points", peaks, line.size());
                c.outcome.rows.push_back(row);
                break;
            }
            case Kind::RisesWith: {
                if (byCycles.empty()) break;
                int rising = 0;
                std::string why;
                for (const auto& [cycles, line] : byCycles) {
                    size_t k = 1;
                    while (k < line.size() && line[k].second > line[k - 1].second) ++k;
                    if (k == line.size()) {
                        ++rising;
                    } else {
                        why += (why.empty() ? "" : "; ") + (std::isfinite(line[k].second) && std::isfinite(line[k - 1].second)
                                                               ? fmt::format("{} falls from {:.4g} at amplitude {:.3g} to {:.4g} at {:.3g}", cyclesName(cycles),
                                                                             line[k - 1].second, line[k - 1].first, line[k].second, line[k].first)
                                                               : fmt::format("{} has a failed point near amplitude {:.3g}", cyclesName(cycles), line[k].first));
                    }
                }
                ComparisonRow row{"cycle counts whose fitness rises with amplitude", static_cast<double>(rising), static_cast<double>(byCycles.size())};
                row.why = why;
                c.outcome.rows.push_back(row);
                break;
            }
            case Kind::CyclesOrder: {
                if (byCycles.empty()) break;
                auto bestOf = [&](double cycles) {
                    double best = NAN;
                    if (byCycles.count(cycles))
                        for (const auto& [amplitude, f] : byCycles.at(cycles))
                            if (std::isfinite(f) && !(f <= best)) best = f;
                    return best;
                };
                std::vector<OrderPair> pairs;
                for (size_t i = 0; i < claim.ranks.size(); ++i)
                    for (size_t j = i + 1; j < claim.ranks.size(); ++j)
                        for (double a : claim.ranks[i])
                            for (double b : claim.ranks[j]) {
                                OrderPair p{cyclesName(a), cyclesName(b), bestOf(a), bestOf(b)};
                                const bool nearly = std::find(claim.nearly.begin(), claim.nearly.end(), std::make_pair(a, b)) != claim.nearly.end();
                                p.relation = nearly ? Relation::NearlyAbove : Relation::Above;
                                p.tolerance = DefaultTolerance(p.oursFirst) + DefaultTolerance(p.oursSecond);
                                pairs.push_back(std::move(p));
                            }
                c.outcome.rows.push_back(OrderRow("cycle counts in the thesis's order", pairs));
                break;
            }
            case Kind::NegativeCycles: {
                if (byCycles.empty()) break;
                int agree = 0;
                std::string why;
                for (const auto& [cycles, line] : byCycles) {
                    const auto lowest = std::min_element(line.begin(), line.end(), [](const auto& a, const auto& b) {
                        return std::isfinite(a.second) && (!std::isfinite(b.second) || a.second < b.second);
                    });
                    const bool negative = lowest != line.end() && std::isfinite(lowest->second) && lowest->second < 0;
                    const bool claimed = std::find(claim.cycles.begin(), claim.cycles.end(), cycles) != claim.cycles.end();
                    if (negative == claimed) {
                        ++agree;
                        continue;
                    }
                    why += (why.empty() ? "" : "; ") +
                           (negative ? fmt::format("{} goes negative here ({:.4g} at amplitude {:.3g}), not in the thesis", cyclesName(cycles), lowest->second, lowest->first)
                                     : fmt::format("{} stays positive here (lowest {:.4g}), negative in the thesis", cyclesName(cycles),
                                                   lowest != line.end() ? lowest->second : NAN));
                }
                ComparisonRow row{"cycle counts negative as the thesis says", static_cast<double>(agree), static_cast<double>(byCycles.size())};
                row.why = why;
                c.outcome.rows.push_back(row);
                break;
            }
        }
    }
}

}  // namespace

void RunSweep(RunContext& c) {
    const Experiment& e = c.e;
    const std::vector<sim::EvalJob> grid = sim::SweepJobs(e.sweep, JobOf(e, e.sweep.base));
    const size_t n = grid.size();
    const auto& axes = e.sweep.axes;

    // Resume after the grid points already archived; what follows the grid is redone.
    std::vector<double> fitness(n, NAN);
    std::vector<sim::Status> status(n, sim::Status::Ok);
    std::vector<std::map<std::string, std::string>> cells(n);  // each point's outputs, by name
    std::vector<std::string> warning(n);                       // EscapeWarning: a mesh that left its own size
    size_t done = 0;
    for (const ArchiveRecord& r : c.recorder.Existing()) {
        if (done >= n || r.role != Role::Grid || r.id != done) break;
        fitness[done] = r.result.fitness;
        status[done] = r.result.status;
        ++done;
    }
    if (c.options.resume) c.recorder.RollBack(done);
    // The resumed points' outputs and warnings need their whole records, which the archive's index leaves out.
    c.recorder.ForEachRecord(0, done, [&](ArchiveRecord&& r) {
        cells[r.id] = OutputCells(r.result, r.job);
        warning[r.id] = EscapeWarning(r.result);
    });

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
        status[j] = r.status;
        cells[j] = OutputCells(r, grid[j]);
        warning[j] = EscapeWarning(r);
        if (r.status == sim::Status::Ok && !(r.fitness <= bestSoFar)) bestSoFar = r.fitness;
        progress.Update(static_cast<long long>(j + 1), static_cast<long long>(n), static_cast<long long>(k + 1),
                        fmt::format("best so far {:.4f}, grid points", bestSoFar));
    });

    std::vector<std::string> header{"evaluation"};
    for (const auto& axis : axes) header.push_back(sim::Name(axis.parameter));
    header.push_back("status");
    // An output that is an axis's setting (the target pressure_kpa) is its axis's column.
    std::vector<std::string> outputs = sim::OutputNames(grid, false);
    for (const auto& axis : axes) std::erase(outputs, std::string(sim::Name(axis.parameter)));
    header.insert(header.end(), outputs.begin(), outputs.end());
    header.push_back("warning");
    Table table(header);
    int best = -1;
    for (size_t j = 0; j < n; ++j) {
        std::vector<std::string> row{std::to_string(j)};
        for (const auto& axis : axes) row.push_back(CsvNumber(sim::SweepValue(grid[j], axis.parameter)));
        const bool ok = status[j] == sim::Status::Ok;
        row.push_back(sim::Name(status[j]));
        for (const std::string& name : outputs) row.push_back(cells[j][name]);
        row.push_back(warning[j]);
        table.AddRow(row);
        if (ok && (best < 0 || fitness[j] > fitness[static_cast<size_t>(best)])) best = static_cast<int>(j);
    }
    WriteFileAtomically((c.dir / "results.csv").string(), table.Csv());

    std::string bestText = "no grid point evaluated successfully";
    if (best >= 0) {
        bestText = "best: ";
        for (size_t a = 0; a < axes.size(); ++a)
            bestText += fmt::format("{}{} {:.4g}", a ? ", " : "", sim::Name(axes[a].parameter), sim::SweepValue(grid[best], axes[a].parameter));
        bestText += fmt::format(",  fitness {:.4f}", fitness[static_cast<size_t>(best)]);
        c.outcome.rows.push_back({"best fitness", fitness[static_cast<size_t>(best)], e.thesisResult.bestFitness});
        c.outcome.bestJob = grid[static_cast<size_t>(best)];
        c.outcome.bestFitness = fitness[static_cast<size_t>(best)];
        c.outcome.bestBlockingForceN = c.recorder.ReadBack({static_cast<std::uint64_t>(best)}).at(0).result.shell.blockingForceN;
        for (const auto& axis : axes) {
            double thesis = NAN;
            for (const auto& [parameter, value] : e.thesisResult.best)
                if (parameter == axis.parameter) thesis = value;
            c.outcome.rows.push_back({std::string("best ") + sim::Name(axis.parameter), sim::SweepValue(grid[best], axis.parameter), thesis});
        }
    }

    // Designs the thesis names in a table (e.g. Table 4.4), evaluated as it states them.
    std::vector<sim::SimResult> pointResults;
    std::vector<sim::EvalJob> pointJobs;
    std::vector<std::string> pointNames;
    if (!e.thesisResult.points.empty()) {
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
            pointNames.push_back(fmt::format("{} (thesis {:g})", name, point.fitness));  // listed above the picture; cells say "design k"
        }
        std::vector<double> atPoint(pointJobs.size(), NAN);
        pointResults.resize(pointJobs.size());
        c.recorder.Evaluate(pointJobs, pointTags, [&](std::uint64_t, size_t k, sim::SimResult&& r) {
            atPoint[k] = r.status == sim::Status::Ok ? r.fitness : NAN;
            pointResults[k] = r;
            c.outcome.rows.push_back({"fitness at " + pointTags[k].label.substr(14), atPoint[k], e.thesisResult.points[k].fitness});
        });
        if (best >= 0) ExplainBest(c, pointTags, atPoint, fitness[static_cast<size_t>(best)]);
    }
    if (best >= 0 && axes.size() == 1 && axes[0].parameter == sim::SweepParameter::Amplitude) {
        // Where the landscape turns negative past its peak (Figure 4.1's "after the amplitude reaches 7").
        double firstNegative = NAN;
        for (size_t j = static_cast<size_t>(best) + 1; j < n && std::isnan(firstNegative); ++j)
            if (status[j] == sim::Status::Ok && fitness[j] < 0) firstNegative = sim::SweepValue(grid[j], axes[0].parameter);
        c.outcome.rows.push_back({"first negative amplitude", firstNegative, NAN});
    }
    AddLandscapeClaimRows(c, grid, fitness, status);

    if (!e.render.figures) return;
    WritePng((c.dir / "landscape.png").string(), LandscapeImage(PlotContextOf(e), fitness, best, bestText), 6);
    c.outcome.figures.push_back("landscape.png");

    // The designs the thesis names, before and after (Figure 4.6 for Table 4.4's three).
    if (!pointResults.empty()) {
        std::vector<DesignPair> pairs;
        std::vector<std::string> lines{"each design the thesis names, evaluated here:"};
        for (size_t k = 0; k < pointResults.size(); ++k) {
            pairs.push_back({&pointResults[k], &pointJobs[k], fmt::format("design {}", k + 1)});
            lines.push_back(fmt::format("design {}: {}", k + 1, pointNames[k]));
        }
        WritePng((c.dir / "thesis_points.png").string(),
                 PairsImage(PairsScene(ExperimentTitle(e) + "  -  the thesis's designs", lines, pairs, std::min<int>(3, static_cast<int>(pairs.size())))),
                 6);
        c.outcome.figures.push_back("thesis_points.png");
    }

    // Every grid point's inflated mesh (an even subsample of large grids), read back from the archive.
    const size_t step = (n + kMaxSheetCells - 1) / kMaxSheetCells;
    std::vector<std::uint64_t> ids;
    for (size_t j = 0; j < n; j += step) ids.push_back(j);
    const std::vector<ArchiveRecord> records = c.recorder.ReadBack(ids);
    std::vector<SheetEntry> entries;
    SheetAxes sheetAxes;
    if (axes.size() == 2 && step == 1) {
        // On the sweep's axes: the shorter axis down the rows, the longer across; cells say the fitness.
        const size_t n1 = axes[1].values.size();
        const size_t across = axes[0].values.size() >= n1 ? 0 : 1, down = 1 - across;
        for (size_t r = 0; r < axes[down].values.size(); ++r)
            for (size_t k = 0; k < axes[across].values.size(); ++k) {
                const ArchiveRecord& record = records[across == 0 ? k * n1 + r : r * n1 + k];
                entries.push_back({&record.result, FitnessCaption(record.result)});
            }
        sheetAxes.columns = static_cast<int>(axes[across].values.size());
        for (double v : axes[across].values) sheetAxes.columnLabels.push_back(fmt::format("{:.3g}", v));
        for (double v : axes[down].values) sheetAxes.rowLabels.push_back(fmt::format("{:.3g}", v));
        sheetAxes.columnTitle = AxisLabel(axes[across].parameter);
        sheetAxes.rowTitle = sim::Name(axes[down].parameter);
    } else {
        for (const ArchiveRecord& r : records) entries.push_back({&r.result, PointLabel(grid[r.id], axes, false) + ": " + FitnessCaption(r.result)});
    }
    std::string key;  // what a caption says, when the cells are not on labelled axes
    if (sheetAxes.columns == 0) {
        for (const auto& axis : axes) key += (key.empty() ? "" : " ") + std::string(sim::Name(axis.parameter));
        key = "  (each cell: " + key + ": fitness)";
    }
    std::unique_ptr<render::MeshRenderer> sheetRenderer;
    const char* loaded = sim::UnderVacuum(grid.front().def) ? "evacuated" : "inflated";
    WriteContactSheet(c.dir / "contact_sheet.png",
                      ExperimentTitle(e) + (step > 1 ? fmt::format("  -  every {}th grid point, {}", step, loaded) : fmt::format("  -  every grid point, {}", loaded)) + key,
                      entries, grid.front(), sheetRenderer, sheetAxes);
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
