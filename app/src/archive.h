// Evaluation archives: every evaluation of a sweep or GA run appended to DIR/evaluations.capnp as
// one packed Cap'n Proto message (schema: sim/actuator.capnp). Each message is written with a
// single write() once complete, so a run cut off at any point leaves a readable archive: at most
// the message being written is lost, and reading stops cleanly there.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/search.h"
#include "sim/solver.h"

namespace app {

struct ArchivedEvaluation {
    std::uint64_t index = 0;   // order in the archive, from 0
    std::string experiment;    // experiment id
    int run = 0;               // GA run, 1-based; 0 for sweeps and lists
    int generation = -1;       // GA generation; -1 for sweeps and lists
    std::string label;         // grid point, shape label, or GA evaluation number
    sim::Shape shape;          // for GA runs, the genome's shape (its B-spline sectors or free-xy offsets)
    sim::SimParams params;
    sim::MeshDef mesh;
    sim::Positions initial, final;  // stored as float32
    sim::Status status = sim::Status::Ok;
    double fitness = 0, contractionPercent = 0, elapsedMs = 0;
    int iterationsRun = 0;
};

// Copies a simulation's outcome (status, numbers, meshes) into a record, and back.
void SetResult(ArchivedEvaluation& record, const sim::SimResult& result);
sim::SimResult ResultOf(const ArchivedEvaluation& record);

class ArchiveWriter {
public:
    // Opens (creating or appending to) the archive; indices continue after what it already holds.
    // Throws UsageError when the file cannot be opened or is not an archive.
    explicit ArchiveWriter(const std::string& path);
    ~ArchiveWriter();
    ArchiveWriter(const ArchiveWriter&) = delete;
    ArchiveWriter& operator=(const ArchiveWriter&) = delete;

    // Sets record.index and appends it. Throws UsageError on a write error.
    void Append(ArchivedEvaluation record);
    std::uint64_t Count() const { return next_; }

private:
    std::string path_;
    int fd_ = -1;
    std::uint64_t next_ = 0;
};

struct ArchiveContents {
    std::vector<ArchivedEvaluation> evaluations;
    bool truncated = false;  // the file ends in an incomplete or unreadable message
    std::string problem;     // what stopped the reading, when truncated
};

// Reads every complete message. withMeshes = false skips the positions (faster listing).
// Throws UsageError only when the file cannot be opened.
ArchiveContents ReadArchive(const std::string& path, bool withMeshes = true);

}  // namespace app
