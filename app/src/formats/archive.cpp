#include "formats/archive.h"

#include <filesystem>
#include <stdexcept>

#include "formats/record_sink.h"

#include <capnp/message.h>
#include <capnp/serialize-packed.h>
#include <fcntl.h>
#include <kj/io.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstring>

#include "support/errors.h"
#include "formats/schema_convert.h"

namespace app {
namespace {

constexpr char kMagic[8] = {'A', 'C', 'T', 'A', 'R', 'C', 'H', '\2'};
constexpr std::uint32_t kMaxFrameBytes = 1u << 30;

// A record's unpacked size is bounded by its frame's: Cap'n Proto's packing shrinks runs of zero
// words about 100-fold, so a 1 MiB frame could declare a 1 GiB message. Our records unpack to 1.01-1.03
// times their frame (their meshes are dense numbers); eight times the frame and 64 KiB leaves room for
// any real one, and the reader refuses a larger message before allocating it.
capnp::ReaderOptions ArchiveLimits(std::uint64_t frameBytes = 16ull << 20) {
    capnp::ReaderOptions options;
    options.traversalLimitInWords = (8 * frameBytes + (64 << 10)) / sizeof(capnp::word);
    options.nestingLimit = 16;
    return options;
}

std::uint32_t Crc(const kj::byte* data, size_t size) {
    return static_cast<std::uint32_t>(crc32(crc32(0, nullptr, 0), data, static_cast<uInt>(size)));
}

void PutU32(kj::byte* out, std::uint32_t v) {
    for (int b = 0; b < 4; ++b) out[b] = static_cast<kj::byte>(v >> (8 * b));
}
std::uint32_t GetU32(const kj::byte* in) {
    std::uint32_t v = 0;
    for (int b = 0; b < 4; ++b) v |= std::uint32_t(in[b]) << (8 * b);
    return v;
}

ArchiveRecord Decode(capnp::MessageReader& message, bool withMeshes) {
    auto e = message.getRoot<schema::Evaluation>();
    ArchiveRecord r;
    r.id = e.getIndex();
    r.experiment = e.getExperiment();
    r.run = static_cast<int>(std::min<std::uint32_t>(e.getRun(), 1u << 30));
    r.generation = e.getGeneration();
    const std::string role = e.getRole();
    r.role = sim::FromName<Role>(role).value_or(Role::Grid);
    r.label = e.getLabel();
    r.job = GetJob(e);
    GetResultNumbers(e.getResult(), r.result);
    if (withMeshes) {
        r.result.initial = GetMesh(e.getInitial());
        r.result.final = GetMesh(e.getFinal());
    }
    return r;
}

// Appends the bytes whole, or takes back what part of them was written and throws (OutputError for
// a full disk): the archive stays whole records.
void AppendAll(int fd, const kj::byte* data, size_t size, const std::string& path) {
    const off_t before = lseek(fd, 0, SEEK_END);
    size_t written = 0;
    while (written < size) {
        const ssize_t n = ::write(fd, data + written, size - written);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int code = n < 0 ? errno : ENOSPC;
            if (before >= 0 && ftruncate(fd, before) != 0) {}
            ThrowWriteError("cannot write archive " + Quote(path), code);
        }
        written += static_cast<size_t>(n);
    }
}

// Reads up to `size` bytes; fewer only at the end of the file.
size_t ReadUpTo(std::FILE* file, kj::byte* into, size_t size) { return std::fread(into, 1, size, file); }

}  // namespace

ArchiveWriter::ArchiveWriter(const std::string& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) throw UsageError("cannot open archive " + Quote(path) + ": " + std::strerror(errno));
    struct stat info {};
    fstat(fd_, &info);
    if (info.st_size == 0) {
        AppendAll(fd_, reinterpret_cast<const kj::byte*>(kMagic), sizeof kMagic, path);
        return;
    }
    const ArchiveScan scan = ScanArchive(path, false, [](ArchiveRecord&&) { return true; });
    if (scan.version != 2) throw UsageError(Quote(path) + " was written by an older version; start afresh with --overwrite");
    if (scan.tornTail || scan.corrupt) throw UsageError(Quote(path) + ": " + scan.problem);
    next_ = scan.records;
}

ArchiveWriter::~ArchiveWriter() {
    if (fd_ >= 0) ::close(fd_);
}

