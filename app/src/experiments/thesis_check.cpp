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
        case Verdict::Followed: return "followed";
        case Verdict::Unexplained: break;
    }
    return "unexplained";
}

bool PairAgrees(const OrderPair& p) {
    if (!std::isfinite(p.oursFirst) || !std::isfinite(p.oursSecond)) return false;
    const bool close = std::fabs(p.oursFirst - p.oursSecond) <= p.tolerance;
    switch (p.relation) {
        case Relation::Above: return p.oursFirst > p.oursSecond;
        case Relation::NearlyAbove: return p.oursFirst > p.oursSecond || close;
        case Relation::Equal: return close;
    }
    return false;
}

std::vector<OrderPair> PairsFromThesisValues(const std::vector<std::string>& names, const std::vector<double>& ours, const std::vector<double>& thesis) {
    std::vector<OrderPair> pairs;
    for (size_t a = 0; a < names.size(); ++a)
        for (size_t b = a + 1; b < names.size(); ++b) {
            if (!std::isfinite(thesis[a]) || !std::isfinite(thesis[b])) continue;
            const bool aFirst = thesis[a] >= thesis[b];
            const size_t hi = aFirst ? a : b, lo = aFirst ? b : a;
            OrderPair p{names[hi], names[lo], ours[hi], ours[lo]};
            p.tolerance = DefaultTolerance(thesis[hi]) + DefaultTolerance(thesis[lo]);
            p.relation = thesis[hi] == thesis[lo] ? Relation::Equal : thesis[hi] - thesis[lo] <= p.tolerance ? Relation::NearlyAbove : Relation::Above;
            pairs.push_back(std::move(p));
        }
    return pairs;
}

ComparisonRow OrderRow(const std::string& quantity, const std::vector<OrderPair>& pairs) {
    int kept = 0;
    std::string why;
    for (const OrderPair& p : pairs) {
        if (PairAgrees(p)) {
            ++kept;
            continue;
        }
        std::string sentence;
        if (!std::isfinite(p.oursFirst) || !std::isfinite(p.oursSecond))
            sentence = fmt::format("{} against {}: ours has no value for one of them", p.first, p.second);
        else if (p.relation == Relation::Equal)
            sentence = fmt::format("{} and {}: the thesis has them equal, ours {}", p.first, p.second, CompareSentence(p.oursFirst, p.oursSecond, p.tolerance));
        else
            sentence = fmt::format("{} against {}: the thesis has the first {}above, ours {}{}", p.first, p.second,
                                   p.relation == Relation::NearlyAbove ? "nearly equal or " : "", OrderSentence(p.oursFirst, p.oursSecond),
                                   p.relation == Relation::NearlyAbove ? fmt::format(" and {}", CompareSentence(p.oursFirst, p.oursSecond, p.tolerance)) : "");
        why += (why.empty() ? "" : "; ") + sentence;
    }
    ComparisonRow row{quantity, static_cast<double>(kept), static_cast<double>(pairs.size())};
    row.why = why;
    return row;
}

std::vector<ItemLine> ItemLines(const Experiment& e, const std::vector<ComparisonRow>& rows, const std::string& anchor) {
    std::vector<ItemLine> lines;
    for (const ThesisItem& item : e.thesisItems) {
        ItemLine line{e.id, anchor, item};
        if (!item.settings.empty()) {
            line.verdict = Verdict::Followed;  // the experiment file follows the table; choices where it is silent are in the note
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
