// Reads the comparison table at the top of a reproduction's report.md and lists what is wrong with
// it: a thesis table or figure of chapters 4-6 without a row, a row without a verdict, a verdict the
// row's own numbers contradict, or a reason sentence ("a is within t of b", "a differs from b by
// more than t", "a is above b", "a is below b") that its numbers contradict. Empty when all holds.
#pragma once

#include <cmath>
#include <cstdlib>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace testing_support {

inline std::vector<std::string> SplitCells(const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    for (size_t k = 1; k < line.size(); ++k) {
        if (line[k] == '|') {
            const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
            cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
            cell.clear();
        } else {
            cell += line[k];
        }
    }
    return cells;
}

// A number as printed in a cell ("0.5966 ([figure](...))", "> 3.7", "-"): NaN when there is none.
inline double CellNumber(const std::string& cell) {
    std::string text = cell;
    if (text.rfind("> ", 0) == 0) text = text.substr(2);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    return end == text.c_str() ? NAN : value;
}

// Every relation the sentence states, re-checked on the printed numbers (which carry 3-4 digits:
// a relation within the printing's rounding is accepted).
inline std::vector<std::string> RelationProblems(const std::string& sentence) {
    std::vector<std::string> problems;
    const std::string number = R"((-?[0-9][0-9.e+\-]*))";
    auto slack = [](double a, double b) { return 1e-3 * std::max({std::fabs(a), std::fabs(b), 1.0}); };
    const std::regex within(number + " is within " + number + " of " + number), differs(number + " differs from " + number + " by more than " + number),
        above(number + " is above " + number), below(number + " is below " + number);
    for (std::sregex_iterator it(sentence.begin(), sentence.end(), within), end; it != end; ++it) {
        const double a = std::stod((*it)[1]), t = std::stod((*it)[2]), b = std::stod((*it)[3]);
        if (std::fabs(a - b) > t + slack(a, b)) problems.push_back("false: '" + it->str() + "'");
    }
    for (std::sregex_iterator it(sentence.begin(), sentence.end(), differs), end; it != end; ++it) {
        const double a = std::stod((*it)[1]), b = std::stod((*it)[2]), t = std::stod((*it)[3]);
        if (std::fabs(a - b) < t - slack(a, b)) problems.push_back("false: '" + it->str() + "'");
    }
    for (std::sregex_iterator it(sentence.begin(), sentence.end(), above), end; it != end; ++it)
        if (!(std::stod((*it)[1]) > std::stod((*it)[2]))) problems.push_back("false: '" + it->str() + "'");
    for (std::sregex_iterator it(sentence.begin(), sentence.end(), below), end; it != end; ++it)
        if (!(std::stod((*it)[1]) < std::stod((*it)[2]))) problems.push_back("false: '" + it->str() + "'");
    return problems;
}

inline std::vector<std::string> ThesisReportProblems(const std::string& report) {
    std::vector<std::string> problems;
    std::set<std::string> items;
    int reproduced = 0, explained = 0, unexplained = 0, followed = 0;
    const size_t start = report.find("| thesis | claim | thesis value | ours | difference | tolerance | verdict |");
    if (start == std::string::npos) return {"no comparison table of thesis items"};
    std::istringstream lines(report.substr(start));
    std::string line;
    std::getline(lines, line);  // header
    std::getline(lines, line);  // alignment row
    while (std::getline(lines, line) && line.rfind("| ", 0) == 0) {
        const auto cells = SplitCells(line);
        if (cells.size() != 8) {
            problems.push_back("a row without 8 cells: " + line);
            continue;
        }
        const std::string item = cells[0].substr(1, cells[0].find(']') - 1);  // "[Figure 4.1](#...), Figure 4.2"
        static const std::regex named(R"((Table|Figure) [0-9]+\.[0-9]+)");
        for (std::sregex_iterator it(cells[0].begin(), cells[0].end(), named), end; it != end; ++it) items.insert(it->str());
        const std::string& verdict = cells[6];
        const double thesis = CellNumber(cells[2]), ours = CellNumber(cells[3]), tolerance = CellNumber(cells[5]);
        const bool atLeast = cells[2].rfind("> ", 0) == 0;
        if (verdict == "followed") {
            ++followed;
            if (cells[3] != "as printed") problems.push_back(item + ": 'followed' is for settings tables, yet ours is " + cells[3]);
            continue;
        }
        if (cells[3] == "as printed") problems.push_back(item + ": a settings table judged '" + verdict + "'");
        if (verdict == "reproduced") {
            ++reproduced;
            const bool holds = atLeast ? ours >= thesis : std::fabs(ours - thesis) <= tolerance * 1.001 + 1e-4;
            if (!holds) problems.push_back(item + ": 'reproduced', yet ours " + cells[3] + " against " + cells[2] + " (tolerance " + cells[5] + ")");
        } else if (verdict == "explained difference" || verdict == "unexplained") {
            (verdict == "unexplained" ? unexplained : explained) += 1;
            if (cells[7].empty()) problems.push_back(item + ": '" + verdict + "' without a reason");
            if (std::isfinite(ours) && std::isfinite(thesis) && std::isfinite(tolerance) && !atLeast && std::fabs(ours - thesis) < tolerance * 0.999 - 1e-4)
                problems.push_back(item + ": '" + verdict + "', yet ours " + cells[3] + " is within " + cells[5] + " of " + cells[2]);
        } else {
            problems.push_back(item + ": no verdict ('" + verdict + "')");
        }
        for (const auto& p : RelationProblems(cells[7])) problems.push_back(item + ": " + p);
    }
    // Every table and figure of chapters 4 to 6.
    const std::vector<std::pair<std::string, int>> counts{{"Table 4.", 4}, {"Figure 4.", 6}, {"Table 5.", 9}, {"Figure 5.", 10}, {"Table 6.", 2}, {"Figure 6.", 2}};
    for (const auto& [prefix, n] : counts)
        for (int k = 1; k <= n; ++k)
            if (!items.count(prefix + std::to_string(k))) problems.push_back(prefix + std::to_string(k) + " has no row");
    // The summary counts what the table holds.
    const std::regex summary(R"(([0-9]+) claims of the thesis's tables, figures and analyses: \*\*([0-9]+) reproduced, ([0-9]+) explained differences, ([0-9]+) unexplained\*\*; and ([0-9]+) settings tables followed)");
    std::smatch m;
    if (!std::regex_search(report, m, summary)) problems.push_back("no summary of the verdicts");
    else if (std::stoi(m[1]) != reproduced + explained + unexplained || std::stoi(m[2]) != reproduced || std::stoi(m[3]) != explained ||
             std::stoi(m[4]) != unexplained || std::stoi(m[5]) != followed)
        problems.push_back("the summary's counts (" + m.str() + ") are not the table's");
    // The explanations in the sections state relations too.
    for (size_t at = report.find("**Why the numbers differ**"); at != std::string::npos; at = report.find("**Why the numbers differ**", at + 1)) {
        const size_t end = report.find("\n\n", report.find("\n\n", at) + 2);
        for (const auto& p : RelationProblems(report.substr(at, end - at))) problems.push_back("a section's reasons: " + p);
    }
    return problems;
}

}  // namespace testing_support
