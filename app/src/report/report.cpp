#include "report/report.h"

#include <cmath>

#include <fmt/format.h>

#include <algorithm>

#include "experiments/thesis_check.h"

namespace app {

bool RowDiffers(const Experiment& e, const ComparisonRow& row) {
    if (!std::isfinite(row.thesis)) return false;
    if (!std::isfinite(row.ours)) return true;
    for (const ThesisItem& item : e.thesisItems)
        if (item.settings.empty() && item.quantity == row.quantity && !std::isfinite(item.thesis)) {
            if (item.atLeast) return row.ours < row.thesis;
            return !WithinTolerance(row.ours, row.thesis, std::isfinite(item.tolerance) ? item.tolerance : DefaultTolerance(row.thesis));
        }
    return !WithinTolerance(row.ours, row.thesis, DefaultTolerance(row.thesis));
}

namespace {

std::string Cell(double value) { return std::isfinite(value) ? fmt::format("{:.4g}", value) : "-"; }

const char* kThesisModel =
    "the `thesis` model of `docs/models/thesis.md` (helical 30 x 30 mass-spring mesh, cross-product inflation, clamped ends; fitness in mesh units)";

}  // namespace

namespace {

// [SECTION] Each def described (a new def adds its overload).
std::string DescriptionOf(sim::ModelKind, const sim::ThesisDef&) { return kThesisModel; }
std::string DescriptionOf(sim::ModelKind model, const sim::ShellDef& s) {
    const sim::GeometryDef& g = s.geometry;
    return fmt::format("the `{}` model of `docs/models/shell.md` ({} at equilibrium): a tube of R = {:g} mm, L = {:g} mm, wall {:g} mm, {} ({}, "
                       "shear modulus {:.3g} kPa), {} x {} ring mesh, {} to {:g} kPa in {} steps; fitness = contraction in percent at that pressure",
                       sim::Name(model), model == sim::ModelKind::Shell ? "membrane and bending" : "membrane only", g.radiusMm, g.lengthMm,
                       g.thicknessMm, sim::Name(s.material.preset), sim::Name(s.material.law), sim::ShearModulusKpa(s.material), g.ringVertices,
                       sim::RingCount(g), sim::Name(s.load.kind), s.load.pressureKpa, s.load.steps);
}

}  // namespace

std::string ModelDescription(const Experiment& e) {
    return std::visit([&](const auto& def) { return DescriptionOf(e.model, def); }, e.def);
}

namespace {

std::string Signed(double v) { return std::isfinite(v) ? fmt::format("{:+.3g}", v) : std::string("-"); }

// A GA experiment's mean best fitness over its runs: the thesis's (from its table) and ours (NaN
// when no run produced one).
struct MeanBest {
    const ReportEntry* entry;
    double thesis = NAN, ours = NAN;
};
std::vector<MeanBest> MeanBests(const std::vector<ReportEntry>& entries) {
    std::vector<MeanBest> means;
    for (const auto& entry : entries) {
        const ThesisResult& t = entry.experiment.thesisResult;
        if (entry.experiment.model != sim::ModelKind::Thesis || t.runBest.empty()) continue;
        MeanBest m{&entry};
        m.thesis = 0;
        for (double v : t.runBest) m.thesis += v / t.runBest.size();
        int ours = 0;
        double sum = 0;
        for (const auto& row : entry.outcome.rows)
            if (row.quantity.size() > 16 && row.quantity.compare(row.quantity.size() - 12, 12, "best fitness") == 0 && row.quantity.rfind("run ", 0) == 0 &&
                std::isfinite(row.ours)) {
                sum += row.ours;
                ++ours;
            }
        if (ours) m.ours = sum / ours;
        means.push_back(m);
    }
    return means;
}

// Claims across experiments (chapter 5's analyses): the order of the mean bests of the three-run
// B-spline experiments (5.2-5.4, whose text compares them) and the ranking of every GA experiment.
std::vector<ItemLine> SummaryItemLines(const std::vector<ReportEntry>& entries) {
    std::vector<ItemLine> lines;
    const std::vector<MeanBest> means = MeanBests(entries);
    auto orderLine = [&](const std::string& item, const std::string& claim, bool multiRunOnly) {
        std::vector<std::string> names;
        std::vector<double> ours, thesis;
        for (const MeanBest& m : means)
            if (!multiRunOnly || m.entry->experiment.thesisResult.runBest.size() > 1) {
                names.push_back(m.entry->experiment.id);
                ours.push_back(m.ours);
                thesis.push_back(m.thesis);
            }
        if (names.size() < 2) return;
        const ComparisonRow row = OrderRow("pairs in the thesis's order", PairsFromThesisValues(names, ours, thesis));
        ThesisItem thesisItem;
        thesisItem.item = item;
        thesisItem.quantity = row.quantity;
        thesisItem.claim = claim;
        ItemLine line{"", "thesis-summary", thesisItem, row.thesis, row.ours, 0};
        line.verdict = row.ours == row.thesis ? Verdict::Reproduced : Verdict::Unexplained;
        line.why = row.why;
        lines.push_back(std::move(line));
    };
    orderLine("Sections 5.2-5.4", "the order of the mean best fitness of the three-run B-spline experiments (5.3.1: reduced from 1.1 to 1.07)", true);
    orderLine("Chapter 5", "the ranking of the GA experiments by mean best fitness", false);
    return lines;
}

// The comparison table at the top: every thesis table and figure the experiments reproduce, with our
// number, the difference, and a verdict decided by rule (thesis_check.h).
std::vector<ItemLine> AllItemLines(const std::vector<ReportEntry>& entries) {
    std::vector<ItemLine> lines;
    for (const auto& entry : entries) {
        auto more = ItemLines(entry.experiment, entry.outcome.rows, entry.folder);
        lines.insert(lines.end(), more.begin(), more.end());
    }
    auto summary = SummaryItemLines(entries);
    lines.insert(lines.end(), summary.begin(), summary.end());
    return lines;
}

std::string ItemsMarkdown(const std::vector<ItemLine>& lines, bool quick) {
    if (lines.empty()) return "";
    int counts[4] = {0, 0, 0, 0};
    for (const auto& line : lines) ++counts[static_cast<int>(line.verdict)];
    const int claims = counts[0] + counts[1] + counts[2];
    std::string md = "<a id=\"thesis-items\"></a>\n\n## The thesis item by item\n\n";
    if (quick) md += "(Quick run: the verdicts below judge reduced experiments, not the thesis's.)\n\n";
    md += fmt::format("{} claims of the thesis's tables, figures and analyses: **{} reproduced, {} explained differences, {} unexplained**; "
                      "and {} settings tables followed. Reproduced means within the tolerance shown (by default 5 % of the thesis's value, at "
                      "least 0.02; counts of relations must all hold); a difference is explained only when this run's own numbers account for it "
                      "(the reason column says how), otherwise it is unexplained. A figure that shows a table's numbers again is listed with that "
                      "claim and counted once; a figure of several designs is judged on each of them. Relations between two numbers: a tie in "
                      "the thesis holds when ours are within the sum of the two tolerances, a near-equality when ours keep the order or are "
                      "that close. Settings tables are followed as printed; where the thesis is silent the section's Settings line says what "
                      "was chosen.\n\n",
                      claims, counts[0], counts[1], counts[2], counts[3]);
    md += "| thesis | claim | thesis value | ours | difference | tolerance | verdict | reason (computed from this run) |\n|---|---|---:|---:|---:|---:|---|---|\n";
    for (const auto& line : lines) {
        const ThesisItem& item = line.item;
        const bool settings = !item.settings.empty();
        std::string ours = settings ? "as printed" : Cell(line.ours);
        std::string figures;
        if (!item.figure.empty()) figures += fmt::format("[figure]({}/{})", line.anchor, item.figure);
        std::string named = fmt::format("[{}](#{})", item.item, line.anchor);
        for (const auto& also : item.also) {
            named += ", " + also.item;
            if (!also.figure.empty()) figures += fmt::format("{}[{}]({}/{})", figures.empty() ? "" : ", ", also.item, line.anchor, also.figure);
        }
        if (!figures.empty()) ours += " (" + figures + ")";
        std::string claim = settings ? item.settings : item.claim;
        if (!item.reading.empty()) claim += " (as read here: " + item.reading + ")";
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} |\n", named, claim,
                          settings ? "-" : (item.atLeast ? "> " : "") + Cell(line.thesis), ours, settings ? "-" : Signed(line.ours - line.thesis),
                          !settings && !item.atLeast ? Cell(line.tolerance) : "-", VerdictName(line.verdict), line.why);
    }
    return md + "\n";
}

