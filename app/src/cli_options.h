// Command-line parsing for `actuator`: a table of options per subcommand, from which both the parser
// and the --help text are made, so that help can never disagree with what is accepted.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace app {

// Bad input from a user: reported as one line on stderr, exit code 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct OptionSpec {
    std::string name;          // without the leading "--"
    std::string valueName;     // empty for a flag
    std::string defaultText;   // shown in help; empty when there is no default
    std::string help;
    std::string implicitValue = "";  // when set, the value may be left out: "--turntable" means "--turntable 60"
};

struct ParsedArgs {
    std::map<std::string, std::string> values;  // option name -> value ("" for flags)
    std::vector<std::string> positionals;

    bool Has(const std::string& name) const { return values.count(name) != 0; }
    const std::string& Get(const std::string& name) const { return values.at(name); }
};

// Parses argv[first..argc). Accepts "--name value" and "--name=value". Throws UsageError on an
// unknown option, a missing value, a repeated option, or a stray positional when none are allowed.
ParsedArgs ParseArgs(int argc, char** argv, int first, const std::vector<OptionSpec>& specs, int maxPositionals);

// "  --name VALUE   help (default: ...)" lines, wrapped for an 100-column terminal.
std::string FormatOptions(const std::vector<OptionSpec>& specs);

// Strict value parsers: the whole text must be consumed and the number finite. `what` names the
// option in the message. Numbers may use pi and + - * / ( ): "pi-0.5", "4pi", "0.5*pi", "-pi/2".
double ParseNumber(const std::string& text, const std::string& what);
int ParseInt(const std::string& text, const std::string& what, int min, int max);
std::vector<double> ParseNumberList(const std::string& text, const std::string& what, char separator = ',');
std::string ParseChoice(const std::string& text, const std::string& what, const std::vector<std::string>& choices);

}  // namespace app
