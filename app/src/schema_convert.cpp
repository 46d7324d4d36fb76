#include "schema_convert.h"

#include <stdexcept>

namespace app {
namespace {

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};

// Enums convert by value: the schema lists them in sim's order. A value from a newer writer that
// this build does not know is an error, never a silent default.
template <class Sim, class Schema>
Sim EnumFromSchema(Schema value, const char* what) {
    const auto index = static_cast<size_t>(value);
    if (index >= sim::EnumNames<Sim>::table.size()) throw std::runtime_error(std::string("unknown ") + what + " value " + std::to_string(index));
    return static_cast<Sim>(index);
}
template <class Schema, class Sim>
Schema EnumToSchema(Sim value) {
    return static_cast<Schema>(static_cast<std::uint16_t>(value));
}
static_assert(static_cast<int>(schema::Status::INVALID_GEOMETRY) == static_cast<int>(sim::Status::InvalidGeometry));
static_assert(static_cast<int>(schema::Load::NONE) == static_cast<int>(sim::Load::None));
static_assert(static_cast<int>(schema::Precision::DOUBLE) == static_cast<int>(sim::Precision::Double));
static_assert(static_cast<int>(schema::SplineRegion::MIDDLE) == static_cast<int>(sim::SplineRegion::Middle));

template <class Value, class List>
void Fill(List list, const std::vector<double>& values) {
    for (unsigned i = 0; i < values.size(); ++i) list.set(i, static_cast<Value>(values[i]));
}

template <class List>
std::vector<double> Copy(List list) {
    std::vector<double> values(list.size());
    for (unsigned i = 0; i < list.size(); ++i) values[i] = list[i];
    return values;
}

bool FloatIsExact(const sim::Positions& p) {
    for (const auto* axis : {&p.x, &p.y, &p.z})
        for (double v : *axis)
            if (static_cast<double>(static_cast<float>(v)) != v && !std::isnan(v)) return false;
    return true;
}

sim::Positions Checked(std::vector<double> x, std::vector<double> y, std::vector<double> z) {
    if (y.size() != x.size() || z.size() != x.size()) throw std::runtime_error("mesh coordinate lists differ in length");
    sim::Positions p;
    p.x = std::move(x);
    p.y = std::move(y);
    p.z = std::move(z);
    return p;
}

}  // namespace

void SetMesh(schema::Mesh::Builder out, const sim::Positions& p) {
    const unsigned n = static_cast<unsigned>(p.Size());
    if (FloatIsExact(p)) {
        Fill<float>(out.initX(n), p.x);
        Fill<float>(out.initY(n), p.y);
        Fill<float>(out.initZ(n), p.z);
    } else {
        Fill<double>(out.initExactX(n), p.x);
        Fill<double>(out.initExactY(n), p.y);
        Fill<double>(out.initExactZ(n), p.z);
    }
}

sim::Positions GetMesh(schema::Mesh::Reader in) {
    // Fetch each list once: every get charges the whole list against the traversal limit.
    if (in.hasExactX()) return Checked(Copy(in.getExactX()), Copy(in.getExactY()), Copy(in.getExactZ()));
    return Checked(Copy(in.getX()), Copy(in.getY()), Copy(in.getZ()));
}

void SetExactMesh(schema::ExactMesh::Builder out, const sim::Positions& p) {
    const unsigned n = static_cast<unsigned>(p.Size());
    Fill<double>(out.initX(n), p.x);
    Fill<double>(out.initY(n), p.y);
    Fill<double>(out.initZ(n), p.z);
}

sim::Positions GetExactMesh(schema::ExactMesh::Reader in) { return Checked(Copy(in.getX()), Copy(in.getY()), Copy(in.getZ())); }