// The thesis's summary numbers beside ours: mean best per GA experiment and their ranking, and its
// timings.
std::string BesideMarkdown(const std::vector<ReportEntry>& entries) {
    std::string md;
    const std::vector<MeanBest> means = MeanBests(entries);
    for (const auto& entry : entries) {
        const Experiment& e = entry.experiment;
        if (e.model != sim::ModelKind::Thesis) continue;
        const ThesisResult& t = e.thesisResult;
        const ExperimentOutcome& o = entry.outcome;
        for (const MeanBest& m : means)
            if (m.entry == &entry)
                md += fmt::format("| [{}](#{}) | mean best fitness over {} run{} | {}{} | {} |\n", e.id, entry.folder, t.runBest.size(), t.runBest.size() > 1 ? "s" : "",
                                  Cell(m.thesis), std::isfinite(t.meanBest) ? fmt::format(" (its text: {:g}, {})", t.meanBest, t.meanBestSource) : std::string(),
                                  Cell(m.ours));
        if (std::isfinite(t.minutes))
            md += fmt::format("| [{}](#{}) | time for the whole sweep | {:g} min{} | {:.1f} s ({:.1f} ms per simulation, this session) |\n", e.id, entry.folder,
                              t.minutes, std::isfinite(t.secondsPerSimulation) ? fmt::format(", {:g} s per simulation on one thread of a 2016 MacBook", t.secondsPerSimulation) : std::string(),
                              o.seconds, o.simulations > 0 ? 1000 * o.seconds / o.simulations : NAN);
    }
    if (md.empty()) return "";
    auto ranking = [&](bool ours) {
        std::vector<std::pair<double, std::string>> r;
        for (const MeanBest& m : means)
            if (std::isfinite(ours ? m.ours : m.thesis)) r.push_back({ours ? m.ours : m.thesis, m.entry->experiment.id});
        std::stable_sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        std::string text;
        for (const auto& [value, id] : r) text += (text.empty() ? "" : " > ") + fmt::format("{} ({:.3g})", id, value);
        return text;
    };
    md = "<a id=\"thesis-summary\"></a>\n\n## Beside the thesis's own summary\n\n| experiment | quantity | thesis | ours |\n|---|---|---:|---:|\n" + md + "\n";
    if (means.size() > 1)
        md += "Ranking of the GA experiments by mean best fitness: thesis " + ranking(false) + "; ours " + ranking(true) +
              " (the item table counts which pairs keep the thesis's order).\n\n";
    return md;
}

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
    md += fmt::format("| throughput | {} simulations, {:.1f} evaluations/s on {}, figures included, this session |\n", simulations,
                      seconds > 0 ? simulations / seconds : 0, evaluator);
    const std::vector<ItemLine> items = AllItemLines(entries);
    if (!items.empty()) {
        const auto unexplained = std::count_if(items.begin(), items.end(), [](const ItemLine& l) { return l.verdict == Verdict::Unexplained; });
        const auto followed = std::count_if(items.begin(), items.end(), [](const ItemLine& l) { return l.verdict == Verdict::Followed; });
        md += fmt::format("| thesis items | {} claims compared, **{} unexplained**; {} settings tables followed ([table](#thesis-items)) |\n",
                          items.size() - followed, unexplained, followed);
    }
    md += "\n";
    if (!items.empty()) md += ItemsMarkdown(items, quick) + BesideMarkdown(entries);
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
                      (RowDiffers(e, row) ? " **" : "") + " |\n";
            md += "\n";
        }
        md += o.tables;
        for (const auto& line : o.details) md += "- " + line + "\n";
        if (!o.details.empty()) md += "\n";
        bool differs = false;
        for (const auto& row : o.rows) differs = differs || RowDiffers(e, row);
        if (differs && quick) md += "Differences here come from the quick run's reduced grids and generations.\n\n";
        // Reasons are computed by the run from its own numbers; a file's `explanation` adds context.
        std::string reasons;
        for (const auto& row : o.rows)
            if (!row.why.empty() && (RowDiffers(e, row) || !std::isfinite(row.thesis)))
                reasons += "- " + row.quantity + ": " + row.why + (row.explained ? " (explained)" : " (unexplained)") + "\n";
        if (!reasons.empty()) md += "**Why the numbers differ** (rows marked **), computed from this run:\n\n" + reasons + "\n";
        if (!e.explanation.empty() && differs && !quick) md += "Context: " + e.explanation + "\n\n";
        for (const auto& figure : o.figures) md += "![" + e.id + " " + figure + "](" + entry.folder + "/" + figure + ")\n\n";
    }
    return md + closing;
}

}  // namespace app
