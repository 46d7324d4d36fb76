// Evaluation archives: every evaluation an experiment makes, appended to DIR/evaluations.capnp with
// its design, parameters, meshes and result. The record's place in the file is its evaluation id,
// the same number in evaluations.csv, thumbnail names, `inspect` and `--from ARCHIVE --index K`.
//
// Format (version 2): the 8 bytes "ACTARCH\2", then one frame per record: payload length (u32,
// little-endian), CRC-32 of the payload (u32), payload (a packed Cap'n Proto Evaluation). Each frame
// is written with a single write() once complete, so a run killed at any point leaves a file whose
// frames are whole but for a torn tail; the checksum tells a damaged record from a cut-off one.
// Version-1 archives (packed messages, no header or checksums) still read.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sim/batch.h"
#include "sim/names.h"

namespace app {

// Why an evaluation was made.
enum class Role {
    Grid,          // a sweep's grid point
    ThesisPoint,   // a design the thesis names in a table, evaluated as it states it
    Shape,         // one of an 'evaluate' experiment's listed shapes
    Individual,    // a GA individual
    ThesisGenome,  // a genome the thesis reports, evaluated in this model
    Figure,        // a re-simulation for a figure (the best design under the other load)
    Characteristic,  // a point of `characterize`'s curves: a free inflation, a held stroke, the isometric test
};

struct ArchiveRecord {
    std::uint64_t id = 0;      // the evaluation id: its place in the archive, from 0
    std::string experiment;    // experiment id
    int run = 0;               // GA run, 1-based; 0 for sweeps and lists
    int generation = -1;       // GA generation; -1 for sweeps and lists
    Role role = Role::Grid;
    std::string label;         // grid point parameters, shape label, or what the figure shows
    sim::EvalJob job;          // the design and the model it was evaluated under
    sim::SimResult result;     // meshes empty when read without them
};

class ArchiveWriter {
public:
    // Opens (creating) the archive for appending; ids continue after its records. An existing file
    // must end in a whole record (see TruncateArchive). Throws UsageError.
    explicit ArchiveWriter(const std::string& path);
    ~ArchiveWriter();
    ArchiveWriter(const ArchiveWriter&) = delete;
    ArchiveWriter& operator=(const ArchiveWriter&) = delete;

    // Appends the record under the next id (its place in the archive), which it returns; the
    // record's own id field is not read. Throws OutputError or UsageError on a write error.
    std::uint64_t Append(const ArchiveRecord& record);
    std::uint64_t Count() const { return next_; }

private:
    std::string path_;
    int fd_ = -1;
    std::uint64_t next_ = 0;
};

// A whole archive's bytes holding `records` under ids 0, 1, ... (their own id fields are not read),
// for a command that writes its archive once, with its other files (WriteFileAtomically in a batch).
std::string ArchiveBytes(const std::vector<ArchiveRecord>& records);

// The archive as a record sink (formats/record_sink.h): records appended under their ids; on resume
// cut back to the first `keep` and opened after them.
class ArchiveSink;

struct ArchiveScan {
    int version = 2;
    std::uint64_t records = 0;    // whole, valid records read
    std::uint64_t goodBytes = 0;  // where the last of them ends
    bool tornTail = false;        // the file ends in part of a record (a run cut off while writing)
    bool corrupt = false;         // a whole record failed its checksum or did not decode
    std::string problem;          // what stopped the reading
};

// Where a scan starts: the start of the file, or where an earlier scan of a version-2 archive
// stopped (its goodBytes and records), so a reader can take the records a few at a time.
struct ArchivePlace {
    std::uint64_t byte = 0;
    std::uint64_t records = 0;
};

// Streams the records in order; `visit` returns false to stop early. withMeshes = false skips the
// positions (fast listing). Throws UsageError when the file cannot be opened or is not an archive,
// and when `from` is not the start of a version-2 archive's record.
ArchiveScan ScanArchive(const std::string& path, bool withMeshes, const std::function<bool(ArchiveRecord&&)>& visit, ArchivePlace from = {});

struct ArchiveContents {
    std::vector<ArchiveRecord> records;
    ArchiveScan scan;
};
ArchiveContents ReadArchive(const std::string& path, bool withMeshes);

// The one record with this id, with its meshes. Throws UsageError naming the valid range.
ArchiveRecord ReadArchiveRecord(const std::string& path, std::uint64_t id);

// For --resume: cuts the archive back to its first `keep` records, dropping a torn tail. Refuses a
// damaged record among those kept (exit 2 naming it) and a version-1 archive.
void TruncateArchive(const std::string& path, std::uint64_t keep);

}  // namespace app

template <>
struct sim::EnumNames<app::Role> {
    static constexpr std::array<std::pair<app::Role, const char*>, 7> table{{
        {app::Role::Grid, "grid"},
        {app::Role::ThesisPoint, "thesis-point"},
        {app::Role::Shape, "shape"},
        {app::Role::Individual, "individual"},
        {app::Role::ThesisGenome, "thesis-genome"},
        {app::Role::Figure, "figure"},
        {app::Role::Characteristic, "characteristic"},
    }};
};
