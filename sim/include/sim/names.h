// One names table per enum: the words used on the command line, in experiment files, in JSON and
// CSV outputs and in messages. Every conversion between an enum and its text goes through here, so a
// new value is named once and is at once accepted, printed and listed among the valid choices.
//
// A table is a specialisation of EnumNames<E> with a static array `table` of {value, name} pairs,
// in the order the choices are listed to a user.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>
#include <string_view>
#include <utility>

namespace sim {

template <class E>
struct EnumNames;  // specialised next to each enum

// The name of a value ("?" for a value outside the table, which would be a programmer error).
template <class E>
constexpr const char* Name(E value) {
    for (const auto& [v, name] : EnumNames<E>::table)
        if (v == value) return name;
    return "?";
}

// The value with this name, or nothing.
template <class E>
constexpr std::optional<E> FromName(std::string_view text) {
    for (const auto& [v, name] : EnumNames<E>::table)
        if (text == name) return v;
    return std::nullopt;
}

// "a, b or c": names listed for messages and help text.
inline std::string ListText(const std::vector<std::string>& names, const char* conjunction = "or") {
    std::string text;
    for (size_t k = 0; k < names.size(); ++k) {
        if (k > 0) text += k + 1 == names.size() ? std::string(" ") + conjunction + " " : std::string(", ");
        text += names[k];
    }
    return text;
}

// "a, b or c": the valid names, for messages and help text.
template <class E>
std::string Choices(const char* conjunction = "or") {
    std::vector<std::string> names;
    for (const auto& [v, name] : EnumNames<E>::table) names.emplace_back(name);
    return ListText(names, conjunction);
}

// "a|b|c": the valid names as an option's value placeholder.
template <class E>
std::string ChoicesBar() {
    std::string text;
    for (const auto& [v, name] : EnumNames<E>::table) text += (text.empty() ? "" : "|") + std::string(name);
    return text;
}

}  // namespace sim
