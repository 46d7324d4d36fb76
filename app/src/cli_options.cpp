#include "cli_options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

namespace app {

ParsedArgs ParseArgs(int argc, char** argv, int first, const std::vector<OptionSpec>& specs, int maxPositionals) {
    ParsedArgs parsed;
    for (int i = first; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg.rfind("--", 0) != 0 || arg == "--") {
            if (static_cast<int>(parsed.positionals.size()) >= maxPositionals)
                throw UsageError("unexpected argument '" + arg + "'");
            parsed.positionals.push_back(arg);
            continue;
        }
        std::string name = arg.substr(2), value;
        bool inlineValue = false;
        if (auto eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
            inlineValue = true;
        }
        const OptionSpec* spec = nullptr;
        for (const auto& s : specs)
            if (s.name == name) spec = &s;
        if (!spec) throw UsageError("unknown option '--" + name + "'");
        if (parsed.Has(name)) throw UsageError("option '--" + name + "' given twice");
        if (spec->valueName.empty()) {
            if (inlineValue) throw UsageError("option '--" + name + "' takes no value");
        } else if (!inlineValue) {
            if (i + 1 >= argc) throw UsageError("option '--" + name + "' needs a value (" + spec->valueName + ")");
            value = argv[++i];
        }
        parsed.values[name] = value;
    }
    return parsed;
}

std::string FormatOptions(const std::vector<OptionSpec>& specs) {
    std::ostringstream out;
    for (const auto& s : specs) {
        std::string head = "  --" + s.name + (s.valueName.empty() ? "" : " " + s.valueName);
        std::string text = s.help + (s.defaultText.empty() ? "" : " (default: " + s.defaultText + ")");
        const size_t column = 30;
        out << head;
        if (head.size() + 2 > column) out << "\n" << std::string(column, ' ');
        else out << std::string(column - head.size(), ' ');
        // Wrap the help text at ~100 columns, indented under itself.
        size_t lineLength = column;
        std::istringstream words(text);
        std::string word;
        bool firstWord = true;
        while (words >> word) {
            if (!firstWord && lineLength + 1 + word.size() > 100) {
                out << "\n" << std::string(column, ' ');
                lineLength = column;
                firstWord = true;
            }
            if (!firstWord) { out << ' '; ++lineLength; }
            out << word;
            lineLength += word.size();
            firstWord = false;
        }
        out << "\n";
    }
    return out.str();
}

double ParseNumber(const std::string& rawText, const std::string& what) {
    std::string text = rawText;
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.erase(text.begin());
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    double scale = 1.0;
    if (text.size() >= 2 && text.compare(text.size() - 2, 2, "pi") == 0) {
        scale = std::numbers::pi;
        text.erase(text.size() - 2);
        if (text.empty() || text == "+" || text == "-") text += "1";
        if (!text.empty() && text.back() == '*') text.pop_back();
    }
    if (text.empty()) throw UsageError(what + ": expected a number, got '" + rawText + "'");
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size()) throw UsageError(what + ": '" + rawText + "' is not a number");
    if (errno == ERANGE || !std::isfinite(value))
        throw UsageError(what + ": '" + rawText + "' is not a finite number");
    return value * scale;
}

int ParseInt(const std::string& text, const std::string& what, int min, int max) {
    errno = 0;
    char* end = nullptr;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || end != text.c_str() + text.size())
        throw UsageError(what + ": '" + text + "' is not a whole number");
    if (errno == ERANGE || value < min || value > max)
        throw UsageError(what + ": " + text + " is out of range (" + std::to_string(min) + " to " + std::to_string(max) + ")");
    return static_cast<int>(value);
}

std::vector<double> ParseNumberList(const std::string& text, const std::string& what, char separator) {
    std::vector<double> values;
    std::string item;
    std::istringstream in(text);
    while (std::getline(in, item, separator)) values.push_back(ParseNumber(item, what));
    if (!text.empty() && text.back() == separator) throw UsageError(what + ": trailing '" + std::string(1, separator) + "' in '" + text + "'");
    if (values.empty()) throw UsageError(what + ": expected a list of numbers, got '" + text + "'");
    return values;
}

std::string ParseChoice(const std::string& text, const std::string& what, const std::vector<std::string>& choices) {
    for (const auto& c : choices)
        if (c == text) return text;
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    throw UsageError(what + ": unknown value '" + text + "' (choose from " + list + ")");
}

}  // namespace app
