#include "sim/shape.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace sim {
namespace {

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};

bool AllFinite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// t in [0, 1] along the part of the helix the spline covers, or -1 for vertices it leaves at rho = 1.
double SplineParameter(SplineRegion region, const MeshDef& def, int vertex) {
    const int n = VertexCount(def);
    if (region == SplineRegion::Entire) return static_cast<double>(vertex) / (n - 1);
    const int band = kClampedTurns * def.resolution;
    if (vertex < band || vertex >= n - band) return -1.0;
    return static_cast<double>(vertex - band) / (n - 2 * band - 1);
}

// Scales the bare helix's x and y by a per-vertex radius.
Positions HelixWithRadius(const MeshDef& def, const std::vector<double>& rho) {
    Positions p = BaseHelix(def);
    for (int i = 0; i < p.Size(); ++i) {
        p.x[i] *= rho[i];
        p.y[i] *= rho[i];
    }
    return p;
}

std::vector<double> SineRadii(const MeshDef& def, double amplitude, double a, double b, bool absolute) {
    const int n = VertexCount(def);
    std::vector<double> rho(n);
    for (int i = 0; i < n; ++i) {
        const double t = static_cast<double>(i) / (n - 1);
        const double s = std::sin(a + t * (b - a));
        rho[i] = amplitude * (absolute ? std::fabs(s) : s);
    }
    return rho;
}

}  // namespace

const char* ShapeName(const Shape& shape) { return Name(KindOf(shape)); }

std::string ShapeError(const Shape& shape, const MeshDef& def) {
    if (def.resolution < kMinResolution) return "resolution must be at least " + std::to_string(kMinResolution);
    if (def.turns < kMinTurns) return "turns must be at least " + std::to_string(kMinTurns);
    if (static_cast<long long>(def.resolution) * def.turns > kMaxVertices)
        return "mesh has more than " + std::to_string(kMaxVertices) + " vertices";
    const int n = VertexCount(def);
    auto sineError = [](double amplitude, double a, double b) -> std::string {
        if (!std::isfinite(amplitude)) return "amplitude must be a finite number";
        if (!std::isfinite(a) || !std::isfinite(b)) return "phase range must be finite numbers";
        return "";
    };
    return std::visit(
        Overloaded{
            [](const CylinderShape&) -> std::string { return ""; },
            [&](const SineShape& s) { return sineError(s.amplitude, s.phaseStart, s.phaseEnd); },
            [&](const AbsSineShape& s) { return sineError(s.amplitude, s.phaseStart, s.phaseEnd); },
            [&](const BSplineShape& s) -> std::string {
                const size_t count = s.splines.size();
                if (count != 1 && count != 2 && count != 4)
                    return "bspline needs 1, 2 or 4 splines (sectors), got " + std::to_string(count);
                if (static_cast<int>(count) > def.resolution) return "more splines than vertices per turn";
                for (size_t k = 0; k < count; ++k) {
                    if (s.splines[k].size() < 4)
                        return "spline " + std::to_string(k + 1) + " has " + std::to_string(s.splines[k].size()) +
                               " control points; a cubic B-spline needs at least 4";
                    if (!AllFinite(s.splines[k]))
                        return "spline " + std::to_string(k + 1) + " has a control point that is not finite";
                }
                return "";
            },
            [&](const FreeXYShape& s) -> std::string {
                if (static_cast<int>(s.dx.size()) != n || static_cast<int>(s.dy.size()) != n)
                    return "free-xy needs one (dx, dy) pair per vertex: " + std::to_string(n) + " pairs, got " +
                           std::to_string(std::min(s.dx.size(), s.dy.size()));
                if (!AllFinite(s.dx) || !AllFinite(s.dy)) return "free-xy offsets must be finite numbers";
                return "";
            },
            [&](const MeshShape& s) -> std::string {
                if (s.positions.Size() != n)
                    return "mesh has " + std::to_string(s.positions.Size()) + " vertices, expected " +
                           std::to_string(n) + " (" + std::to_string(def.resolution) + " per turn x " +
                           std::to_string(def.turns) + " turns)";
                if (!AllFinite(s.positions.x) || !AllFinite(s.positions.y) || !AllFinite(s.positions.z))
                    return "mesh has a coordinate that is not finite";
                return "";
            },
        },
        shape);
}

