// Numbers as users write them: plain decimals, or arithmetic on numbers and pi, so that phases can
// be written as the thesis writes them: "pi-0.5", "4pi", "0.5*pi", "(8/3)pi", "-pi/2". Used by the
// command line, experiment files, --set values and OBJ/offset files alike.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace app {

// Nesting (parentheses and signs) deeper than this is refused: the parser recurses once per level.
constexpr int kMaxExpressionDepth = 64;

// Strict: the whole text must be consumed and the value finite. `what` names the option or file
// position in the message. Throws UsageError.
double ParseNumber(std::string_view text, const std::string& what);
// A whole number in [min, max]; the message quotes the text as given.
long long ParseInteger(std::string_view text, const std::string& what, long long min, long long max);
std::vector<double> ParseNumberList(std::string_view text, const std::string& what, char separator = ',');

// An angle as people write it: "pi-0.5", "4pi", "0" for simple multiples of pi (with 0 or +-0.5),
// else up to 4 significant digits.
std::string FormatRadians(double value);

// The same without throwing: false on anything that is not a finite number.
bool TryParseNumber(std::string_view text, double* value);

}  // namespace app