namespace {

// One record's frame: payload length, its CRC-32, the packed payload, under evaluation id `index`.
std::vector<kj::byte> RecordFrame(const ArchiveRecord& r, std::uint64_t index) {
    capnp::MallocMessageBuilder message;
    auto e = message.initRoot<schema::Evaluation>();
    e.setIndex(index);
    e.setExperiment(r.experiment);
    e.setRun(static_cast<std::uint32_t>(r.run));
    e.setGeneration(r.generation);
    e.setRole(sim::Name(r.role));
    e.setLabel(r.label);
    SetJob(e, r.job);
    SetMesh(e.initInitial(), r.result.initial);
    SetMesh(e.initFinal(), r.result.final);
    SetResultNumbers(e.initResult(), r.result, r.job.model);
    kj::VectorOutputStream payload;
    capnp::writePackedMessage(payload, message);
    const auto bytes = payload.getArray();
    std::vector<kj::byte> frame(8 + bytes.size());
    PutU32(frame.data(), static_cast<std::uint32_t>(bytes.size()));
    PutU32(frame.data() + 4, Crc(bytes.begin(), bytes.size()));
    std::memcpy(frame.data() + 8, bytes.begin(), bytes.size());
    return frame;
}

}  // namespace

std::uint64_t ArchiveWriter::Append(const ArchiveRecord& r) {
    // Frame in memory, then one write: a kill leaves the whole frame or a torn tail.
    const std::vector<kj::byte> frame = RecordFrame(r, next_);
    AppendAll(fd_, frame.data(), frame.size(), path_);
    return next_++;
}

std::string ArchiveBytes(const std::vector<ArchiveRecord>& records) {
    std::string bytes(kMagic, sizeof kMagic);
    for (size_t id = 0; id < records.size(); ++id) {
        const std::vector<kj::byte> frame = RecordFrame(records[id], id);
        bytes.append(reinterpret_cast<const char*>(frame.data()), frame.size());
    }
    return bytes;
}

ArchiveScan ScanArchive(const std::string& path, bool withMeshes, const std::function<bool(ArchiveRecord&&)>& visit, ArchivePlace from) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) throw UsageError("cannot open archive " + Quote(path) + ": " + std::strerror(errno));
    struct stat info {};
    fstat(fileno(file), &info);
    if (!S_ISREG(info.st_mode)) {
        std::fclose(file);
        throw UsageError(Quote(path) + " is not a regular file");
    }
    ArchiveScan scan;
    kj::byte magic[8];
    const size_t got = ReadUpTo(file, magic, sizeof magic);
    std::vector<kj::byte> payload;
    if (got < sizeof magic && std::memcmp(magic, kMagic, got) == 0) {
        // Empty, or cut off inside the header: a version-2 archive with no records.
        scan.tornTail = got > 0;
        if (scan.tornTail) scan.problem = "the file ends inside its header";
        std::fclose(file);
        return scan;
    }
    if (got == sizeof magic && std::memcmp(magic, kMagic, sizeof magic) == 0) {
        scan.goodBytes = sizeof magic;
        if (from.byte > sizeof magic) {
            if (from.byte > static_cast<std::uint64_t>(info.st_size) || std::fseek(file, static_cast<long>(from.byte), SEEK_SET) != 0) {
                std::fclose(file);
                throw UsageError(Quote(path) + " has no record at byte " + std::to_string(from.byte) + " (was it cut back meanwhile?)");
            }
            scan.goodBytes = from.byte;
            scan.records = from.records;
        }
        for (;;) {
            kj::byte header[8];
            const size_t h = ReadUpTo(file, header, sizeof header);
            if (h == 0) break;
            const std::uint32_t size = GetU32(header), crc = GetU32(header + 4);
            if (h < sizeof header || size > kMaxFrameBytes) {
                scan.tornTail = h < sizeof header;
                scan.corrupt = !scan.tornTail;
                scan.problem = scan.tornTail ? "the file ends inside record " + std::to_string(scan.records) + " (a run cut off while writing)"
                                             : "record " + std::to_string(scan.records) + " has an impossible size: the archive is damaged";
                break;
            }
            payload.resize(size);
            if (ReadUpTo(file, payload.data(), size) < size) {
                scan.tornTail = true;
                scan.problem = "the file ends inside record " + std::to_string(scan.records) + " (a run cut off while writing)";
                break;
            }
            if (Crc(payload.data(), size) != crc) {
                scan.corrupt = true;
                scan.problem = "record " + std::to_string(scan.records) + " fails its checksum: the archive is damaged there";
                break;
            }
            try {
                kj::ArrayInputStream stream(kj::ArrayPtr<const kj::byte>(payload.data(), payload.size()));
                capnp::PackedMessageReader message(stream, ArchiveLimits(size));
                ArchiveRecord record = Decode(message, withMeshes);
                ++scan.records;
                scan.goodBytes += sizeof header + size;
                if (!visit(std::move(record))) break;
            } catch (const kj::Exception& error) {
                scan.corrupt = true;
                scan.problem = "record " + std::to_string(scan.records) + " does not decode (" + error.getDescription().cStr() + ")";
                break;
            } catch (const std::exception& error) {
                scan.corrupt = true;
                scan.problem = "record " + std::to_string(scan.records) + " does not decode (" + error.what() + ")";
                break;
            }
        }
        std::fclose(file);
        return scan;
    }
    // Version 1: packed messages back to back, no header, no checksums.
    if (from.byte > 0) {
        std::fclose(file);
        throw UsageError(Quote(path) + " is a version-1 archive: it reads only from its start");
    }
    scan.version = 1;
    std::rewind(file);
    kj::FdInputStream raw(fileno(file));
    kj::BufferedInputStreamWrapper stream(raw);
    // A record that does not decode: not an archive at all when it is the first, else a torn tail.
    auto unreadable = [&] {
        if (scan.records == 0) {
            std::fclose(file);
            throw UsageError(Quote(path) + " is not an evaluation archive");
        }
        scan.tornTail = true;
        scan.problem = "the file ends in an incomplete record after " + std::to_string(scan.records);
    };
    while (stream.tryGetReadBuffer().size() > 0) {
        try {
            capnp::PackedMessageReader message(stream, ArchiveLimits(static_cast<std::uint64_t>(info.st_size)));
            ArchiveRecord record = Decode(message, withMeshes);
            ++scan.records;
            if (!visit(std::move(record))) break;
        } catch (const std::exception&) {
            unreadable();
            break;
        } catch (const kj::Exception&) {
            unreadable();
            break;
        }
    }
    std::fclose(file);
    return scan;
}

