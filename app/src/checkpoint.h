// A GA run's state on disk, so that an interrupted run resumes exactly where it stopped: the
// population with fitness and status, the generator's state, the logbook, the best individual of
// every generation and the hall of fame. JSON with round-trip doubles; written atomically.
#pragma once

#include <string>

#include "sim/search.h"

namespace app {

struct RunCheckpoint {
    std::uint64_t seed = 0;
    sim::GaState state;
};

std::string FormatCheckpoint(const RunCheckpoint& checkpoint);
// Throws UsageError naming the file when it is not a checkpoint this version wrote.
RunCheckpoint ParseCheckpoint(const std::string& text, const std::string& path);

// The run's tables, as CSV text (shortest round-trip numbers, so equal runs give equal bytes).
std::string LogbookCsv(const sim::GaState& state);
std::string BestPerGenerationCsv(const sim::GaState& state);
std::string HallOfFameCsv(const sim::GaState& state);

}  // namespace app
