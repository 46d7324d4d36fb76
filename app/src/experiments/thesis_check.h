// Our numbers set beside the thesis's, decided by rule rather than written in advance: the tolerance
// within which a number counts as reproduced, the sentences that state a relation between two
// numbers (in a fixed wording that tests parse and re-check), and each thesis item's verdict.
#pragma once

#include <string>
#include <vector>

#include "experiments/experiment.h"
#include "experiments/experiment_runner.h"

namespace app {

// Reproduced when |ours - thesis| <= this: the thesis prints two or three digits and its numbers are
// snapshots of a transient, so 5 % of its value, and never less than 0.02.
double DefaultTolerance(double thesis);

// "0.959 differs from 3.5 by more than 0.175" or "1.12 is within 0.056 of 1.13": the relation the
// numbers have, never a claim the numbers contradict. `WithinTolerance` is the test behind it.
bool WithinTolerance(double ours, double thesis, double tolerance);
std::string CompareSentence(double ours, double thesis, double tolerance);
// "3.85 is above 1.13", "0.356 is below 1.19" or "1.1 equals 1.1".
std::string OrderSentence(double a, double b);

// Order claims ("six cycles perform best, nearly as five and seven"; Table 6.2's two -2.62s): each
// pair the thesis relates, and whether ours keeps the relation. Two numbers that each sit within
// their tolerance of the truth can swap when they are closer than the sum of their tolerances, so
// the thesis's near-equalities (stated or that close) hold when ours keep the order or are that
// close; its ties (equal numbers) hold only when ours are that close.
enum class Relation { Above, NearlyAbove, Equal };  // the first of a pair against the second, in the thesis
struct OrderPair {
    std::string first, second;  // names as the report shows them
    double oursFirst = NAN, oursSecond = NAN;
    Relation relation = Relation::Above;
    double tolerance = NAN;  // for NearlyAbove and Equal: how close counts as equal
};
bool PairAgrees(const OrderPair& pair);
// The pairs of numbers the thesis prints, related as above: names[k] has ours[k] and thesis[k].
std::vector<OrderPair> PairsFromThesisValues(const std::vector<std::string>& names, const std::vector<double>& ours, const std::vector<double>& thesis);
// "pairs in the thesis's order": ours = pairs that agree, thesis = pairs related; the reason lists
// each pair that does not, in sentences the report's checker re-checks.
ComparisonRow OrderRow(const std::string& quantity, const std::vector<OrderPair>& pairs);

// Settings tables are followed, not reproduced: they are counted apart.
enum class Verdict { Reproduced, Explained, Unexplained, Followed };
const char* VerdictName(Verdict verdict);  // "reproduced", "explained difference", "unexplained", "followed"

// One line of the report's comparison table: a thesis item with our number and its verdict.
struct ItemLine {
    std::string experiment;  // experiment id, e.g. "5.2"
    std::string anchor;      // the experiment's section in the report
    ThesisItem item;
    double thesis = NAN, ours = NAN, tolerance = NAN;
    std::string why{};       // the computed reason, for explained and unexplained differences
    Verdict verdict = Verdict::Unexplained;
};
// The experiment's items against its outcome's rows. An item whose row the run did not produce is
// unexplained, saying so.
std::vector<ItemLine> ItemLines(const Experiment& e, const std::vector<ComparisonRow>& rows, const std::string& anchor);

}  // namespace app