ArchiveContents ReadArchive(const std::string& path, bool withMeshes) {
    ArchiveContents contents;
    contents.scan = ScanArchive(path, withMeshes, [&](ArchiveRecord&& r) {
        contents.records.push_back(std::move(r));
        return true;
    });
    return contents;
}

ArchiveRecord ReadArchiveRecord(const std::string& path, std::uint64_t id) {
    ArchiveRecord found;
    bool hit = false;
    std::uint64_t seen = 0;
    const ArchiveScan scan = ScanArchive(path, true, [&](ArchiveRecord&& r) {
        if (seen++ == id) {
            found = std::move(r);
            found.id = id;
            hit = true;
            return false;
        }
        return true;
    });
    if (!hit) {
        if (scan.records == 0) throw UsageError("--index " + std::to_string(id) + ": " + Quote(path) + " holds no evaluations");
        throw UsageError("--index " + std::to_string(id) + ": " + Quote(path) + " holds evaluations 0 to " + std::to_string(scan.records - 1));
    }
    return found;
}

void TruncateArchive(const std::string& path, std::uint64_t keep) {
    std::uint64_t seen = 0;
    // goodBytes is updated before each visit: stopping after record keep-1 leaves it at that record's end.
    const ArchiveScan scan = ScanArchive(path, false, [&](ArchiveRecord&&) { return ++seen < keep; });
    if (scan.version != 2) throw UsageError(Quote(path) + " was written by an older version and cannot be resumed; start afresh with --overwrite");
    if (scan.records < keep) {
        if (scan.corrupt) throw UsageError(Quote(path) + ": " + scan.problem + "; it cannot be resumed");
        throw UsageError(Quote(path) + " holds " + std::to_string(scan.records) + " evaluations, fewer than its checkpoint's " + std::to_string(keep));
    }
    const std::uint64_t bytes = keep == 0 ? 0 : scan.goodBytes;  // an empty file gets its header from the writer
    if (::truncate(path.c_str(), static_cast<off_t>(bytes)) != 0)
        throw UsageError("cannot cut " + Quote(path) + " back to its checkpoint: " + std::strerror(errno));
}

ArchiveSink::ArchiveSink(std::string path, bool resume) : path_(std::move(path)) {
    if (!resume) writer_ = std::make_unique<ArchiveWriter>(path_);
}

void ArchiveSink::Append(const ArchiveRecord& record) {
    if (!writer_) throw std::logic_error("a resumed archive is opened by RollBack");
    if (writer_->Append(record) != record.id) throw std::logic_error("an archive record out of id order");
}

void ArchiveSink::RollBack(std::uint64_t keep, const std::vector<ArchiveRecord>&) {
    writer_.reset();
    std::error_code ec;
    if (std::filesystem::exists(path_, ec)) TruncateArchive(path_, keep);
    writer_ = std::make_unique<ArchiveWriter>(path_);
}

}  // namespace app
