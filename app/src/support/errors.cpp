#include "support/errors.h"

#include <cerrno>
#include <cstring>

namespace app {

std::string Quote(std::string_view text) {
    constexpr size_t kShown = 80;
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string quoted = "'";
    auto append = [&quoted](std::string_view part) {
        for (unsigned char c : part) quoted += c < 0x20 || c == 0x7f ? '?' : static_cast<char>(c);
    };
    if (text.size() <= kShown) {
        append(text);
        return quoted + "'";
    }
    // The start and the end (a long path keeps its file name), and how long the whole was.
    append(text.substr(0, 40));
    quoted += "...";
    append(text.substr(text.size() - 37));
    return quoted + "' (" + std::to_string(text.size()) + " characters)";
}

[[noreturn]] void ThrowWriteError(const std::string& what, int code) {
    const std::string message = what + ": " + std::strerror(code);
    if (code == ENOSPC || code == EDQUOT || code == EFBIG || code == EIO) throw OutputError(message);
    throw UsageError(message);
}

}  // namespace app
