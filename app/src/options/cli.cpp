#include "options/cli.h"

#include <cmath>

namespace app {

Cli::Cli(const std::string& command, const std::string& description) : command_(command), app_(description, "actuator " + command) {
    app_.set_help_flag("-h,--help", "show this help and exit");
    app_.get_formatter()->column_width(34);
    app_.get_formatter()->label("REQUIRED", "(required)");
    app_.option_defaults()->always_capture_default();
}

CLI::Option* Cli::Number(const std::string& name, double& target, const std::string& help, double min, double max) {
    auto* option = app_.add_option_function<std::string>(
        name,
        [&target, name, min, max](const std::string& text) {
            const double value = ParseNumber(text, name);
            if (value < min || value > max)
                throw UsageError(name + ": " + Quote(text) + " is out of range (" + (min == -sim::kUnbounded ? std::string("any") : fmt::format("{}", min)) +
                                 " to " + (max == sim::kUnbounded ? std::string("any") : fmt::format("{}", max)) + ")");
            target = value;
        },
        help);
    return option->type_name("X")->default_str(fmt::format("{}", target))->group(group_);
}

CLI::Option* Cli::Integer(const std::string& name, int& target, const std::string& help, long long min, long long max) {
    auto* option = app_.add_option_function<std::string>(
        name, [&target, name, min, max](const std::string& text) { target = static_cast<int>(ParseInteger(text, name, min, max)); }, help);
    return option->type_name("N")->default_str(std::to_string(target))->group(group_);
}

CLI::Option* Cli::Text(const std::string& name, std::string& target, const std::string& help) {
    auto* option = app_.add_option(name, target, help)->group(group_);
    if (name.rfind("--", 0) == 0) option->type_name("TEXT");
    return option;
}

CLI::Option* Cli::List(const std::string& name, std::vector<std::string>& target, const std::string& help) {
    return app_.add_option(name, target, help)->group(group_)->take_all()->allow_extra_args(false);
}

CLI::Option* Cli::Flag(const std::string& name, bool& target, const std::string& help) {
    return app_.add_flag(name, target, help)->group(group_)->disable_flag_override();
}

bool Cli::Parse(int argc, char** argv, int first) {
    std::vector<std::string> args;
    for (int i = argc - 1; i >= first; --i) args.emplace_back(argv[i]);  // CLI11 takes them reversed
    // A flag takes no value: CLI11 would read --help=1 or --quick=true as the flag given.
    for (const std::string& arg : args) {
        const size_t equals = arg.find('=');
        if (arg.rfind("--", 0) != 0 || equals == std::string::npos) continue;
        const CLI::Option* option = app_.get_option_no_throw(arg.substr(0, equals));
        if (option && option->get_expected_max() == 0)  // a flag; options with an optional value take one
            throw UsageError(arg.substr(0, equals) + " takes no value (given " + Quote(arg) + "); give " + arg.substr(0, equals) + " alone");
    }
    try {
        app_.parse(args);
    } catch (const CLI::CallForHelp&) {
        std::printf("%s", app_.help().c_str());
        return false;
    } catch (const CLI::ExtrasError& error) {
        const auto extras = error.what();
        throw UsageError(std::string(extras) + " (run 'actuator " + command_ + " --help' for the options)");
    } catch (const CLI::ParseError& error) {
        std::string message = error.what();
        for (char& c : message)
            if (c == '\n') c = ' ';
        throw UsageError(message);
    }
    return true;
}

bool Cli::Given(const std::string& name) const {
    const CLI::Option* option = app_.get_option_no_throw(name);
    return option && option->count() > 0;
}

void Cli::RefuseIfGiven(const std::string& name, const std::string& why) const {
    if (Given(name)) throw UsageError(name + " " + why);
}

const char* Version() { return ACTUATOR_VERSION; }

}  // namespace app
