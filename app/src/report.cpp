#include "report.h"

#include <cmath>

#include <fmt/format.h>

namespace app {

bool MarkedlyDifferent(double ours, double thesis) {
    if (!std::isfinite(thesis)) return false;
    if (!std::isfinite(ours)) return true;
    return std::fabs(ours - thesis) > 0.05 && std::fabs(ours - thesis) > 0.1 * std::fabs(thesis);
}

namespace {

std::string Cell(double value) { return std::isfinite(value) ? fmt::format("{:.4g}", value) : "-"; }

const char* kThesisModel =
    "the `thesis` model of `shared/MODEL.md` (helical 30 x 30 mass-spring mesh, cross-product inflation, clamped ends; fitness in mesh units)";

}  // namespace

std::string ModelDescription(const Experiment& e) {
    if (e.model == sim::ModelKind::Thesis) return kThesisModel;
    const sim::ShellDef& s = e.shell;
    const sim::GeometryDef& g = s.geometry;
    return fmt::format("the `{}` model of `shared/SHELL.md` ({} at equilibrium): a tube of R = {:g} mm, L = {:g} mm, wall {:g} mm, {} ({}, "
                       "shear modulus {:.3g} kPa), {} x {} ring mesh, {} to {:g} kPa in {} steps; fitness = contraction in percent at that pressure",
                       sim::Name(e.model), e.model == sim::ModelKind::Shell ? "membrane and bending" : "membrane only", g.radiusMm, g.lengthMm,
                       g.thicknessMm, sim::Name(s.material.preset), sim::Name(s.material.law), sim::ShearModulusKpa(s.material), g.ringVertices,
                       sim::RingCount(g), sim::Name(s.load.kind), s.load.pressureKpa, s.load.steps);
}

namespace {

}  // namespace

std::string ReportMarkdown(const std::vector<ReportEntry>& entries, bool quick, double seconds, const std::string& evaluator, const std::string& chapter,
                           const std::string& closing) {
    long long simulations = 0, evaluations = 0;
    for (const auto& entry : entries) {
        simulations += entry.outcome.simulations;
        evaluations += entry.outcome.evaluations;
    }
    std::string md = entries.size() == 1 ? "# " + ExperimentTitle(entries[0].experiment) + "\n\n" : "# Reproducing the 2019 thesis with Actuator Workbench\n\n";
    if (quick)
        md += "**Quick run** (`--quick`): at most 3 values per sweep axis, one GA run of 2 generations of 6 individuals, 2,000 "
              "iterations. The numbers below check that everything runs; they are not the thesis's experiments.\n\n";
    bool allThesis = true;
    for (const auto& entry : entries) allThesis = allThesis && entry.experiment.model == sim::ModelKind::Thesis;
    md += allThesis ? std::string("Model: ") + kThesisModel + ". " : std::string("Models: as stated in each section. ");
    md += "Every experiment file is in `assets/experiments/`; its settings are copied beside its results.\n\n";
    md += "| | |\n|---|---|\n";
    md += "| experiments | " + std::to_string(entries.size()) + " |\n";
    md += "| evaluations | " + std::to_string(evaluations) + " (archived) |\n";
    // Timing lines: this session's, so a resumed run states what it did (tests skip them).
    md += fmt::format("| wall time | {:.1f} s ({:.1f} min), this session |\n", seconds, seconds / 60);
    md += fmt::format("| throughput | {} simulations, {:.1f} evaluations/s on {}, figures included, this session |\n\n", simulations,
                      seconds > 0 ? simulations / seconds : 0, evaluator);
    md += "## Contents\n\n";
    bool chapterListed = false;
    for (const auto& entry : entries) {
        if (!chapter.empty() && !entry.experiment.compare.empty() && !chapterListed) {
            md += "- [Part 2: under a physical model](#physical-chapter)\n";
            chapterListed = true;
        }
        md += "- [" + entry.experiment.id + " " + entry.experiment.title + "](#" + entry.folder + ")\n";
    }
    if (!closing.empty()) md += "- [Part 3: optimizers compared](#optimizers)\n";
    md += "\n";

    bool chapterWritten = false;
    for (const auto& entry : entries) {
        const Experiment& e = entry.experiment;
        if (!chapter.empty() && !e.compare.empty() && !chapterWritten) {
            md += chapter;
            chapterWritten = true;
        }
        const ExperimentOutcome& o = entry.outcome;
        md += "<a id=\"" + entry.folder + "\"></a>\n\n## " + e.id + " " + e.title + "\n\n";
        if (!e.thesis.empty()) md += "Thesis: " + e.thesis + ".\n\n";
        if (!allThesis) md += "Model: " + ModelDescription(e) + ".\n\n";
        if (!e.note.empty()) md += "Settings: " + e.note + "\n\n";
        md += fmt::format("Results in [`{0}/`]({0}/): {1} evaluations.\n", entry.folder, o.evaluations);
        md += fmt::format("This session: {} simulations in {:.1f} s.\n\n", o.simulations, o.seconds);
        if (!o.rows.empty()) {
            md += "| | ours | thesis | difference |\n|---|---:|---:|---:|\n";
            for (const auto& row : o.rows)
                md += "| " + row.quantity + " | " + Cell(row.ours) + " | " + Cell(row.thesis) + " | " +
                      (std::isfinite(row.ours) && std::isfinite(row.thesis) ? fmt::format("{:+.3g}", row.ours - row.thesis) : std::string("-")) +
                      (MarkedlyDifferent(row.ours, row.thesis) ? " **" : "") + " |\n";
            md += "\n";
        }
        for (const auto& line : o.details) md += "- " + line + "\n";
        if (!o.details.empty()) md += "\n";
        bool differs = false;
        for (const auto& row : o.rows) differs = differs || MarkedlyDifferent(row.ours, row.thesis);
        if (differs && quick)
            md += "Differences here come from the quick run's reduced grids and generations.\n\n";
        else if (differs)
            md += "**Why the numbers differ** (rows marked **): " +
                  (e.explanation.empty() ? std::string("no explanation recorded for this experiment.") : e.explanation) + "\n\n";
        for (const auto& figure : o.figures) md += "![" + e.id + " " + figure + "](" + entry.folder + "/" + figure + ")\n\n";
    }
    return md + closing;
}

}  // namespace app
