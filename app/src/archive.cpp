#include "archive.h"

#include <capnp/message.h>
#include <capnp/serialize-packed.h>
#include <fcntl.h>
#include <kj/io.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "actuator.capnp.h"
#include "cli_options.h"
#include "mesh_io.h"

namespace app {
namespace {

namespace schema = actuator::schema;

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};

void SetMesh(schema::Mesh::Builder out, const sim::Positions& p) {
    const unsigned n = static_cast<unsigned>(p.Size());
    auto x = out.initX(n), y = out.initY(n), z = out.initZ(n);
    for (unsigned i = 0; i < n; ++i) {
        x.set(i, static_cast<float>(p.x[i]));
        y.set(i, static_cast<float>(p.y[i]));
        z.set(i, static_cast<float>(p.z[i]));
    }
}

sim::Positions GetMesh(schema::Mesh::Reader in) {
    sim::Positions p;
    const unsigned n = in.getX().size();
    if (in.getY().size() != n || in.getZ().size() != n) throw std::runtime_error("mesh coordinate lists differ in length");
    p.Resize(static_cast<int>(n));
    for (unsigned i = 0; i < n; ++i) {
        p.x[i] = in.getX()[i];
        p.y[i] = in.getY()[i];
        p.z[i] = in.getZ()[i];
    }
    return p;
}

void SetSplines(capnp::List<schema::Spline>::Builder out, const std::vector<std::vector<double>>& splines) {
    for (unsigned k = 0; k < splines.size(); ++k) {
        auto points = out[k].initControlPoints(static_cast<unsigned>(splines[k].size()));
        for (unsigned j = 0; j < splines[k].size(); ++j) points.set(j, splines[k][j]);
    }
}

std::vector<std::vector<double>> GetSplines(capnp::List<schema::Spline>::Reader in) {
    std::vector<std::vector<double>> splines;
    for (auto spline : in) {
        std::vector<double> points;
        for (double c : spline.getControlPoints()) points.push_back(c);
        splines.push_back(std::move(points));
    }
    return splines;
}

void SetShape(schema::Shape::Builder out, const sim::Shape& shape) {
    std::visit(Overloaded{
                   [&](const sim::CylinderShape&) { out.setCylinder(); },
                   [&](const sim::SineShape& s) {
                       auto b = out.initSine();
                       b.setAmplitude(s.amplitude); b.setPhaseStart(s.phaseStart); b.setPhaseEnd(s.phaseEnd);
                   },
                   [&](const sim::AbsSineShape& s) {
                       auto b = out.initAbsSine();
                       b.setAmplitude(s.amplitude); b.setPhaseStart(s.phaseStart); b.setPhaseEnd(s.phaseEnd);
                   },
                   [&](const sim::BSplineShape& s) {
                       auto b = out.initBspline();
                       b.setRegion(s.region == sim::SplineRegion::Entire ? schema::SplineRegion::ENTIRE : schema::SplineRegion::MIDDLE);
                       SetSplines(b.initSplines(static_cast<unsigned>(s.splines.size())), s.splines);
                   },
                   [&](const sim::FreeXYShape& s) {
                       auto b = out.initFreeXY();
                       auto dx = b.initDx(static_cast<unsigned>(s.dx.size())), dy = b.initDy(static_cast<unsigned>(s.dy.size()));
                       for (unsigned i = 0; i < s.dx.size(); ++i) { dx.set(i, s.dx[i]); dy.set(i, s.dy[i]); }
                   },
                   [&](const sim::MeshShape& s) { SetMesh(out.initMesh(), s.positions); },
               },
               shape);
}

sim::Shape GetShape(schema::Shape::Reader in) {
    switch (in.which()) {
        case schema::Shape::CYLINDER: return sim::CylinderShape{};
        case schema::Shape::SINE: {
            auto s = in.getSine();
            return sim::SineShape{s.getAmplitude(), s.getPhaseStart(), s.getPhaseEnd()};
        }
        case schema::Shape::ABS_SINE: {
            auto s = in.getAbsSine();
            return sim::AbsSineShape{s.getAmplitude(), s.getPhaseStart(), s.getPhaseEnd()};
        }
        case schema::Shape::BSPLINE: {
            auto s = in.getBspline();
            return sim::BSplineShape{s.getRegion() == schema::SplineRegion::ENTIRE ? sim::SplineRegion::Entire : sim::SplineRegion::Middle,
                                     GetSplines(s.getSplines())};
        }
        case schema::Shape::FREE_X_Y: {
            sim::FreeXYShape s;
            for (double v : in.getFreeXY().getDx()) s.dx.push_back(v);
            for (double v : in.getFreeXY().getDy()) s.dy.push_back(v);
            return s;
        }
        case schema::Shape::MESH: return sim::MeshShape{GetMesh(in.getMesh())};
    }
    throw std::runtime_error("unknown shape kind");
}

schema::Status ToSchema(sim::Status s) {
    return s == sim::Status::Ok ? schema::Status::OK : s == sim::Status::NaN ? schema::Status::NOT_A_NUMBER : schema::Status::DIVERGED;
}
sim::Status FromSchema(schema::Status s) {
    return s == schema::Status::OK ? sim::Status::Ok : s == schema::Status::NOT_A_NUMBER ? sim::Status::NaN : sim::Status::Diverged;
}


}  // namespace

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
    SetSplines(e.initGenome(static_cast<unsigned>(r.genome.size())), r.genome);
    SetShape(e.initShape(), r.shape);
    auto p = e.initParams();
    p.setIterations(static_cast<std::uint32_t>(r.params.iterations));
    p.setLoad(r.params.load == sim::Load::Inflate ? schema::Load::INFLATE : r.params.load == sim::Load::Stretch ? schema::Load::STRETCH : schema::Load::NONE);
    p.setSpringConstant(r.params.springConstant);
    p.setPressureScale(r.params.pressureScale);
    p.setPullForce(r.params.pullForce);
    p.setStepScale(r.params.stepScale);
    p.setDivergenceLimit(r.params.divergenceLimit);
    p.setPrecision(r.params.precision == sim::Precision::Float ? schema::Precision::FLOAT : schema::Precision::DOUBLE);
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
            r.genome = GetSplines(e.getGenome());
            r.shape = GetShape(e.getShape());
            auto p = e.getParams();
            r.params.iterations = static_cast<int>(p.getIterations());
            r.params.load = p.getLoad() == schema::Load::INFLATE ? sim::Load::Inflate : p.getLoad() == schema::Load::STRETCH ? sim::Load::Stretch : sim::Load::None;
            r.params.springConstant = p.getSpringConstant();
            r.params.pressureScale = p.getPressureScale();
            r.params.pullForce = p.getPullForce();
            r.params.stepScale = p.getStepScale();
            r.params.divergenceLimit = p.getDivergenceLimit();
            r.params.precision = p.getPrecision() == schema::Precision::FLOAT ? sim::Precision::Float : sim::Precision::Double;
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