double EvaluateBSpline(const std::vector<double>& c, double t) {
    assert(c.size() >= 4);
    const int m = static_cast<int>(c.size());
    const double x = t * (m - 3);
    const int s = std::min(static_cast<int>(std::floor(x)), m - 4);
    const double u = x - s;
    const double u2 = u * u;
    const double u3 = u2 * u;
    const double b0 = (1 - u) * (1 - u) * (1 - u) / 6.0;
    const double b1 = (3 * u3 - 6 * u2 + 4) / 6.0;
    const double b2 = (-3 * u3 + 3 * u2 + 3 * u + 1) / 6.0;
    const double b3 = u3 / 6.0;
    return b0 * c[s] + b1 * c[s + 1] + b2 * c[s + 2] + b3 * c[s + 3];
}

double DesignRadius(const Shape& shape, double t, double angle, double clampFraction) {
    if (const auto* s = std::get_if<SineShape>(&shape)) return s->amplitude * std::sin(s->phaseStart + t * (s->phaseEnd - s->phaseStart));
    if (const auto* a = std::get_if<AbsSineShape>(&shape))
        return a->amplitude * std::fabs(std::sin(a->phaseStart + t * (a->phaseEnd - a->phaseStart)));
    if (const auto* b = std::get_if<BSplineShape>(&shape)) {
        const int sectors = static_cast<int>(b->splines.size());
        double turn = angle / (2 * std::numbers::pi);
        turn -= std::floor(turn);
        const int sector = std::min(sectors - 1, static_cast<int>(turn * sectors));
        if (b->region == SplineRegion::Entire) return EvaluateBSpline(b->splines[sector], t);
        // Middle: the clamped rings keep the base radius; the spline spans the free part.
        if (t < clampFraction - 1e-12 || t > 1 - clampFraction + 1e-12) return 1.0;
        return EvaluateBSpline(b->splines[sector], std::clamp((t - clampFraction) / (1 - 2 * clampFraction), 0.0, 1.0));
    }
    if (std::holds_alternative<CylinderShape>(shape)) return 1.0;
    return std::nan("");
}

Positions BuildInitialPositions(const Shape& shape, const MeshDef& def) {
    assert(ShapeError(shape, def).empty());
    const int n = VertexCount(def);
    return std::visit(
        Overloaded{
            [&](const CylinderShape&) { return BaseHelix(def); },
            [&](const SineShape& s) {
                return HelixWithRadius(def, SineRadii(def, s.amplitude, s.phaseStart, s.phaseEnd, false));
            },
            [&](const AbsSineShape& s) {
                return HelixWithRadius(def, SineRadii(def, s.amplitude, s.phaseStart, s.phaseEnd, true));
            },
            [&](const BSplineShape& s) {
                const int sectors = static_cast<int>(s.splines.size());
                std::vector<double> rho(n, 1.0);
                for (int i = 0; i < n; ++i) {
                    const double t = SplineParameter(s.region, def, i);
                    if (t < 0) continue;
                    const int sector = ((i % def.resolution) * sectors) / def.resolution;
                    rho[i] = EvaluateBSpline(s.splines[sector], t);
                }
                return HelixWithRadius(def, rho);
            },
            [&](const FreeXYShape& s) {
                Positions p = BaseHelix(def);
                for (int i = 0; i < n; ++i) {
                    p.x[i] += s.dx[i];
                    p.y[i] += s.dy[i];
                }
                return p;
            },
            [&](const MeshShape& s) { return s.positions; },
        },
        shape);
}

}  // namespace sim
