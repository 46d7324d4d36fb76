// A GA run's state on disk, so that an interrupted run resumes exactly where it stopped: the
// population with fitness and status, the generator's state, the logbook, the best individual of
// every generation, the hall of fame, how many evaluations the archive held, and the experiment it
// was made with (a resume under an edited experiment is refused, naming what changed). JSON with
// round-trip doubles, written atomically. Everything read back is checked like user input.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "experiments/experiment.h"
#include "sim/search.h"

namespace app {

struct RunCheckpoint {
    std::uint64_t seed = 0;
    sim::GaState state;
    std::uint64_t archiveCount = 0;  // evaluations in the archive when this was written
    std::string experimentHash;      // ExperimentHash of what the run was started with
    nlohmann::ordered_json experiment;  // the experiment itself, to name what changed
};

std::string FormatCheckpoint(const RunCheckpoint& checkpoint);
// Throws UsageError naming the file and what is wrong: not a checkpoint, made with another
// experiment (and what differs), or contents that this experiment's GA could not have produced.
RunCheckpoint ParseCheckpoint(const std::string& text, const std::string& path, const Experiment& experiment);

// The run's tables, as CSV text (shortest round-trip numbers, so equal runs give equal bytes).
std::string LogbookCsv(const sim::GaState& state);
std::string BestPerGenerationCsv(const sim::GaState& state);
std::string HallOfFameCsv(const sim::GaState& state);

// An optimizer run's state on disk. No optimizer state: a resume replays the run from its seed with
// the archive's results as answers (pagmo_engine.cpp), so the generation, the archive's length, the
// stop reason and the experiment are all it needs.
struct OptimizerCheckpoint {
    std::uint64_t seed = 0;
    int generation = -1;             // generations completed (0: the initial population)
    std::uint64_t archiveCount = 0;  // evaluations in the archive when written
    std::string stopReason;          // set once the run has ended
    double seconds = 0;              // wall time spent so far; kept only under a seconds stop criterion
};
std::string FormatOptimizerCheckpoint(const OptimizerCheckpoint& checkpoint, const Experiment& experiment);
// Throws UsageError like ParseCheckpoint.
OptimizerCheckpoint ParseOptimizerCheckpoint(const std::string& text, const std::string& path, const Experiment& experiment);

}  // namespace app
