// One progress line on stderr for long work: done/total, rate, a detail (e.g. the best so far) and
// the time left; rewritten in place on a terminal, printed about every 10% into a log.
#pragma once

#include <chrono>
#include <string>

namespace app {

class Progress {
public:
    // `unit` names what the rate counts: "evaluations", "frames".
    Progress(std::string what, bool enabled, std::string unit = "evaluations");
    // `count`: units done so far this session (for the rate); `detail` is shown as it is.
    void Update(long long done, long long total, long long count, const std::string& detail);

private:
    std::string what_, unit_;
    std::chrono::steady_clock::time_point start_;
    bool tty_, enabled_;
    int lastDecile_ = -1;
};

// "m:ss" (or "h:mm:ss"); "?" for a time that is not known.
std::string FormatDuration(double seconds);

}  // namespace app
