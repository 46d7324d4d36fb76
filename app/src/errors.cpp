#include "errors.h"

namespace app {

std::string Quote(std::string_view text) {
    constexpr size_t kShown = 80;
    auto printable = [](std::string_view part) {
        std::string out;
        for (unsigned char c : part) out += c < 0x20 || c == 0x7f ? '?' : static_cast<char>(c);
        return out;
    };
    if (text.size() <= kShown) return "'" + printable(text) + "'";
    // The start and the end (a long path keeps its file name), and how long the whole was.
    return "'" + printable(text.substr(0, 40)) + "..." + printable(text.substr(text.size() - 37)) + "' (" + std::to_string(text.size()) + " characters)";
}

}  // namespace app
