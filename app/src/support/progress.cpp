#include "support/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fmt/format.h>

namespace app {

std::string FormatDuration(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "?";
    const long s = std::lround(seconds);
    if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
    return fmt::format("{}:{:02}", s / 60, s % 60);
}

Progress::Progress(std::string what, bool enabled, std::string unit)
    : what_(std::move(what)), unit_(std::move(unit)), start_(std::chrono::steady_clock::now()), tty_(isatty(STDERR_FILENO)), enabled_(enabled) {}

void Progress::Update(long long done, long long total, long long count, const std::string& detail) {
    if (!enabled_) return;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = seconds > 0 ? count / seconds : 0;
    const double left = done > 0 ? seconds * (total - done) / done : NAN;
    const int decile = total > 0 ? static_cast<int>(10 * done / total) : 10;
    if (!tty_ && decile == lastDecile_ && done != total) return;
    lastDecile_ = decile;
    std::fprintf(stderr, "%s%s: %lld/%lld, %.1f %s/s%s%s, %s left%s", tty_ ? "\r\033[K" : "", what_.c_str(), done, total, rate, unit_.c_str(),
                 detail.empty() ? "" : ", ", detail.c_str(), FormatDuration(left).c_str(), tty_ && done != total ? "" : "\n");
    std::fflush(stderr);
}

}  // namespace app
