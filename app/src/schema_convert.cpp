#include "schema_convert.h"

#include <stdexcept>

namespace app {
namespace {

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};

// Meshes travel as three coordinate lists, float32 in archives and float64 on the wire.
template <class Value, class Builder>
void WriteXyz(Builder out, const sim::Positions& p) {
    const unsigned n = static_cast<unsigned>(p.Size());
    auto x = out.initX(n), y = out.initY(n), z = out.initZ(n);
    for (unsigned i = 0; i < n; ++i) {
        x.set(i, static_cast<Value>(p.x[i]));
        y.set(i, static_cast<Value>(p.y[i]));
        z.set(i, static_cast<Value>(p.z[i]));
    }
}

template <class Reader>
sim::Positions ReadXyz(Reader in) {
    // Fetch each list once: every get charges the whole list against the traversal limit.
    const auto x = in.getX(), y = in.getY(), z = in.getZ();
    const unsigned n = x.size();
    if (y.size() != n || z.size() != n) throw std::runtime_error("mesh coordinate lists differ in length");
    sim::Positions p;
    p.Resize(static_cast<int>(n));
    for (unsigned i = 0; i < n; ++i) {
        p.x[i] = x[i];
        p.y[i] = y[i];
        p.z[i] = z[i];
    }
    return p;
}

}  // namespace

void SetMesh(schema::Mesh::Builder out, const sim::Positions& p) { WriteXyz<float>(out, p); }
sim::Positions GetMesh(schema::Mesh::Reader in) { return ReadXyz(in); }
void SetExactMesh(schema::ExactMesh::Builder out, const sim::Positions& p) { WriteXyz<double>(out, p); }
sim::Positions GetExactMesh(schema::ExactMesh::Reader in) { return ReadXyz(in); }



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





void SetParams(schema::SimParams::Builder p, const sim::SimParams& params) {
    p.setIterations(static_cast<std::uint32_t>(params.iterations));
    p.setLoad(params.load == sim::Load::Inflate ? schema::Load::INFLATE : params.load == sim::Load::Stretch ? schema::Load::STRETCH : schema::Load::NONE);
    p.setSpringConstant(params.springConstant);
    p.setPressureScale(params.pressureScale);
    p.setPullForce(params.pullForce);
    p.setStepScale(params.stepScale);
    p.setDivergenceLimit(params.divergenceLimit);
    p.setPrecision(params.precision == sim::Precision::Float ? schema::Precision::FLOAT : schema::Precision::DOUBLE);
}

sim::SimParams GetParams(schema::SimParams::Reader p) {
    sim::SimParams params;
    params.iterations = static_cast<int>(std::min<std::uint32_t>(p.getIterations(), 2'000'000'000u));
    params.load = p.getLoad() == schema::Load::INFLATE ? sim::Load::Inflate : p.getLoad() == schema::Load::STRETCH ? sim::Load::Stretch : sim::Load::None;
    params.springConstant = p.getSpringConstant();
    params.pressureScale = p.getPressureScale();
    params.pullForce = p.getPullForce();
    params.stepScale = p.getStepScale();
    params.divergenceLimit = p.getDivergenceLimit();
    params.precision = p.getPrecision() == schema::Precision::FLOAT ? sim::Precision::Float : sim::Precision::Double;
    return params;
}

}  // namespace app
