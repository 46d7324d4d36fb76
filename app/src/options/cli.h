// The command line through CLI11: options bound to variables that start out holding the def
// structs' defaults (so --help shows them, never typed twice), number expressions ("pi-0.5") for
// every number, whole numbers with ranges, enum options with their names from sim::EnumNames, and
// every parse error as one line (UsageError, exit 2).
#pragma once

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <string>
#include <vector>

#include "support/errors.h"
#include "sim/fields.h"
#include "support/number_expression.h"
#include "sim/names.h"

namespace app {

using sim::kUnbounded;

// "spring_constant" -> "--spring-constant".
inline std::string OptionName(const char* key) {
    std::string name = std::string("--") + key;
    for (char& c : name)
        if (c == '_') c = '-';
    return name;
}


class Cli {
public:
    // `command` as the user types it, e.g. "simulate"; `description` opens the help.
    Cli(const std::string& command, const std::string& description);

    CLI::App& App() { return app_; }
    const std::string& Command() const { return command_; }

    CLI::Option* Number(const std::string& name, double& target, const std::string& help, double min = -sim::kUnbounded, double max = sim::kUnbounded);
    CLI::Option* Integer(const std::string& name, int& target, const std::string& help, long long min, long long max);
    CLI::Option* Text(const std::string& name, std::string& target, const std::string& help);
    CLI::Option* List(const std::string& name, std::vector<std::string>& target, const std::string& help);  // repeatable
    CLI::Option* Flag(const std::string& name, bool& target, const std::string& help);
    template <class E>
    CLI::Option* Enum(const std::string& name, E& target, const std::string& help) {
        const std::string option = name;
        return app_
            .add_option_function<std::string>(
                name, [this, &target, option](const std::string& text) { target = ParseEnum<E>(text, option); }, help)
            ->type_name(sim::ChoicesBar<E>())
            ->default_str(sim::Name(target))
            ->group(group_);
    }
    // The options of a def struct (see fields.h), in the current group.
    template <class Def>
    void Fields(Def& def, std::vector<std::string> except = {});

    // The fields of `from` whose options were given, copied into `to` (e.g. settings given on the
    // command line over those stored in an archive).
    template <class Def>
    void CopyGivenFields(const Def& from, Def& to) const;
    // Refuses every field's option: "--iterations does not go with --from: ...".
    template <class Def>
    void RefuseFields(Def& def, const std::string& why) const;

    // Options added from now on are listed under this heading in --help.
    void Group(const std::string& heading) { group_ = heading; }
    void Examples(const std::string& text) { app_.footer("Examples:\n" + text); }

    // Parses argv[first..argc). False when --help was asked for (the help is printed). Throws
    // UsageError with one line for anything else that is wrong.
    bool Parse(int argc, char** argv, int first);
    bool Given(const std::string& name) const;
    // Refuses an option given when it does not apply: "--amplitude does not apply to --shape bspline".
    void RefuseIfGiven(const std::string& name, const std::string& why) const;

    template <class E>
    static E ParseEnum(const std::string& text, const std::string& what) {
        if (auto value = sim::FromName<E>(text)) return *value;
        throw UsageError(what + ": unknown value " + Quote(text) + " (choose " + sim::Choices<E>() + ")");
    }

private:
    std::string command_;
    std::string group_ = "Options";
    CLI::App app_;
};

// The program's version: `git describe` at build time.
const char* Version();

namespace detail {

struct FieldBinder {
    Cli& cli;
    std::vector<std::string> except;
    bool Skip(const char* key) const { return std::find(except.begin(), except.end(), key) != except.end(); }
    void Integer(const char* key, int& v, const char* help, long long min, long long max) {
        if (!Skip(key)) cli.Integer(OptionName(key), v, help, min, max);
    }
    void Number(const char* key, double& v, const char* help, double min, double max) {
        if (!Skip(key)) cli.Number(OptionName(key), v, help, min, max);
    }
    template <class E>
    void Enum(const char* key, E& v, const char* help) {
        if (!Skip(key)) cli.Enum(OptionName(key), v, help);
    }
};

template <class Def>
struct FieldCopier {
    const Cli& cli;
    const Def& from;
    Def& to;
    // The same field of `from` as `field` is of `to` (both are the one struct type).
    template <class T>
    const T& Same(const T& field) const {
        const auto offset = reinterpret_cast<const char*>(&field) - reinterpret_cast<const char*>(&to);
        return *reinterpret_cast<const T*>(reinterpret_cast<const char*>(&from) + offset);
    }
    void Integer(const char* key, int& v, const char*, long long, long long) {
        if (cli.Given(OptionName(key))) v = Same(v);
    }
    void Number(const char* key, double& v, const char*, double, double) {
        if (cli.Given(OptionName(key))) v = Same(v);
    }
    template <class E>
    void Enum(const char* key, E& v, const char*) {
        if (cli.Given(OptionName(key))) v = Same(v);
    }
};

struct FieldRefuser {
    const Cli& cli;
    const std::string& why;
    void Integer(const char* key, const int&, const char*, long long, long long) { cli.RefuseIfGiven(OptionName(key), why); }
    void Number(const char* key, const double&, const char*, double, double) { cli.RefuseIfGiven(OptionName(key), why); }
    template <class E>
    void Enum(const char* key, const E&, const char*) {
        cli.RefuseIfGiven(OptionName(key), why);
    }
};

}  // namespace detail

template <class Def>
void Cli::Fields(Def& def, std::vector<std::string> except) {
    VisitFields(def, detail::FieldBinder{*this, std::move(except)});
}
template <class Def>
void Cli::CopyGivenFields(const Def& from, Def& to) const {
    VisitFields(to, detail::FieldCopier<Def>{*this, from, to});
}
template <class Def>
void Cli::RefuseFields(Def& def, const std::string& why) const {
    VisitFields(def, detail::FieldRefuser{*this, why});
}

}  // namespace app
