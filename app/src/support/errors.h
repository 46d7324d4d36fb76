// The app's three ways out, besides success: bad input (exit 2), every evaluation server gone
// (exit 3), and an internal error (exit 70, a bug). Numerical failure is never an error: it is a
// status in the result.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace app {

// Bad input from a user: one line on stderr, exit code 2, nothing half-written.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Every worker failed: the run cannot continue here (exit code 3; runs keep their checkpoint).
struct WorkersGone : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The output itself could not be written: a full disk, a quota, a file-size limit, an I/O error
// (exit code 74, EX_IOERR). Not the user's input at fault: what was written is taken back.
struct OutputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// "cannot write X: <reason>" as an OutputError when the system's error `code` says the storage failed
// (ENOSPC, EDQUOT, EFBIG, EIO), else as a UsageError (a path the user can change).
[[noreturn]] void ThrowWriteError(const std::string& what, int code);

// A user's text inside a message: quoted, at most 80 characters (a 10 MB number stays one short
// line; a long path keeps its start and its file name), control characters shown as '?'.
std::string Quote(std::string_view text);

}  // namespace app
