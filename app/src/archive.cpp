#include "archive.h"

#include <capnp/message.h>
#include <capnp/serialize-packed.h>
#include <fcntl.h>
#include <kj/io.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "schema_convert.h"
#include "cli_options.h"
#include "mesh_io.h"

namespace app {

void SetResult(ArchivedEvaluation& a, const sim::SimResult& r) {
    a.initial = r.initial;
    a.final = r.final;
    a.status = r.status;
    a.fitness = r.fitness;
    a.contractionPercent = r.contractionPercent;
    a.iterationsRun = r.iterationsRun;
    a.elapsedMs = r.elapsedMs;
}

sim::SimResult ResultOf(const ArchivedEvaluation& a) {
    sim::SimResult r;
    r.initial = a.initial;
    r.final = a.final;
    r.status = a.status;
    r.fitness = a.fitness;
    r.contractionPercent = a.contractionPercent;
    r.iterationsRun = a.iterationsRun;
    r.elapsedMs = a.elapsedMs;
    return r;
}

ArchiveWriter::ArchiveWriter(const std::string& path) : path_(path) {
    // Continue numbering after what the archive already holds (a resumed run appends to it).
    if (access(path.c_str(), F_OK) == 0) next_ = ReadArchive(path, false).evaluations.size();
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0) throw UsageError("cannot open archive '" + path + "': " + std::strerror(errno));
}

ArchiveWriter::~ArchiveWriter() {
    if (fd_ >= 0) ::close(fd_);
}

void ArchiveWriter::Append(ArchivedEvaluation r) {
    r.index = next_;
    capnp::MallocMessageBuilder message;
    auto e = message.initRoot<schema::Evaluation>();
    e.setIndex(r.index);
    e.setExperiment(r.experiment);
    e.setRun(static_cast<std::uint32_t>(r.run));
    e.setGeneration(r.generation);
    e.setLabel(r.label);
    SetShape(e.initShape(), r.shape);
    SetParams(e.initParams(), r.params);
    e.initMeshSize().setResolution(static_cast<std::uint32_t>(r.mesh.resolution));
    e.getMeshSize().setTurns(static_cast<std::uint32_t>(r.mesh.turns));
    SetMesh(e.initInitial(), r.initial);
    SetMesh(e.initFinal(), r.final);
    auto result = e.initResult();
    result.setStatus(ToSchema(r.status));
    result.setFitness(r.fitness);
    result.setContractionPercent(r.contractionPercent);
    result.setIterationsRun(static_cast<std::uint32_t>(r.iterationsRun));
    result.setElapsedMs(r.elapsedMs);

    // Pack in memory, then one write: a kill leaves either the whole message or a torn tail.
    kj::VectorOutputStream bytes;
    capnp::writePackedMessage(bytes, message);
    const auto data = bytes.getArray();
    size_t written = 0;
    while (written < data.size()) {
        const ssize_t n = ::write(fd_, data.begin() + written, data.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw UsageError("cannot write archive '" + path_ + "': " + std::strerror(errno));
        written += static_cast<size_t>(n);
    }
    ++next_;
}

ArchiveContents ReadArchive(const std::string& path, bool withMeshes) {
    const std::string text = ReadTextFile(path);
    ArchiveContents contents;
    kj::ArrayInputStream stream(kj::ArrayPtr<const kj::byte>(reinterpret_cast<const kj::byte*>(text.data()), text.size()));
    capnp::ReaderOptions options;
    options.traversalLimitInWords = 64ull << 20;  // 512 MiB: far above any real evaluation
    options.nestingLimit = 16;
    while (stream.tryGetReadBuffer().size() > 0) {
        try {
            capnp::PackedMessageReader message(stream, options);
            auto e = message.getRoot<schema::Evaluation>();
            ArchivedEvaluation r;
            r.index = e.getIndex();
            r.experiment = e.getExperiment();
            r.run = static_cast<int>(e.getRun());
            r.generation = e.getGeneration();
            r.label = e.getLabel();
            r.shape = GetShape(e.getShape());
            r.params = GetParams(e.getParams());
            r.mesh = sim::MeshDef{static_cast<int>(e.getMeshSize().getResolution()), static_cast<int>(e.getMeshSize().getTurns())};
            if (withMeshes) {
                r.initial = GetMesh(e.getInitial());
                r.final = GetMesh(e.getFinal());
            }
            auto result = e.getResult();
            r.status = FromSchema(result.getStatus());
            r.fitness = result.getFitness();
            r.contractionPercent = result.getContractionPercent();
            r.iterationsRun = static_cast<int>(result.getIterationsRun());
            r.elapsedMs = result.getElapsedMs();
            contents.evaluations.push_back(std::move(r));
        } catch (const kj::Exception& error) {
            contents.truncated = true;
            contents.problem = error.getDescription().cStr();
            break;
        } catch (const std::exception& error) {
            contents.truncated = true;
            contents.problem = error.what();
            break;
        }
    }
    return contents;
}

}  // namespace app
