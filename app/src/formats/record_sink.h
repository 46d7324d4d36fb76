// What is kept of every evaluation a run makes, each by a sink the recorder appends to in
// evaluation-id order: the archive, evaluations.csv, the thumbnails. On --resume each is cut back to
// the records the run resumes from, so that the resumed run's outputs equal an uninterrupted run's.
// An output per evaluation is one more sink (docs/architecture.md, "how to add an output format").
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "formats/archive.h"

namespace app {

class RecordSink {
public:
    virtual ~RecordSink() = default;
    // One evaluation, in id order (the record's id is its place in the archive).
    virtual void Append(const ArchiveRecord& record) = 0;
    // Resume: keep the first `keep` records (the archive's, without meshes, are `kept`, for sinks
    // that are rebuilt from them), then take appends after them.
    virtual void RollBack(std::uint64_t keep, const std::vector<ArchiveRecord>& kept) = 0;
};

// The archive, DIR/evaluations.capnp: where a record's id is its place. On a resume it is opened by
// RollBack, which first cuts off what follows the records the run resumes from.
class ArchiveSink final : public RecordSink {
public:
    ArchiveSink(std::string path, bool resume);
    void Append(const ArchiveRecord& record) override;
    void RollBack(std::uint64_t keep, const std::vector<ArchiveRecord>& kept) override;
    std::uint64_t Count() const { return writer_ ? writer_->Count() : 0; }

private:
    std::string path_;
    std::unique_ptr<ArchiveWriter> writer_;
};

}  // namespace app
