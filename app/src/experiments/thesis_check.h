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

enum class Verdict { Reproduced, Explained, Unexplained };
const char* VerdictName(Verdict verdict);  // "reproduced", "explained difference", "unexplained"

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
