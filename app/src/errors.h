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

// A user's text inside a message: quoted, at most 80 characters (a 10 MB number stays one short
// line; a long path keeps its start and its file name), control characters shown as '?'.
std::string Quote(std::string_view text);

}  // namespace app
