#include "materials/tensile_curve.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "formats/files.h"
#include "support/errors.h"

namespace app {
namespace {

std::string Lower(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

std::string Trim(const std::string& text) {
    const size_t first = text.find_first_not_of(" \t\"");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t\"") + 1 - first);
}

// One line's fields: split on ';' when it has one (European spreadsheets), else on ',' or tabs.
std::vector<std::string> Fields(const std::string& line) {
    const char separator = line.find(';') != std::string::npos ? ';' : line.find(',') != std::string::npos ? ',' : '\t';
    std::vector<std::string> fields;
    size_t start = 0;
    while (true) {
        const size_t end = line.find(separator, start);
        fields.push_back(Trim(line.substr(start, end == std::string::npos ? std::string::npos : end - start)));
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return fields;
}

bool Names(const std::string& field, const char* word) {
    const std::string name = Lower(field);
    return name.find(word) != std::string::npos && name.find("true") == std::string::npos;
}

bool ParseFieldNumber(const std::string& text, double* value) {
    if (text.empty()) return false;
    char* end = nullptr;
    *value = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && std::isfinite(*value);
}

}  // namespace

TensileCurve ReadTensileCurve(const std::string& path, StressUnit unit) {
    const std::string text = ReadInputFile(path, 64ull << 20);
    const std::string where = path + ": ";
    std::vector<std::string> lines;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(start, end - start);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (lines.empty() && line.rfind("\xEF\xBB\xBF", 0) == 0) line = line.substr(3);  // a spreadsheet's byte-order mark
        lines.push_back(line);
        start = end + 1;
    }

    // The header: the first row naming both columns.
    TensileCurve curve;
    int strainColumn = -1, stressColumn = -1, specimenColumn = -1;
    size_t header = 0;
    for (; header < lines.size(); ++header) {
        const std::vector<std::string> fields = Fields(lines[header]);
        strainColumn = stressColumn = specimenColumn = -1;
        for (size_t c = 0; c < fields.size(); ++c) {
            if (strainColumn < 0 && Names(fields[c], "strain")) strainColumn = static_cast<int>(c);
            else if (stressColumn < 0 && Names(fields[c], "stress")) stressColumn = static_cast<int>(c);
            else if (specimenColumn < 0 && Names(fields[c], "specimen") && !Names(fields[c], "(")) specimenColumn = static_cast<int>(c);
        }
        if (strainColumn >= 0 && stressColumn >= 0) {
            curve.strainColumn = fields[strainColumn];
            curve.stressColumn = fields[stressColumn];
            if (specimenColumn >= 0) curve.specimenColumn = fields[specimenColumn];
            break;
        }
    }
    if (header == lines.size())
        throw UsageError(where + "no header row naming a strain column and a stress column (e.g. \"strain,stress_kpa\"; columns of true strain or stress are not used)");

    // The stress's unit: the column's name, or the option; both when they agree.
    const std::string stressName = Lower(curve.stressColumn);
    StressUnit named = StressUnit::FromHeader;
    if (stressName.find("mpa") != std::string::npos || stressName.find("n/mm") != std::string::npos) named = StressUnit::Mpa;
    else if (stressName.find("kpa") != std::string::npos) named = StressUnit::Kpa;
    if (named == StressUnit::FromHeader) {
        // A unit named that is not one of ours ("Stress (psi)", "stress_pa"): refused, not guessed.
        const size_t open = stressName.find('('), underscore = stressName.rfind('_');
        const std::string given = open != std::string::npos ? Trim(stressName.substr(open + 1, stressName.find(')', open) - open - 1))
                                  : underscore != std::string::npos ? stressName.substr(underscore + 1)
                                                                    : std::string();
        if (!given.empty())
            throw UsageError(where + "the stress column " + Quote(curve.stressColumn) + " names the unit " + Quote(given) + ", not one this reads (kPa, MPa or N/mm^2)");
    }
    if (named != StressUnit::FromHeader && unit != StressUnit::FromHeader && named != unit)
        throw UsageError(where + "the stress column " + Quote(curve.stressColumn) + " names another unit than --unit " + (unit == StressUnit::Kpa ? "kpa" : "mpa"));
    const StressUnit used = named != StressUnit::FromHeader ? named : unit;
    if (used == StressUnit::FromHeader)
        throw UsageError(where + "the stress column " + Quote(curve.stressColumn) + " names no unit: name it (\"stress_kpa\", \"Stress (MPa)\") or give --unit kpa|mpa");
    curve.unit = used == StressUnit::Mpa ? "MPa" : "kPa";
    const double toKpa = used == StressUnit::Mpa ? 1000 : 1;
    const double strainScale = curve.strainColumn.find('%') != std::string::npos ? 0.01 : 1;

    std::map<std::string, int> specimenIndex;
    std::map<int, double> lastStrain;
    const int needed = std::max({strainColumn, stressColumn, specimenColumn}) + 1;
    for (size_t row = header + 1; row < lines.size(); ++row) {
        const std::vector<std::string> fields = Fields(lines[row]);
        if (std::all_of(fields.begin(), fields.end(), [](const std::string& f) { return f.empty(); })) continue;
        const std::string at = where + "row " + std::to_string(row + 1) + ": ";
        if (static_cast<int>(fields.size()) < needed) throw UsageError(at + "has " + std::to_string(fields.size()) + " fields; the header has " + std::to_string(needed) + " or more");
        sim::TensilePoint p;
        double strain = 0, stress = 0;
        if (!ParseFieldNumber(fields[strainColumn], &strain)) throw UsageError(at + Quote(fields[strainColumn]) + " in " + Quote(curve.strainColumn) + " is not a number");
        if (!ParseFieldNumber(fields[stressColumn], &stress)) throw UsageError(at + Quote(fields[stressColumn]) + " in " + Quote(curve.stressColumn) + " is not a number");
        if (strain < 0) throw UsageError(at + "negative strain " + fields[strainColumn] + " (a tensile test's engineering strain starts at 0)");
        if (stress < 0) throw UsageError(at + "negative stress " + fields[stressColumn] + " (trim the rows before the specimen is taut, or zero the load cell)");
        if (specimenColumn >= 0) p.specimen = specimenIndex.emplace(fields[specimenColumn], static_cast<int>(specimenIndex.size())).first->second;
        p.strain = strain * strainScale;
        p.stressKpa = stress * toKpa;
        if (auto last = lastStrain.find(p.specimen); last != lastStrain.end() && p.strain < last->second)
            throw UsageError(at + "strain " + fields[strainColumn] + " is below the row before's: a curve is read as loading only (keep one pull per specimen; "
                                  "name several specimens in a specimen column)");
        lastStrain[p.specimen] = p.strain;
        curve.points.push_back(p);
    }
    if (curve.points.size() < 2) throw UsageError(where + "the curve has " + std::to_string(curve.points.size()) + " point" + (curve.points.size() == 1 ? "" : "s") + "; a fit needs at least two");
    curve.specimens = std::max<int>(1, static_cast<int>(specimenIndex.size()));
    return curve;
}

}  // namespace app