void SetShape(schema::Shape::Builder out, const sim::Shape& shape) {
    auto sine = [](auto b, double amplitude, double a, double z) {
        b.setAmplitude(amplitude);
        b.setPhaseStart(a);
        b.setPhaseEnd(z);
    };
    std::visit(Overloaded{
                   [&](const sim::CylinderShape&) { out.setCylinder(); },
                   [&](const sim::SineShape& s) { sine(out.initSine(), s.amplitude, s.phaseStart, s.phaseEnd); },
                   [&](const sim::AbsSineShape& s) { sine(out.initAbsSine(), s.amplitude, s.phaseStart, s.phaseEnd); },
                   [&](const sim::BSplineShape& s) {
                       auto b = out.initBspline();
                       b.setRegion(EnumToSchema<schema::SplineRegion>(s.region));
                       auto splines = b.initSplines(static_cast<unsigned>(s.splines.size()));
                       for (unsigned k = 0; k < s.splines.size(); ++k)
                           Fill<double>(splines[k].initControlPoints(static_cast<unsigned>(s.splines[k].size())), s.splines[k]);
                   },
                   [&](const sim::FreeXYShape& s) {
                       auto b = out.initFreeXY();
                       Fill<double>(b.initDx(static_cast<unsigned>(s.dx.size())), s.dx);
                       Fill<double>(b.initDy(static_cast<unsigned>(s.dy.size())), s.dy);
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
            sim::BSplineShape b{EnumFromSchema<sim::SplineRegion>(s.getRegion(), "spline region"), {}};
            for (auto spline : s.getSplines()) b.splines.push_back(Copy(spline.getControlPoints()));
            return b;
        }
        case schema::Shape::FREE_X_Y: return sim::FreeXYShape{Copy(in.getFreeXY().getDx()), Copy(in.getFreeXY().getDy())};
        case schema::Shape::MESH: return sim::MeshShape{GetMesh(in.getMesh())};
    }
    throw std::runtime_error("unknown shape kind");
}

void SetParams(schema::SimParams::Builder p, const sim::SimParams& params) {
    p.setIterations(static_cast<std::uint32_t>(params.iterations));
    p.setLoad(EnumToSchema<schema::Load>(params.load));
    p.setSpringConstant(params.springConstant);
    p.setPressureScale(params.pressureScale);
    p.setPullForce(params.pullForce);
    p.setStepScale(params.stepScale);
    p.setDivergenceLimit(params.divergenceLimit);
    p.setPrecision(EnumToSchema<schema::Precision>(params.precision));
}

sim::SimParams GetParams(schema::SimParams::Reader p) {
    sim::SimParams params;
    params.iterations = static_cast<int>(std::min<std::uint32_t>(p.getIterations(), 2'000'000'000u));
    params.load = EnumFromSchema<sim::Load>(p.getLoad(), "load");
    params.springConstant = p.getSpringConstant();
    params.pressureScale = p.getPressureScale();
    params.pullForce = p.getPullForce();
    params.stepScale = p.getStepScale();
    params.divergenceLimit = p.getDivergenceLimit();
    params.precision = EnumFromSchema<sim::Precision>(p.getPrecision(), "precision");
    return params;
}

void SetResultNumbers(schema::EvalResult::Builder r, const sim::SimResult& result) {
    r.setStatus(EnumToSchema<schema::Status>(result.status));
    r.setFitness(result.fitness);
    r.setContractionPercent(result.contractionPercent);
    r.setIterationsRun(static_cast<std::uint32_t>(result.iterationsRun));
    r.setElapsedMs(result.elapsedMs);
}

void GetResultNumbers(schema::EvalResult::Reader r, sim::SimResult& result) {
    result.status = EnumFromSchema<sim::Status>(r.getStatus(), "status");
    result.fitness = r.getFitness();
    result.contractionPercent = r.getContractionPercent();
    result.iterationsRun = static_cast<int>(std::min<std::uint32_t>(r.getIterationsRun(), 2'000'000'000u));
    result.elapsedMs = r.getElapsedMs();
}

}  // namespace app
