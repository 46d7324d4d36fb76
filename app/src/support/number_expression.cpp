#include "support/number_expression.h"

#include <cctype>
#include <cstdio>
#include <charconv>
#include <cmath>
#include <numbers>

#include "support/errors.h"

namespace app {
namespace {

// Grammar: sum := product (('+'|'-') product)*; product := factor (('*'|'/') factor)*;
// factor := ('+'|'-') factor | NUMBER ['pi'] | 'pi' | '(' sum ')' ['pi']. Depth counts nested
// factors, so 70,000 signs or 300,000 parentheses end in a refusal, not a stack overflow.
class NumberExpression {
public:
    explicit NumberExpression(std::string_view text) : text_(text) {}

    bool Parse(double& value) {
        if (!Sum(value)) return false;
        SkipSpaces();
        return pos_ == text_.size();
    }
    bool TooDeep() const { return tooDeep_; }

private:
    void SkipSpaces() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }
    bool Accept(char c) {
        SkipSpaces();
        if (pos_ < text_.size() && text_[pos_] == c) {
            ++pos_;
            return true;
        }
        return false;
    }
    bool AcceptPi() {
        SkipSpaces();
        if (text_.substr(pos_, 2) == "pi") {
            pos_ += 2;
            return true;
        }
        return false;
    }
    bool Sum(double& value) {
        if (!Product(value)) return false;
        for (;;) {
            double rhs;
            if (Accept('+')) {
                if (!Product(rhs)) return false;
                value += rhs;
            } else if (Accept('-')) {
                if (!Product(rhs)) return false;
                value -= rhs;
            } else {
                return true;
            }
        }
    }
    bool Product(double& value) {
        if (!Factor(value)) return false;
        for (;;) {
            double rhs;
            if (Accept('*')) {
                if (!Factor(rhs)) return false;
                value *= rhs;
            } else if (Accept('/')) {
                if (!Factor(rhs)) return false;
                value /= rhs;
            } else {
                return true;
            }
        }
    }
    bool Factor(double& value) {
        if (depth_ >= kMaxExpressionDepth) {
            tooDeep_ = true;
            return false;
        }
        ++depth_;
        const bool ok = FactorBody(value);
        --depth_;
        return ok;
    }
    bool FactorBody(double& value) {
        if (Accept('-')) {
            if (!Factor(value)) return false;
            value = -value;
            return true;
        }
        if (Accept('+')) return Factor(value);
        if (Accept('(')) {
            if (!Sum(value) || !Accept(')')) return false;
            if (AcceptPi()) value *= std::numbers::pi;
            return true;
        }
        if (AcceptPi()) {
            value = std::numbers::pi;
            return true;
        }
        // A plain decimal number (no "inf", "nan" or hex).
        SkipSpaces();
        const size_t start = pos_;
        auto digits = [&] {
            size_t n = 0;
            while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) {
                ++pos_;
                ++n;
            }
            return n;
        };
        size_t count = digits();
        if (pos_ < text_.size() && text_[pos_] == '.') {
            ++pos_;
            count += digits();
        }
        if (count == 0) return false;
        if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
            ++pos_;
            if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
            if (digits() == 0) return false;
        }
        const auto [end, error] = std::from_chars(text_.data() + start, text_.data() + pos_, value);
        if (error == std::errc::result_out_of_range) value = INFINITY;  // caught as "not finite"
        else if (error != std::errc()) return false;
        (void)end;
        if (text_.substr(pos_, 2) == "pi") {  // "4pi"
            pos_ += 2;
            value *= std::numbers::pi;
        }
        return true;
    }

    std::string_view text_;
    size_t pos_ = 0;
    int depth_ = 0;
    bool tooDeep_ = false;
};

}  // namespace

std::string FormatRadians(double value) {
    for (int n = 0; n <= 16; ++n)
        for (double offset : {0.0, 0.5, -0.5}) {
            if (std::fabs(value - (n * std::numbers::pi + offset)) > 1e-9) continue;
            if (n == 0) return offset == 0 ? "0" : offset > 0 ? "0.5" : "-0.5";
            const std::string pis = n == 1 ? "pi" : std::to_string(n) + "pi";
            return offset == 0 ? pis : pis + (offset > 0 ? "+0.5" : "-0.5");
        }
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

bool TryParseNumber(std::string_view text, double* value) {
    NumberExpression expression(text);
    return expression.Parse(*value) && std::isfinite(*value);
}

double ParseNumber(std::string_view text, const std::string& what) {
    double value = 0;
    NumberExpression expression(text);
    if (!expression.Parse(value)) {
        if (expression.TooDeep())
            throw UsageError(what + ": " + Quote(text) + " nests deeper than " + std::to_string(kMaxExpressionDepth) + " levels");
        throw UsageError(what + ": " + Quote(text) + " is not a number");
    }
    if (!std::isfinite(value)) throw UsageError(what + ": " + Quote(text) + " is not a finite number");
    return value;
}

long long ParseInteger(std::string_view text, const std::string& what, long long min, long long max) {
    long long value = 0;
    const char* begin = text.data();
    const char* end = text.data() + text.size();
    if (begin != end && *begin == '+') ++begin;
    const auto [stop, error] = std::from_chars(begin, end, value);
    if (text.empty() || stop != end || (error != std::errc() && error != std::errc::result_out_of_range))
        throw UsageError(what + ": " + Quote(text) + " is not a whole number");
    if (error == std::errc::result_out_of_range || value < min || value > max)
        throw UsageError(what + ": " + Quote(text) + " is out of range (" + std::to_string(min) + " to " + std::to_string(max) + ")");
    return value;
}

std::vector<double> ParseNumberList(std::string_view text, const std::string& what, char separator) {
    std::vector<double> values;
    if (text.empty()) throw UsageError(what + ": expected a list of numbers, got nothing");
    size_t start = 0;
    for (;;) {
        const size_t next = text.find(separator, start);
        const std::string_view item = text.substr(start, next == std::string_view::npos ? std::string_view::npos : next - start);
        if (item.empty()) throw UsageError(what + ": empty item in " + Quote(text));
        values.push_back(ParseNumber(item, what));
        if (next == std::string_view::npos) break;
        start = next + 1;
    }
    return values;
}

}  // namespace app
