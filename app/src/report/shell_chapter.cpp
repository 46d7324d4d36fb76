#include "report/shell_chapter.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <optional>

#include "evaluation/mesh_check.h"
#include "formats/archive.h"
#include "formats/csv.h"
#include "formats/table.h"
#include "support/errors.h"
#include "pictures/figures.h"
#include "pictures/plots.h"
#include "formats/files.h"

namespace app {
namespace {

namespace fs = std::filesystem;

std::string Cell(double value, const char* format = "{:.3g}") { return std::isfinite(value) ? fmt::format(fmt::runtime(format), value) : "-"; }

// "ok, -1.23 %" or the status.
std::string Outcome(const sim::SimResult& r) {
    if (r.status == sim::Status::Ok) return fmt::format("{:+.2f} %", r.contractionPercent);
    std::string text = sim::Name(r.status);
    if (r.status == sim::Status::LimitPoint && std::isfinite(r.shell.limitPressureKpa)) text += fmt::format(" at {:.2g} kPa", r.shell.limitPressureKpa);
    return text;
}

std::string ChangeText(const MeshChange& c) {
    if (!std::isfinite(c.points)) return "-";
    return fmt::format("{:.2f} points ({:.1f} %){}", c.points, c.relativePercent, c.within ? "" : " **");
}

// What a design's wall carries: no fibres (an isotropic study, or a fibre study's design with both
// families switched off), one family (a single helix, meridian or hoop) or a braid (both).
enum FibreClass { kNoFibres, kOneFamily, kBraid, kFibreClasses };
FibreClass ClassOf(const sim::EvalJob& job) {
    const auto* def = std::get_if<sim::ShellDef>(&job.def);
    const int on = def ? sim::FamiliesOn(def->fibres) : 0;
    return on == 2 ? kBraid : on == 1 ? kOneFamily : kNoFibres;
}
const char* const kClassNames[kFibreClasses] = {"without fibres", "with one fibre family", "with a braid"};

// What the study adds to a thesis shape beyond the shape itself: "" for an isotropic study, else its
// fibres as the job carries them (", with a braid at +/-30 deg added").
std::string FibresAdded(const sim::EvalJob& job) {
    const auto* def = std::get_if<sim::ShellDef>(&job.def);
    switch (ClassOf(job)) {
        case kBraid: return fmt::format(", with a braid at +/-{:g} deg added", def->fibres.angleDeg);
        case kOneFamily: return fmt::format(", with one fibre family at {:g} deg added", def->fibres.angleDeg);
        default: return "";
    }
}

struct ClassTally {
    int evaluated = 0, ok = 0, contracting = 0;
    std::optional<ArchiveRecord> best;  // the record of the best contraction (no meshes)
};

struct Tally {
    std::map<std::string, int> statuses;
    int evaluated = 0, contracting = 0;
    double bestContraction = NAN;
    std::optional<ArchiveRecord> best;  // the record of the best contraction (no meshes)
    ClassTally classes[kFibreClasses];
};

Tally TallyOf(const fs::path& archive) {
    Tally t;
    std::error_code ec;
    if (!fs::exists(archive, ec)) return t;
    ScanArchive(archive.string(), false, [&](ArchiveRecord&& r) {
        if (r.role == Role::Figure) return true;
        ++t.evaluated;
        ++t.statuses[sim::Name(r.result.status)];
        ClassTally& c = t.classes[ClassOf(r.job)];
        ++c.evaluated;
        if (r.result.status == sim::Status::Ok) {
            ++c.ok;
            if (r.result.contractionPercent > 0) ++t.contracting, ++c.contracting;
            if (!c.best || r.result.contractionPercent > c.best->result.contractionPercent) c.best = r;
            if (!(r.result.contractionPercent <= t.bestContraction)) {
                t.bestContraction = r.result.contractionPercent;
                t.best = std::move(r);
            }
        }
        return true;
    });
    return t;
}

// "+0.68 %; at twice the mesh +0.71 %, 4.6 % apart: converged by the 5 % rule" beside a headline number.
std::string WithMeshVerdict(double coarse, const ChapterRow& row) {
    std::string text = fmt::format("{:+.2f} %", coarse);
    const bool same = row.physical->outcome.bestJob && std::fabs(row.physical->outcome.bestFitness - coarse) < 1e-9;
    if (!same || !row.fineEvaluated) return text + " (not re-run at twice the mesh)";
    if (row.fine.status != sim::Status::Ok) return text + fmt::format(" (at twice the mesh: {}; not converged)", sim::Name(row.fine.status));
    const MeshChange c = ChangeOf(coarse, row.fine.contractionPercent);
    return text + fmt::format(" (at twice the mesh {:+.2f} %, {}: {})", row.fine.contractionPercent,
                              std::fabs(row.fine.contractionPercent) < 1 ? fmt::format("{:.2f} points apart", c.points) : fmt::format("{:.1f} % apart", c.relativePercent),
                              c.within ? "converged by the mesh rule" : "outside the mesh rule, so not yet converged");
}

std::string StatusText(const std::map<std::string, int>& statuses) {
    std::string text;
    for (const auto& [status, count] : statuses) text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + status;
    return text.empty() ? "none" : text;
}

// The muscle's characteristic curves of the best contracting fibre-reinforced design of the chapter
// (its study's model, ends and material) at a quarter, half and all of the study's pressure: what a
// muscle paper would show of it. None when no fibre design is valid or the study's load is not an
// inflation.
std::optional<ChapterCurves> BestFibreCurves(const Chapter& chapter, const fs::path& dir) {
    std::optional<ArchiveRecord> best;
    std::string experiment;
    for (const ChapterRow& row : chapter.rows) {
        if (std::get<sim::ShellDef>(row.physical->experiment.def).fibres.layout == sim::FibreLayout::None) continue;
        Tally tally = TallyOf(dir / row.physical->folder / "evaluations.capnp");
        if (tally.best && (!best || tally.best->result.contractionPercent > best->result.contractionPercent)) {
            best = std::move(tally.best);
            experiment = row.physical->experiment.id;
        }
    }
    if (!best || !CharacterizeJobError(best->job).reason.empty()) return std::nullopt;
    const double p = best->job.Shell().load.pressureKpa;
    ChapterCurves c{experiment, best->job, Characterize(best->job, {p / 4, p / 2, p}, 6, 0), "", ""};
    c.figure = chapter.folder + "/" + experiment + "_best_force_contraction.png";
    c.table = chapter.folder + "/" + experiment + "_best_characteristic.csv";
    const CharacteristicImages images = CharacteristicCurveImages(experiment + ": the best fibre-reinforced design, " + sim::Name(best->job.model) + " model",
                                                                  c.curves.pressuresKpa, c.curves.contractionPercent, c.curves.forceN,
                                                                  IdealMuscleForces(best->job, c.curves), c.curves.isometric, c.curves.free.back());
    WritePng((dir / c.figure).string(), images.forceContraction, 6);
    WriteFileAtomically((dir / c.table).string(), CharacteristicTable(c.curves).Csv());
    return c;
}

}  // namespace

Chapter CompareChapters(const std::vector<ReportEntry>& entries, const fs::path& dir, Evaluator& evaluator, bool quick) {
    const auto started = std::chrono::steady_clock::now();
    Chapter chapter;
    chapter.folder = "comparison";
    std::vector<sim::EvalJob> jobs;
    struct Slot {
        size_t row;
        bool fine;
    };
    std::vector<Slot> slots;
    for (const ReportEntry& entry : entries) {
        if (entry.experiment.compare.empty()) continue;
        ChapterRow row;
        row.physical = &entry;
        // A vacuum study is not set beside the thesis model's best: that design was bred to inflate,
        // and evacuated it folds over thousands of contact pairs for a figure no one asked for.
        if (!sim::UnderVacuum(entry.experiment.def))
            for (const ReportEntry& other : entries)
                if (other.experiment.id == entry.experiment.compare && other.experiment.compare.empty()) row.thesis = &other;
        row.statuses = TallyOf(dir / entry.folder / "evaluations.capnp").statuses;
        if (row.thesis && row.thesis->outcome.bestJob) {
            jobs.push_back(JobOf(entry.experiment, row.thesis->outcome.bestJob->shape));
            slots.push_back({chapter.rows.size(), false});
        }
        if (entry.outcome.bestJob && !(quick && sim::UnderVacuum(entry.experiment.def))) {
            jobs.push_back(RefinedJob(*entry.outcome.bestJob));
            slots.push_back({chapter.rows.size(), true});
        }
        chapter.rows.push_back(std::move(row));
    }
    if (chapter.rows.empty()) return chapter;

    std::error_code ec;
    fs::create_directories(dir / chapter.folder, ec);
    if (!fs::is_directory(dir / chapter.folder, ec)) throw UsageError("cannot create folder " + Quote((dir / chapter.folder).string()));
    auto renderer = MakeRenderer(1024, 768);
    evaluator.Evaluate(jobs, [&](size_t k, sim::SimResult&& result) {
        ChapterRow& row = chapter.rows[slots[k].row];
        const std::string id = row.physical->experiment.id;
        const std::string model = sim::Name(row.physical->experiment.model);
        if (slots[k].fine) {
            row.fine = std::move(result);
            row.fineEvaluated = true;
            return;
        }
        row.thesisBestHere = std::move(result);
        row.thesisBestJob = jobs[k];
        // A design refused before any solve (it cannot be built as a tube, or lies outside the study's
        // envelope) has no loaded wall to draw: the text gives its status.
        const sim::Status status = row.thesisBestHere.status;
        if (status == sim::Status::InvalidGeometry || status == sim::Status::OutsideEnvelope || row.thesisBestHere.initial.Size() == 0) return;
        row.thesisBestFigure = chapter.folder + "/" + id + "_thesis_best_under_" + model + ".png";
        const std::string title = fmt::format("{}: the thesis model's best shape under the {} model{}", row.thesis->experiment.id, model, FibresAdded(jobs[k]));
        WritePng((dir / row.thesisBestFigure).string(), renderer->Render(BeforeAfterScene(title, row.thesisBestHere, jobs[k])), 6);
    });

    Table table(std::vector<std::string>{"experiment", "compares", "evaluations", "statuses", "thesis_model_best_fitness", "thesis_best_status",
                              "thesis_best_contraction_percent", "best_contraction_percent", "best_contraction_percent_at_2x_mesh",
                              "mesh_change_relative_percent"});
    for (const ChapterRow& row : chapter.rows) {
        const double best = row.physical->outcome.bestFitness;
        const double fine = row.fineEvaluated && row.fine.status == sim::Status::Ok ? row.fine.contractionPercent : NAN;
        int evaluated = 0;
        for (const auto& [status, count] : row.statuses) evaluated += count;
        table.AddRow({row.physical->experiment.id, row.physical->experiment.compare, std::to_string(evaluated), StatusText(row.statuses),
                       row.thesis ? CsvNumber(row.thesis->outcome.bestFitness) : "", row.thesis ? sim::Name(row.thesisBestHere.status) : "",
                       CsvNumber(row.thesisBestHere.status == sim::Status::Ok ? row.thesisBestHere.contractionPercent : NAN), CsvNumber(best),
                       CsvNumber(fine), CsvNumber(ChangeOf(best, fine).relativePercent)});
    }
    WriteFileAtomically((dir / chapter.folder / "comparison.csv").string(), table.Csv());
    chapter.bestCurves = BestFibreCurves(chapter, dir);
    chapter.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return chapter;
}

std::string ChapterMarkdown(const Chapter& chapter, bool quick, const std::optional<SearchEvidence>& search) {
    if (chapter.rows.empty()) return "";
    const Experiment& first = chapter.rows.front().physical->experiment;
    const std::string model = sim::Name(first.model);
    const sim::ShellDef& shell = std::get<sim::ShellDef>(first.def);  // the chapter is of a shell-def model
    std::string md = fmt::format("<a id=\"physical-chapter\"></a>\n\n# Part 2: the thesis's experiments under the `{}` model\n\n", model);
    md += "Model: " + ModelDescription(first) + ". The thesis's shapes map onto the tube with one radius unit = " +
          fmt::format("{:g} mm", shell.geometry.radiusMm) +
          " (docs/models/shell.md section 1); a design whose radius reaches zero or that intersects itself is `invalid-geometry`, one past its pressure "
          "maximum `limit-point`, one stretched beyond the material's limit `over-stretched`: none of them has a fitness. The GA runs are "
          "shorter than the thesis's (see each section's settings).\n\n";
    if (quick) md += "**Quick run**: grids and GA runs are shrunk; the numbers check that everything runs.\n\n";

    md += "| experiment | designs evaluated | their statuses | thesis model's best (mesh units) | that design here | best here | best at 2x mesh | change |\n";
    md += "|---|---:|---|---:|---|---:|---:|---:|\n";
    int thesisBestsValid = 0, thesisBests = 0, thesisRows = 0;
    // Designs by what their wall carries: the isotropic studies' designs, and the fibre studies' by
    // class (braids, single families and both families off are not the same actuator).
    // Vacuum studies (a negative pressure: walls collapse onto each other) are counted apart: their
    // contraction is not an inflated actuator's.
    ClassTally isotropic, vacuum, fibreStudy[kFibreClasses];
    struct Best {
        const ChapterRow* row = nullptr;
        std::optional<ArchiveRecord> record;
    } bestIsotropic, bestWithFibres, bestVacuum;
    const auto underVacuum = [](const ChapterRow& row) { return sim::UnderVacuum(row.physical->experiment.def); };
    int meshChecked = 0, meshWithin = 0;
    for (const ChapterRow& row : chapter.rows) {
        Tally tally = TallyOf(row.physical->outcome.dir / "evaluations.capnp");
        const bool fibres = std::get<sim::ShellDef>(row.physical->experiment.def).fibres.layout != sim::FibreLayout::None;
        const bool evacuated = underVacuum(row);
        for (int k = 0; k < kFibreClasses; ++k) {
            ClassTally& into = evacuated ? vacuum : fibres ? fibreStudy[k] : isotropic;
            const ClassTally& from = tally.classes[k];
            into.evaluated += from.evaluated;
            into.ok += from.ok;
            into.contracting += from.contracting;
        }
        Best& slot = evacuated ? bestVacuum : fibres ? bestWithFibres : bestIsotropic;
        for (int k = fibres && !evacuated ? kOneFamily : kNoFibres; k < (fibres || evacuated ? kFibreClasses : kOneFamily); ++k) {
            const auto& candidate = tally.classes[k].best;
            if (candidate && (!slot.record || candidate->result.contractionPercent > slot.record->result.contractionPercent)) {
                slot.row = &row;
                slot.record = candidate;
            }
        }
        const double best = row.physical->outcome.bestFitness;
        const double fine = row.fineEvaluated && row.fine.status == sim::Status::Ok ? row.fine.contractionPercent : NAN;
        const MeshChange change = ChangeOf(best, fine);
        if (std::isfinite(change.points)) {
            ++meshChecked;
            meshWithin += change.within;
        }
        thesisRows += row.thesis != nullptr;
        if (row.thesis && row.thesis->outcome.bestJob) {
            ++thesisBests;
            thesisBestsValid += row.thesisBestHere.status == sim::Status::Ok;
        }
        md += fmt::format("| [{} {}](#{}) | {} | {} | {} | {} | {} | {} | {} |\n", row.physical->experiment.id, row.physical->experiment.title,
                          row.physical->folder, tally.evaluated, StatusText(tally.statuses),
                          row.thesis ? Cell(row.thesis->outcome.bestFitness, "{:.3f}") : std::string("-"),
                          row.thesis && row.thesis->outcome.bestJob ? Outcome(row.thesisBestHere) : std::string("-"),
                          std::isfinite(best) ? fmt::format("{:+.2f} %", best) : std::string("none valid"),
                          row.physical->outcome.bestJob ? Outcome(row.fine) : std::string("-"), ChangeText(change));
    }
    md += "\n";

    // The finding, from this run's numbers only.
    double inflatedKpa = shell.load.pressureKpa;  // the inflated studies' pressure
    for (const ChapterRow& row : chapter.rows)
        if (!underVacuum(row)) {
            inflatedKpa = std::get<sim::ShellDef>(row.physical->experiment.def).load.pressureKpa;
            break;
        }
    md += "**Finding.** ";
    md += fmt::format("Of {} designs of the isotropic studies (no fibres) evaluated under the `{}` model at {:g} kPa, {} reached equilibrium and {} "
                      "contracted", isotropic.evaluated, model, inflatedKpa, isotropic.ok, isotropic.contracting);
    if (isotropic.contracting > 0 && bestIsotropic.record)
        md += fmt::format("; the best, in experiment {}: {}.", bestIsotropic.row->physical->experiment.id,
                          WithMeshVerdict(bestIsotropic.record->result.contractionPercent, *bestIsotropic.row));
    else if (bestIsotropic.record)
        md += fmt::format(": every one that reached equilibrium lengthened; the best, in experiment {}: {}.", bestIsotropic.row->physical->experiment.id,
                          WithMeshVerdict(bestIsotropic.record->result.contractionPercent, *bestIsotropic.row));
    else
        md += ".";
    if (search) {
        md += fmt::format(" Part 3's searches aimed at contraction alone under the same model ({} runs, {} evaluations: [optimizers compared](#optimizers)) "
                          "found at best {:+.3f} % ({}, seed {}){}.", search->runs, search->evaluations, search->bestContractionPercent, search->bestLabel,
                          search->bestSeed, search->bestContractionPercent > 0 ? "" : ": none of their designs contracted either");
    }
    if (thesisRows > 0)
        md += fmt::format(" Of the thesis model's {} best designs, {} reach equilibrium here; the others are refused or fail as the table says.",
                          thesisBests, thesisBestsValid);
    else  // part 2 alone (--part physical): there is nothing of part 1's to re-evaluate
        md += " Part 1's results (the thesis model's runs) are not in this folder, so its best designs were not re-evaluated here: "
              "run `actuator reproduce` with `--part both` (the default) for that comparison.";
    if (meshChecked > 0)
        md += fmt::format(" Mesh convergence (docs/models/shell.md section 2: {}): {} of {} best designs pass{}.", kMeshRule,
                          meshWithin, meshChecked, meshWithin == meshChecked ? "" : "; the others (marked **) need a finer mesh than the default to be trusted");
    int fibreEvaluated = 0;
    for (const ClassTally& c : fibreStudy) fibreEvaluated += c.evaluated;
    if (fibreEvaluated > 0) {
        md += fmt::format("\n\n**With fibres.** The fibre studies evaluated {} designs, counted by what their wall carries:", fibreEvaluated);
        for (int k : {kBraid, kOneFamily, kNoFibres}) {
            const ClassTally& c = fibreStudy[k];
            md += fmt::format("{} {} {}{}, {} reached equilibrium and {} contracted", k == kBraid ? "" : ";", c.evaluated, kClassNames[k],
                              k == kNoFibres ? " (both families switched off)" : "", c.ok, c.contracting);
        }
        md += ".";
        auto describe = [&](const Best& b, const char* what) {
            if (!b.record) return;
            const sim::ShellOutputs& o = b.record->result.shell;
            const FibreClass fibreClass = ClassOf(b.record->job);
            md += fmt::format(" The best {} design (experiment {}{}): contraction {} at {:g} kPa, blocking force {} N, largest stretch {:.2f} (limit {:.2f})",
                              what, b.row->physical->experiment.id, fibreClass == kNoFibres ? "" : fmt::format(", {}", kClassNames[fibreClass]),
                              WithMeshVerdict(b.record->result.contractionPercent, *b.row), o.targetPressureKpa, Cell(o.blockingForceN), o.maxStretch,
                              o.stretchLimit);
            if (std::isfinite(o.fibreAngleDeg))
                md += fmt::format(", {} at {:.0f} deg to the axis at that pressure, fibre strain {:.2f} %", fibreClass == kBraid ? "braid" : "fibres", o.fibreAngleDeg,
                                  100 * o.maxFibreStrain);
            // The top's turn as the study's ends had it: free (a bench's default) or held by a torque.
            if (const auto* def = std::get_if<sim::ShellDef>(&b.record->job.def)) {
                if (def->ends.twist == sim::TwistEnd::Held) md += fmt::format(", its top held from turning by {} N mm", Cell(o.torqueNMm));
                else md += fmt::format(", its top free to turn: {:+.1f} deg", o.twistDeg);
            }
            md += ".";
        };
        describe(bestWithFibres, "fibre-reinforced");
        describe(bestIsotropic, "isotropic");
        md += "\n\n";
        if (const auto& b = chapter.bestCurves) {
            // Its curves as a muscle paper shows them: the force it pulls with against its contraction.
            const CharacteristicCurves& c = b->curves;
            md += fmt::format("Its characteristic curves (experiment {}'s best, the study's ends and material; [table]({})): ", b->experiment, b->table);
            for (size_t k = 0; k < c.pressuresKpa.size(); ++k) {
                const bool ok = c.free[k].status == sim::Status::Ok;
                md += fmt::format("{}at {:g} kPa {}", k ? "; " : "", c.pressuresKpa[k],
                                  ok ? fmt::format("{} N with the top held at its rest place, {:+.2f} % free, {} mJ per stroke",
                                                   Cell(c.forceN[k].empty() ? NAN : c.forceN[k][0]), c.free[k].contractionPercent, Cell(c.workPerStrokeMj[k]))
                                     : std::string(sim::Name(c.free[k].status)));
            }
            md += ".\n\n![" + b->experiment + " best: force against contraction](" + b->figure + ")\n\n";
        }
        for (const Best* b : {&bestWithFibres, &bestIsotropic}) {
            if (!b->row) continue;
            for (const auto& figure : b->row->physical->outcome.figures)
                if (figure == "best_inflation.png" || figure == "best_pressure_curve.png")
                    md += "![" + b->row->physical->experiment.id + " " + figure + "](" + b->row->physical->folder + "/" + figure + ")\n";
        }
    }
    if (vacuum.evaluated > 0) {
        const sim::ShellDef& evacuated = std::get<sim::ShellDef>(bestVacuum.row ? bestVacuum.row->physical->experiment.def : first.def);
        md += fmt::format("\n\n**Under vacuum.** The vacuum studies (self-contact on: collapsing walls rest a wall thickness apart) evaluated {} designs at "
                          "{:g} kPa; {} reached equilibrium and {} contracted.",
                          vacuum.evaluated, evacuated.load.pressureKpa, vacuum.ok, vacuum.contracting);
        if (bestVacuum.record) {
            const sim::ShellOutputs& o = bestVacuum.record->result.shell;
            md += fmt::format(" The best, in experiment {}: {}; its wall collapsed at {} kPa and rests on itself over {} contact pairs (smallest gap {} mm "
                              "beyond the wall's thickness, contact force {} N).",
                              bestVacuum.row->physical->experiment.id, WithMeshVerdict(bestVacuum.record->result.contractionPercent, *bestVacuum.row),
                              Cell(o.collapsePressureKpa), o.contactPairs, Cell(o.minGapMm), Cell(o.contactForceN));
            if (bestIsotropic.record)
                md += fmt::format(" Beside it, the best inflated design without fibres (experiment {}, the same tube and material at {:g} kPa): {:+.2f} %.",
                                  bestIsotropic.row->physical->experiment.id, bestIsotropic.record->result.shell.targetPressureKpa,
                                  bestIsotropic.record->result.contractionPercent);
            md += "\n\n";
            for (const auto& figure : bestVacuum.row->physical->outcome.figures)
                if (figure == "best_inflation.png" || figure == "best_pressure_curve.png")
                    md += "![" + bestVacuum.row->physical->experiment.id + " " + figure + "](" + bestVacuum.row->physical->folder + "/" + figure + ")\n";
        }
    }
    md += fmt::format("\n\nThe comparison took {:.0f} s; its numbers are in [`{}/comparison.csv`]({}/comparison.csv).\n\n", chapter.seconds,
                      chapter.folder, chapter.folder);

    for (const ChapterRow& row : chapter.rows) {
        if (!row.thesis) continue;
        md += fmt::format("### {} beside {}\n\n", row.physical->experiment.id, row.thesis->experiment.id);
        if (row.thesis->outcome.bestJob)
            md += fmt::format("The thesis model's best, {} (fitness {:.3f} mesh units), under the `{}` model{}: {}.\n\n", ShapeTitle(row.thesis->outcome.bestJob->shape),
                              row.thesis->outcome.bestFitness, model, FibresAdded(row.thesisBestJob), Outcome(row.thesisBestHere));
        for (const auto& figure : row.thesis->outcome.figures)
            if (figure == "best_inflation.png") md += "![" + row.thesis->experiment.id + " best, thesis model](" + row.thesis->folder + "/" + figure + ")\n";
        if (!row.thesisBestFigure.empty()) md += "![the same shape under the " + model + " model" + FibresAdded(row.thesisBestJob) + "](" + row.thesisBestFigure + ")\n";
        md += "\n";
    }
    return md;
}

}  // namespace app
