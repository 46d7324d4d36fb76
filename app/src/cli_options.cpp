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
            const bool nextIsValue = i + 1 < argc && std::string(argv[i + 1]).rfind("--", 0) != 0;
            if (!spec->implicitValue.empty() && !nextIsValue) value = spec->implicitValue;
            else if (!nextIsValue && i + 1 >= argc) throw UsageError("option '--" + name + "' needs a value (" + spec->valueName + ")");
            else value = argv[++i];
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

namespace {

// Arithmetic on numbers and pi, so that phases can be written as the thesis writes them:
// "pi-0.5", "4pi", "0.5*pi", "(8/3)pi". Grammar: sum := product (('+'|'-') product)*;
// product := factor (('*'|'/') factor)*; factor := ('+'|'-') factor | NUMBER ['pi'] | 'pi' | '(' sum ')'.
class NumberExpression {
public:
    explicit NumberExpression(const std::string& text) : text_(text) {}

    bool Parse(double& value) {
        if (!Sum(value)) return false;
        SkipSpaces();
        return pos_ == text_.size();
    }

private:
    void SkipSpaces() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }
    bool Accept(char c) {
        SkipSpaces();
        if (pos_ < text_.size() && text_[pos_] == c) { ++pos_; return true; }
        return false;
    }
    bool AcceptPi() {
        SkipSpaces();
        if (text_.compare(pos_, 2, "pi") == 0) { pos_ += 2; return true; }
        return false;
    }
    bool Sum(double& value) {
        if (!Product(value)) return false;
        for (;;) {
            double rhs;
            if (Accept('+')) { if (!Product(rhs)) return false; value += rhs; }
            else if (Accept('-')) { if (!Product(rhs)) return false; value -= rhs; }
            else return true;
        }
    }
    bool Product(double& value) {
        if (!Factor(value)) return false;
        for (;;) {
            double rhs;
            if (Accept('*')) { if (!Factor(rhs)) return false; value *= rhs; }
            else if (Accept('/')) { if (!Factor(rhs)) return false; value /= rhs; }
            else return true;
        }
    }
    bool Factor(double& value) {
        if (Accept('-')) { if (!Factor(value)) return false; value = -value; return true; }
        if (Accept('+')) return Factor(value);
        if (Accept('(')) {
            if (!Sum(value) || !Accept(')')) return false;
            if (AcceptPi()) value *= std::numbers::pi;
            return true;
        }
        if (AcceptPi()) { value = std::numbers::pi; return true; }
        // A plain decimal number (no "inf", "nan" or hex, which strtod alone would take).
        SkipSpaces();
        const size_t start = pos_;
        auto digits = [&] { size_t n = 0; while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) { ++pos_; ++n; } return n; };
        size_t count = digits();
        if (pos_ < text_.size() && text_[pos_] == '.') { ++pos_; count += digits(); }
        if (count == 0) return false;
        if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
            ++pos_;
            if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
            if (digits() == 0) return false;
        }
        value = std::strtod(text_.substr(start, pos_ - start).c_str(), nullptr);
        if (text_.compare(pos_, 2, "pi") == 0) { pos_ += 2; value *= std::numbers::pi; }  // "4pi"
        return true;
    }

    const std::string& text_;
    size_t pos_ = 0;
};

}  // namespace

double ParseNumber(const std::string& text, const std::string& what) {
    double value = 0;
    if (!NumberExpression(text).Parse(value)) throw UsageError(what + ": '" + text + "' is not a number");
    if (!std::isfinite(value)) throw UsageError(what + ": '" + text + "' is not a finite number");
    return value;
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
