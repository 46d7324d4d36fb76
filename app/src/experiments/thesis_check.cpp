#include "experiments/thesis_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace app {

double DefaultTolerance(double thesis) { return std::max(0.02, 0.05 * std::fabs(thesis)); }

bool WithinTolerance(double ours, double thesis, double tolerance) {
    return std::isfinite(ours) && std::isfinite(thesis) && std::fabs(ours - thesis) <= tolerance;
}

std::string CompareSentence(double ours, double thesis, double tolerance) {
    if (!std::isfinite(ours)) return "ours failed";
    return WithinTolerance(ours, thesis, tolerance) ? fmt::format("{:.4g} is within {:.3g} of {:.4g}", ours, tolerance, thesis)
                                                    : fmt::format("{:.4g} differs from {:.4g} by more than {:.3g}", ours, thesis, tolerance);
}

std::string OrderSentence(double a, double b) {
    // Compared as printed, so that a reader (and the report's test) sees the same relation.
    const double pa = std::stod(fmt::format("{:.4g}", a)), pb = std::stod(fmt::format("{:.4g}", b));
    return fmt::format("{:.4g} {} {:.4g}", a, pa > pb ? "is above" : pa < pb ? "is below" : "equals", b);
}

const char* VerdictName(Verdict verdict) {
    switch (verdict) {
        case Verdict::Reproduced: return "reproduced";
        case Verdict::Explained: return "explained difference";
        case Verdict::Unexplained: break;
    }
    return "unexplained";
}

std::vector<ItemLine> ItemLines(const Experiment& e, const std::vector<ComparisonRow>& rows, const std::string& anchor) {
    std::vector<ItemLine> lines;
    for (const ThesisItem& item : e.thesisItems) {
        ItemLine line{e.id, anchor, item};
        if (!item.settings.empty()) {
            line.verdict = Verdict::Reproduced;  // the experiment file follows the table; choices where it is silent are in the note
            lines.push_back(std::move(line));
            continue;
        }
        const auto row = std::find_if(rows.begin(), rows.end(), [&](const ComparisonRow& r) { return r.quantity == item.quantity; });
        if (row == rows.end()) {
            line.why = "the run produced no number '" + item.quantity + "'";
            lines.push_back(std::move(line));
            continue;
        }
        line.ours = row->ours;
        line.thesis = std::isfinite(item.thesis) ? item.thesis : row->thesis;
        line.tolerance = std::isfinite(item.tolerance) ? item.tolerance : DefaultTolerance(line.thesis);
        const bool reproduced = item.atLeast ? std::isfinite(line.ours) && line.ours >= line.thesis : WithinTolerance(line.ours, line.thesis, line.tolerance);
        if (reproduced) {
            line.verdict = Verdict::Reproduced;
        } else {
            line.verdict = row->explained ? Verdict::Explained : Verdict::Unexplained;
            line.why = row->why.empty() ? (item.atLeast ? OrderSentence(line.ours, line.thesis) : CompareSentence(line.ours, line.thesis, line.tolerance))
                                        : row->why;
        }
        lines.push_back(std::move(line));
    }
    return lines;
}

}  // namespace app
