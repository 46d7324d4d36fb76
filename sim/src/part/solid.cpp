#include "sim/solid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>

#include "sim/shell.h"
#include "shell/shell_problem.h"

namespace sim {
namespace {

using Vec = std::array<double, 3>;

Vec Sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec Cross(const Vec& a, const Vec& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double Dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::string Format(const char* format, double a, double b, double c = 0, double d = 0) {
    char text[320];
    std::snprintf(text, sizeof text, format, a, b, c, d);
    return text;
}

// Faces joined by exact coordinates: a point computed once (or by the same expression) and used by
// several faces is one vertex, so the faces meet edge to edge.
class Builder {
public:
    int Vertex(const Vec& p) {
        const auto [it, inserted] = index_.try_emplace(p, static_cast<int>(mesh_.vertices.size()));
        if (inserted) mesh_.vertices.push_back(p);
        return it->second;
    }
    // a, b, c counter-clockwise seen from outside.
    void Triangle(int a, int b, int c) { mesh_.triangles.push_back({a, b, c}); }
    void Quad(int a, int b, int c, int d) {
        Triangle(a, b, c);
        Triangle(a, c, d);
    }
    // A triangle of a face whose outward normal is known: turned to face it.
    void Facing(int a, int b, int c, const Vec& normal) {
        const Vec n = Cross(Sub(mesh_.vertices[b], mesh_.vertices[a]), Sub(mesh_.vertices[c], mesh_.vertices[a]));
        if (Dot(n, normal) < 0) std::swap(b, c);
        Triangle(a, b, c);
    }
    // A quad a b c d (in order around it) as two triangles facing `normal`.
    void FacingQuad(int a, int b, int c, int d, const Vec& normal) {
        Facing(a, b, c, normal);
        Facing(a, c, d, normal);
    }
    // A convex polygon (in order around it) fanned from its first vertex.
    void Fan(const std::vector<int>& polygon, const Vec& normal) {
        for (size_t k = 1; k + 1 < polygon.size(); ++k) Facing(polygon[0], polygon[k], polygon[k + 1], normal);
    }
    const Vec& At(int v) const { return mesh_.vertices[v]; }
    // The mesh, without vertices no triangle uses (points computed for a face that a slot removed).
    TriangleMesh Take() {
        std::vector<int> renumber(mesh_.vertices.size(), -1);
        TriangleMesh out;
        for (auto& t : mesh_.triangles)
            for (int& v : t) {
                if (renumber[v] < 0) {
                    renumber[v] = static_cast<int>(out.vertices.size());
                    out.vertices.push_back(mesh_.vertices[v]);
                }
                v = renumber[v];
            }
        out.triangles = std::move(mesh_.triangles);
        mesh_ = {};
        index_.clear();
        return out;
    }

private:
    TriangleMesh mesh_;
    std::map<Vec, int> index_;
};

// Samples on rings of constant height: ring j (0 .. nz-1) from the bottom end, sample i around.
struct Grid {
    int nz = 0, nt = 0;
    std::vector<Vec> p;
    Vec& At(int j, int i) { return p[static_cast<size_t>(j) * nt + (i % nt)]; }
    const Vec& At(int j, int i) const { return p[static_cast<size_t>(j) * nt + (i % nt)]; }
};

// cos and sin of sample i's angle, exact at the quarter turns (the mold's split plane and box
// corners need points that lie exactly on y = 0 and on the diagonals' rays).
std::pair<double, double> Direction(int i, int nt) {
    const int k = i % nt;
    if (k == 0) return {1, 0};
    if (4 * k == nt) return {0, 1};
    if (2 * k == nt) return {-1, 0};
    if (4 * k == 3 * nt) return {0, -1};
    const double angle = 2 * std::numbers::pi * k / nt;
    return {std::cos(angle), std::sin(angle)};
}

double Degrees(int i, int nt) { return 360.0 * (i % nt) / nt; }

}  // namespace

RadiusField MeasuredRadiusField(const EvalJob& job, std::string* error) {
    const double pi = std::numbers::pi;
    if (job.model == ModelKind::Thesis) {
        if (std::string e = ShapeError(job.shape, job.Thesis().mesh); !e.empty()) {
            *error = e;
            return {};
        }
        const Positions p = BuildInitialPositions(job.shape, job.Thesis().mesh);
        const int r = job.Thesis().mesh.resolution, n = VertexCount(job.Thesis().mesh), turns = job.Thesis().mesh.turns;
        std::vector<double> rho(static_cast<size_t>(n));
        for (int i = 0; i < n; ++i) rho[i] = std::hypot(p.x[i], p.y[i]);
        // Vertex i lies at helix angle 2 pi i / R (x = sin, y = cos) and height (i + 1) / R turns.
        return [rho, r, n, turns, pi](double t, double angle) {
            auto along = [&](double s) {  // the radius at a fractional vertex index, clamped to the helix
                s = std::clamp(s, 0.0, static_cast<double>(n - 1));
                const int k = std::min(static_cast<int>(s), n - 2);
                return rho[k] + (s - k) * (rho[k + 1] - rho[k]);
            };
            double turn = (0.5 * pi - angle) / (2 * pi);
            turn -= std::floor(turn);
            const double h = t * turns, first = turn + 1.0 / r;  // the helix passes this angle at heights first + k
            const double k = std::floor(h - first);
            const double below = (turn + k) * r, w = std::clamp(h - (first + k), 0.0, 1.0);
            return (1 - w) * along(below) + w * along(below + r);
        };
    }
    const ShellProblem problem = BuildTubeProblem(job.Shell(), job.shape, job.model == ModelKind::Shell, error);
    if (!error->empty()) return {};
    const GeometryDef& g = job.Shell().geometry;
    const int r = g.ringVertices, rings = RingCount(g);
    std::vector<double> rho(static_cast<size_t>(r) * rings);
    for (int v = 0; v < r * rings; ++v) rho[v] = std::hypot(problem.rest.x[v], problem.rest.y[v]) / g.radiusMm;
    // Ring j's vertex i lies at angle 2 pi (i + j/2) / R, ring j at height fraction heights[j] (graded
    // meshes space them unevenly).
    std::vector<double> heights = RingHeightsMm(g);
    for (double& z : heights) z /= g.lengthMm;
    return [rho, r, rings, pi, heights](double t, double angle) {
        auto ring = [&](int j) {
            double u = angle * r / (2 * pi) - 0.5 * j;
            u -= r * std::floor(u / r);
            const int i = static_cast<int>(u) % r;
            const double f = u - std::floor(u);
            return rho[static_cast<size_t>(j) * r + i] + f * (rho[static_cast<size_t>(j) * r + (i + 1) % r] - rho[static_cast<size_t>(j) * r + i]);
        };
        const double s = std::clamp(t, 0.0, 1.0);
        const int j = std::clamp(static_cast<int>(std::upper_bound(heights.begin(), heights.end(), s) - heights.begin()) - 1, 0, rings - 2);
        const double f = std::clamp((s - heights[j]) / (heights[j + 1] - heights[j]), 0.0, 1.0);
        return ring(j) + f * (ring(j + 1) - ring(j));
    };
}

double SectorBlendRadians(const PartDef& part) {
    // Two wall thicknesses of arc at the base radius, and at least three samples.
    return std::max(2 * part.thicknessMm / part.radiusMm, 3 * 2 * std::numbers::pi / part.angularSamples);
}

double DemouldingStretchLimit(const MaterialDef& material) { return std::min(StretchLimit(material), 3.0); }

double MeshVolume(const TriangleMesh& mesh) {
    double six = 0;
    for (const auto& t : mesh.triangles) six += Dot(mesh.vertices[t[0]], Cross(mesh.vertices[t[1]], mesh.vertices[t[2]]));
    return six / 6;
}

std::array<double, 6> MeshBounds(const TriangleMesh& mesh) {
    std::array<double, 6> b{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (const Vec& v : mesh.vertices)
        for (int k = 0; k < 3; ++k) {
            b[k] = std::min(b[k], v[k]);
            b[k + 3] = std::max(b[k + 3], v[k]);
        }
    return b;
}

namespace {

// The design's rest surface in millimetres; an error when it has no positive radius somewhere.
std::string RestSurface(const Shape& shape, const PartDef& part, const RadiusField& measured, Grid* rest) {
    const bool perVertex = std::holds_alternative<FreeXYShape>(shape) || std::holds_alternative<MeshShape>(shape);
    if (perVertex && !measured) return std::string(ShapeName(shape)) + " designs are defined per vertex: their radius must be measured from the rest mesh";
    rest->nz = part.axialSamples;
    rest->nt = part.angularSamples;
    rest->p.resize(static_cast<size_t>(rest->nz) * rest->nt);
    // B-spline sectors meet in a step; a wall cannot follow a step's normals, so the radius is blended
    // from one sector's to the next over SectorBlendRadians either side of each boundary.
    const auto* spline = std::get_if<BSplineShape>(&shape);
    const int sectors = spline ? static_cast<int>(spline->splines.size()) : 1;
    const double blend = SectorBlendRadians(part);
    auto radius = [&](double t, double standardAngle) {
        if (perVertex) return measured(t, standardAngle);
        // The design's own angle: the thesis helix runs x = sin, y = cos.
        const double angle = part.helixAngles ? 0.5 * std::numbers::pi - standardAngle : standardAngle;
        if (sectors < 2) return DesignRadius(shape, t, angle, part.clampFraction);
        const double step = 2 * std::numbers::pi / sectors;
        const double boundary = step * std::round(angle / step);
        const double d = angle - boundary;
        if (std::fabs(d) >= blend) return DesignRadius(shape, t, angle, part.clampFraction);
        const double before = DesignRadius(shape, t, boundary - 0.5 * blend, part.clampFraction);
        const double after = DesignRadius(shape, t, boundary + 0.5 * blend, part.clampFraction);
        const double u = (d + blend) / (2 * blend);
        const double w = u * u * (3 - 2 * u);  // smoothstep: level with each sector where it meets it
        return (1 - w) * before + w * after;
    };
    // A piece spans its fractions of the design's length, its own heights from 0.
    const double from = part.fromFraction, to = part.toFraction, pieceMm = (to - from) * part.lengthMm;
    for (int j = 0; j < rest->nz; ++j) {
        const double u = static_cast<double>(j) / (rest->nz - 1), t = from + (to - from) * u;
        for (int i = 0; i < rest->nt; ++i) {
            const double rho = radius(t, 2 * std::numbers::pi * i / rest->nt);
            if (!(rho > 0))
                return Format("the design's radius is %.3g mm at z = %.4g mm, angle %.4g deg: a part needs a positive radius everywhere",
                              rho * part.radiusMm, t * part.lengthMm, Degrees(i, rest->nt));
            const auto [c, s] = Direction(i, rest->nt);
            rest->At(j, i) = {part.radiusMm * rho * c, part.radiusMm * rho * s, j == rest->nz - 1 ? pieceMm : u * pieceMm};
        }
    }
    return "";
}

// The guide grooves cut into a layer's outer face: each sample moved in along the normal by the
// deepest of the families' cosine profiles at its distance across their threads.
std::string CutGuides(const PartDef& part, const std::vector<Vec>& normals, Grid* outer);

// Unit normals of the rest surface from its samples (steep steps between B-spline sectors included),
// kept horizontal on the end rings (the end faces stay flat) and in the plane y = 0 on the meridians
// at 0 and 180 degrees (the mold's split plane).
std::vector<Vec> Normals(const Grid& g) {
    std::vector<Vec> normals(g.p.size());
    for (int j = 0; j < g.nz; ++j)
        for (int i = 0; i < g.nt; ++i) {
            const Vec around = Sub(g.At(j, i + 1), g.At(j, i + g.nt - 1));
            const Vec along = Sub(g.At(std::min(j + 1, g.nz - 1), i), g.At(std::max(j - 1, 0), i));
            Vec n = Cross(around, along);
            if (j == 0 || j == g.nz - 1) n[2] = 0;
            if (i == 0 || 2 * i == g.nt) n[1] = 0;
            const double length = std::sqrt(Dot(n, n));
            normals[static_cast<size_t>(j) * g.nt + i] = length > 0 ? Vec{n[0] / length, n[1] / length, n[2] / length} : Vec{0, 0, 0};
        }
    return normals;
}

Grid Offset(const Grid& rest, const std::vector<Vec>& normals, double distance) {
    Grid g = rest;
    for (size_t k = 0; k < g.p.size(); ++k)
        for (int c = 0; c < 3; ++c) g.p[k][c] += distance * normals[k][c];
    return g;
}

// A wall surface that stays a graph over (angle, height): every sample off the axis, angles rising
// around each ring, heights rising along each meridian, every cell positively oriented. Otherwise the
// offset has folded over itself (a wall thicker than the surface's radius of curvature there).
std::string FoldError(const Grid& g, const Grid& rest, const char* which, const PartDef& part) {
    auto angle = [&](int j, int i) {
        const Vec& p = g.At(j, i);
        const double nominal = 2 * std::numbers::pi * i / g.nt;  // i may be nt: one turn on
        return nominal + std::remainder(std::atan2(p[1], p[0]) - nominal, 2 * std::numbers::pi);
    };
    for (int j = 0; j < g.nz; ++j)
        for (int i = 0; i < g.nt; ++i) {
            const Vec& p = g.At(j, i);
            const Vec& q = rest.At(j, i);
            // Past the axis, the offset point lies on the other side of it from its rest point.
            if (!(p[0] * q[0] + p[1] * q[1] > 1e-6 * part.radiusMm * std::hypot(q[0], q[1])) || !std::isfinite(p[0] + p[1] + p[2]))
                return std::string("the ") + which +
                       Format(" wall surface reaches the axis at z = %.4g mm, angle %.4g deg: the radius there is below the wall thickness", p[2],
                              Degrees(i, g.nt));
        }
    for (int j = 0; j + 1 < g.nz; ++j)
        for (int i = 0; i < g.nt; ++i) {
            const double a0 = angle(j, i), a1 = angle(j, i + 1), b0 = angle(j + 1, i), b1 = angle(j + 1, i + 1);
            const double z0 = g.At(j, i)[2], z1 = g.At(j, i + 1)[2], w0 = g.At(j + 1, i)[2], w1 = g.At(j + 1, i + 1)[2];
            // Triangles (j,i) (j,i+1) (j+1,i+1) and (j,i) (j+1,i+1) (j+1,i) in the (angle, z) plane.
            const double first = (a1 - a0) * (w1 - z0) - (z1 - z0) * (b1 - a0);
            const double second = (b1 - a0) * (w0 - z0) - (w1 - z0) * (b0 - a0);
            if (!(first > 0) || !(second > 0) || !(w0 > z0))
                return std::string("the ") + which +
                       Format(" wall surface folds over itself near z = %.4g mm, angle %.4g deg: a wall of %.3g mm is thicker than the surface's "
                              "radius of curvature there (a thinner wall, or --wall outward, may fit)",
                              g.At(j, i)[2], Degrees(i, g.nt), part.thicknessMm);
        }
    return "";
}

std::string CutGuides(const PartDef& part, const std::vector<Vec>& normals, Grid* outer) {
    const GuideDef& g = part.guides;
    if (g.anglePerRing.empty()) return "";
    if (part.layerMm <= 0) return "guide grooves are cut into a first-stage layer (PartDef::layerMm)";
    if (!(g.depthMm > 0 && g.depthMm < 0.5 * part.layerMm) || !(g.widthMm > 0))
        return Format("guide grooves %.3g mm deep and %.3g mm wide do not fit a %.3g mm layer (at most half of it deep)", g.depthMm, g.widthMm,
                      part.layerMm);
    const int nz = outer->nz, nt = outer->nt;
    for (size_t f = 0; f < g.anglePerRing.size(); ++f)
        if (static_cast<int>(g.anglePerRing[f].size()) != nz || g.cosinePerRing.size() <= f || static_cast<int>(g.cosinePerRing[f].size()) != nz)
            return "the guides need one angle and one cosine per ring of the part";
    for (int j = 0; j < nz; ++j)
        for (int i = 0; i < nt; ++i) {
            Vec& p = outer->At(j, i);
            const double r = std::hypot(p[0], p[1]), theta = std::atan2(p[1], p[0]);
            double depth = 0;
            for (size_t f = 0; f < g.anglePerRing.size(); ++f) {
                // Across the thread: the arc to it along the ring, times the cosine of its angle to the meridian.
                const double across = std::fabs(std::remainder(theta - g.anglePerRing[f][j], 2 * std::numbers::pi)) * r * g.cosinePerRing[f][j];
                const double u = across / (0.5 * g.widthMm);
                if (u < 1) depth = std::max(depth, 0.5 * g.depthMm * (1 + std::cos(std::numbers::pi * u)));
            }
            const Vec& n = normals[static_cast<size_t>(j) * nt + i];
            for (int c = 0; c < 3; ++c) p[c] -= depth * n[c];
        }
    return "";
}

// The block's boundary point on the ray from the axis at sample i's angle, at height z.
Vec BoxPoint(int i, int nt, double w, double z) {
    const int k = i % nt;
    if (8 * k % nt == 0) {  // the eighth turns: the split plane, the box's faces' middles and its corners
        const int eighth = 8 * k / nt;
        static constexpr double kX[] = {1, 1, 0, -1, -1, -1, 0, 1}, kY[] = {0, 1, 1, 1, 0, -1, -1, -1};
        return {kX[eighth] * w, kY[eighth] * w, z};
    }
    const auto [c, s] = Direction(i, nt);
    if (std::fabs(c) >= std::fabs(s)) return {std::copysign(w, c), std::copysign(w, c) * s / c, z};
    return {std::copysign(w, s) * c / s, std::copysign(w, s), z};
}

// Which side of the box the ray at sample i meets: 0 x = +w, 1 y = +w, 2 x = -w, 3 y = -w; at a corner
// both of its sides count.
bool OnSide(int i, int nt, int side) {
    const double degrees = Degrees(i, nt);
    const double from = 90.0 * side - 45, to = 90.0 * side + 45;
    return (degrees >= from && degrees <= to) || (degrees - 360 >= from && degrees - 360 <= to);
}

// The mold's slots as built: the sprue in the bottom end wall, the vents in the top one.
struct Slots {
    double sprueDegrees = 0, ventDegrees = 0;
    double sprueReachMm = 0;  // the sprue beyond the wall's outer face, radially
};

// Whether an end wall is open over sample cell i (from sample i to i + 1): at the bottom the sprue,
// centred at 90 degrees (shell A); at the top the vents, at 45 and 135 (A), 225 and 315 degrees (B).
// Each spans at least one cell.
bool IsOpening(bool atTop, int i, int nt, const Slots& slots) {
    const double cell = 360.0 / nt, middle = cell * ((i % nt) + 0.5);
    auto within = [&](double centre, double width) { return std::fabs(middle - centre) < std::max(width, cell) / 2; };
    if (!atTop) return slots.sprueDegrees > 0 && within(90, slots.sprueDegrees);
    if (!(slots.ventDegrees > 0)) return false;
    for (const double centre : {45.0, 135.0, 225.0, 315.0})
        if (within(centre, slots.ventDegrees)) return true;
    return false;
}

// A point `reach` further out than `outer`, on the line from `inner` through it (in the vertical
// plane of the slot's end faces): the sprue's outer wall.
Vec Beyond(const Vec& inner, const Vec& outer, double reach) {
    const double dx = outer[0] - inner[0], dy = outer[1] - inner[1], d = std::hypot(dx, dy);
    return {outer[0] + reach * dx / d, outer[1] + reach * dy / d, outer[2]};
}

// The xy area of the quad a0 a1 b1 b0 (a slot's cross-section over one sample cell).
double SlotArea(const Vec& a0, const Vec& a1, const Vec& b1, const Vec& b0) {
    const Vec* corners[] = {&a0, &a1, &b1, &b0};
    double twice = 0;
    for (int k = 0; k < 4; ++k) twice += (*corners[k])[0] * (*corners[(k + 1) % 4])[1] - (*corners[(k + 1) % 4])[0] * (*corners[k])[1];
    return std::fabs(twice) / 2;
}

// The rows of bands each registration pin covers on each meridian: one pin near each end, about
// half the margin long. None on meshes too short to hold them apart.
std::vector<std::pair<int, int>> PinRows(int nz, int length) {
    if (nz < 10 || 2 * length + 4 > nz) return {};
    const int low = std::max(1, static_cast<int>(std::lround(0.12 * (nz - 1))));
    const int high = std::min(nz - 2, static_cast<int>(std::lround(0.88 * (nz - 1))));
    return {{low, low + length}, {high - length, high}};
}

// Bands each pin spans: about as long (along z) as it is wide, half the margin.
int PinBands(const PartDef& part, const MoldDef& mold, int nz) {
    return std::max(1, static_cast<int>(std::lround(0.5 * mold.marginMm * (nz - 1) / part.lengthMm)));
}

// A pin's top is its foot inset by the clearance on every side: a clearance of half the foot or more
// would turn it inside out (its facets reversed).
std::string PinError(const Grid& outer, const PartDef& part, const MoldDef& mold) {
    const double c = mold.pinClearanceMm, across = 0.5 * mold.marginMm;
    if (!(c >= 0)) return "the pins' clearance must not be negative";
    for (const auto& [ja, jb] : PinRows(outer.nz, PinBands(part, mold, outer.nz)))
        for (const int i : {0, outer.nt / 2}) {
            const double along = outer.At(jb, i)[2] - outer.At(ja, i)[2], foot = std::min(across, along);
            if (!(2 * c < foot))
                return Format("a pin clearance of %.3g mm does not fit the registration pins (%.3g x %.3g mm at their feet, set by the mold's margin): "
                              "give a clearance below %.3g mm, or a wider margin",
                              c, across, along, foot / 2);
        }
    return "";
}

bool InPin(int band, int nz, int length) {
    for (const auto& [a, b] : PinRows(nz, length))
        if (band >= a && band < b) return true;
    return false;
}

// The pour mark: an arrow pointing up, engraved in the block's side at y = +w (shell A's back, over
// the sprue at 90 degrees), centred at x = 0 and in height: a shaft 2s wide from zA to zB, a head 2h
// wide at its base zB with its tip at zT; the head's edges cross the shaft's sides at zQ.
struct PourArrow {
    double h = 0, s = 0, zA = 0, zB = 0, zQ = 0, zT = 0;
};

PourArrow PourArrowOn(double w, double zLow, double zHigh) {
    PourArrow a;
    a.h = std::min(0.6 * w, (zHigh - zLow) / 7.5);
    a.s = 0.4 * a.h;
    a.zA = 0.5 * (zLow + zHigh) - 2.25 * a.h;
    a.zB = a.zA + 3 * a.h;
    a.zT = a.zB + 1.5 * a.h;
    a.zQ = a.zB + (a.zT - a.zB) * (a.h - a.s) / a.h;
    return a;
}

// The side with the arrow `depth` deep. The side is `bottomEdge` (its points on the block's bottom
// face, x from +w to -w) and `topEdge` (x from -w to +w); its corner edges carry points at zA and zT
// (the neighbouring sides have them too). The face is cut in columns at the arrow's corners so that
// every piece is convex, and the pocket's walls and floor close it. Returns the pocket's volume (mm^3).
double EngravedSide(Builder& b, const std::vector<int>& bottomEdge, const std::vector<int>& topEdge, double w, const PourArrow& arrow,
                    double depth) {
    const Vec face{0, 1, 0};
    const auto [h, s, zA, zB, zQ, zT] = arrow;
    auto V = [&](double x, double z, double y) { return b.Vertex({x, y, z}); };
    auto F = [&](double x, double z) { return V(x, z, w); };
    auto fanFromCentre = [&](const std::vector<int>& polygon) {
        Vec centre{0, 0, 0};
        for (int v : polygon)
            for (int c = 0; c < 3; ++c) centre[c] += b.At(v)[c] / polygon.size();
        centre[1] = w;
        const int middle = b.Vertex(centre);
        for (size_t k = 0; k < polygon.size(); ++k) b.Facing(middle, polygon[k], polygon[(k + 1) % polygon.size()], face);
    };
    // Below the arrow and above it: the side's own edge and a line across at zA (zT).
    std::vector<int> below = bottomEdge;
    for (const double x : {-w, -h, -s, s, h, w}) below.push_back(F(x, zA));
    fanFromCentre(below);
    std::vector<int> above;
    for (const double x : {w, h, s, 0.0, -s, -h, -w}) above.push_back(F(x, zT));
    above.insert(above.end(), topEdge.begin(), topEdge.end());
    fanFromCentre(above);
    // Beside it, mirrored: the outer column, the column beside the shaft below and beside the head
    // above, and the corner between the head and the top line over the shaft.
    for (const double side : {-1.0, 1.0}) {
        b.Fan({F(side * w, zA), F(side * h, zA), F(side * h, zB), F(side * h, zT), F(side * w, zT)}, face);
        b.Fan({F(side * h, zA), F(side * s, zA), F(side * s, zB), F(side * h, zB)}, face);
        b.Fan({F(side * h, zB), F(side * s, zQ), F(side * s, zT), F(side * h, zT)}, face);
        b.Facing(F(side * s, zQ), F(0, zT), F(side * s, zT), face);
    }
    // The pocket: its outline around the arrow, walls facing into it, its floor facing out. The point
    // just above the head's base sees every edge from inside (the arrow is star-shaped about it).
    const std::vector<std::array<double, 2>> outline{{-s, zA}, {s, zA}, {s, zB}, {h, zB}, {s, zQ}, {0, zT}, {-s, zQ}, {-h, zB}, {-s, zB}};
    const std::array<double, 2> kernel{0, zB + 0.1 * (zT - zB)};
    const int floorCentre = V(kernel[0], kernel[1], w - depth);
    for (size_t k = 0; k < outline.size(); ++k) {
        const auto& p = outline[k];
        const auto& q = outline[(k + 1) % outline.size()];
        // The edge's normal in the face's plane, toward the kernel point: into the pocket.
        Vec normal{-(q[1] - p[1]), 0, q[0] - p[0]};
        if (normal[0] * (kernel[0] - p[0]) + normal[2] * (kernel[1] - p[1]) < 0) normal = {-normal[0], 0, -normal[2]};
        b.FacingQuad(F(p[0], p[1]), F(q[0], q[1]), V(q[0], q[1], w - depth), V(p[0], p[1], w - depth), normal);
        b.Facing(floorCentre, V(p[0], p[1], w - depth), V(q[0], q[1], w - depth), face);
    }
    return depth * (2 * s * (zB - zA) + h * (zT - zB));
}

TriangleMesh Shell(bool upper, const Grid& outer, const Grid& inner, double w, const PartDef& part, const MoldDef& mold, const Slots& slots,
                   PartSolids* volumes) {
    double& openings = volumes->openingsMm3;
    double& sprue = volumes->sprueMm3;
    double& pins = volumes->pinsLessHolesMm3;
    const int nt = outer.nt, nz = outer.nz, half = nt / 2, first = upper ? 0 : half;
    const double bottom = -mold.endWallMm, top = part.lengthMm + mold.endWallMm;
    const Vec up{0, 0, 1}, down{0, 0, -1};
    Builder b;
    auto O = [&](int j, int k) { return b.Vertex(outer.At(j, first + k)); };
    auto I = [&](int j, int k) { return b.Vertex(inner.At(j, first + k)); };
    auto Channel = [&](bool atTop, int k) {  // the core's channel ring on the block's end face
        const Vec& p = inner.At(atTop ? nz - 1 : 0, first + k);
        return b.Vertex({p[0], p[1], atTop ? top : bottom});
    };
    auto towardAxis = [&](int v) {
        const Vec& p = b.At(v);
        return Vec{-p[0], -p[1], 0};
    };
    // The end walls' slots over the silicone's end faces (the sprue at the bottom, the vents at the
    // top), cell by cell; none crosses the split plane.
    auto Open = [&](bool atTop, int k) { return k >= 0 && k < half && IsOpening(atTop, first + k, nt, slots); };
    // The slot's outer wall: at the top the actuator's outer ring, at the bottom that ring reached
    // out by the sprue's reach. `onFace`: carried to the block's end face.
    auto SlotRim = [&](bool atTop, int k, bool onFace) {
        const int j = atTop ? nz - 1 : 0;
        const Vec p = atTop ? outer.At(j, first + k) : Beyond(inner.At(j, first + k), outer.At(j, first + k), slots.sprueReachMm);
        return b.Vertex({p[0], p[1], onFace ? (atTop ? top : bottom) : p[2]});
    };
    for (int k = 0; k < half; ++k) {
        // The cavity's wall: the actuator's outer surface, facing the axis.
        for (int j = 0; j + 1 < nz; ++j) b.Quad(O(j, k), O(j + 1, k), O(j + 1, k + 1), O(j, k + 1));
        for (const bool atTop : {false, true}) {
            const int j = atTop ? nz - 1 : 0;
            const Vec inward = atTop ? down : up;  // the end wall's face against the silicone's end, into the cavity
            const Vec outward = atTop ? up : down; // the block's end face
            const int c0 = Channel(atTop, k), c1 = Channel(atTop, k + 1), i0 = I(j, k), i1 = I(j, k + 1), o0 = O(j, k), o1 = O(j, k + 1);
            const double z = atTop ? top : bottom;
            const int b0 = b.Vertex(BoxPoint(first + k, nt, w, z)), b1 = b.Vertex(BoxPoint(first + k + 1, nt, w, z));
            if (!Open(atTop, k)) {
                // The end wall's inner face (the actuator's end face), the core's channel, and the block's
                // end face between the channel and the box, split where a slot beside it has its rim.
                b.FacingQuad(i0, i1, o1, o0, inward);
                b.FacingQuad(c0, c1, i1, i0, towardAxis(c0));
                const bool slotBefore = Open(atTop, k - 1), slotAfter = Open(atTop, k + 1);
                if (!slotBefore && !slotAfter) {
                    b.FacingQuad(c0, c1, b1, b0, outward);
                    continue;
                }
                std::vector<int> polygon{c0};
                if (slotBefore) polygon.push_back(SlotRim(atTop, k, true));
                polygon.insert(polygon.end(), {b0, b1});
                if (slotAfter) polygon.push_back(SlotRim(atTop, k + 1, true));
                polygon.push_back(c1);
                // Fanned from a point inside: the rims lie on the strip's edges.
                Vec centre{0, 0, z};
                for (const int v : {c0, c1, b0, b1})
                    for (int d = 0; d < 2; ++d) centre[d] += b.At(v)[d] / 4;
                const int middle = b.Vertex(centre);
                for (size_t n = 0; n < polygon.size(); ++n) b.Facing(middle, polygon[n], polygon[(n + 1) % polygon.size()], outward);
                continue;
            }
            // A slot: the core's handle is its inner wall; its outer wall rises from the rim (at the
            // bottom past the actuator's outer face, under a ledge of the end wall) to the block's face.
            const int x0 = SlotRim(atTop, k, false), x1 = SlotRim(atTop, k + 1, false), r0 = SlotRim(atTop, k, true), r1 = SlotRim(atTop, k + 1, true);
            if (x0 != o0) b.FacingQuad(o0, o1, x1, x0, outward);  // the ledge, facing down into the slot
            b.FacingQuad(x0, x1, r1, r0, towardAxis(x0));
            b.FacingQuad(r0, r1, b1, b0, outward);
            // Its ends where the closed cells begin: in the vertical plane of each end ray.
            auto End = [&](int c, int i, int o, int x, int r, const Vec& normal) {
                std::vector<int> polygon{c, i, o};
                if (x != o) polygon.push_back(x);
                polygon.push_back(r);
                b.Fan(polygon, normal);
            };
            const auto [cs, sn] = Direction(first + k, nt);
            const auto [cs2, sn2] = Direction(first + k + 1, nt);
            if (!Open(atTop, k - 1)) End(c0, i0, o0, x0, r0, Vec{-sn, cs, 0});
            if (!Open(atTop, k + 1)) End(c1, i1, o1, x1, r1, Vec{sn2, -cs2, 0});
            const double volume = SlotArea(inner.At(j, first + k), inner.At(j, first + k + 1), b.At(x1), b.At(x0)) * mold.endWallMm;
            openings += volume;
            if (!atTop) sprue += volume;
        }
    }
    // The split face (y = 0) on each meridian: bands between the cavity's profile and the box's edge.
    const Vec splitNormal{0, upper ? -1.0 : 1.0, 0};
    // Pins about as long (along z) as they are wide: half the margin.
    const int pinBands = PinBands(part, mold, nz);
    std::map<int, std::vector<int>> lineOf;  // meridian sample -> the box edge's vertices on y = 0, upward
    for (const int m : {0, half}) {
        const int i = first + m;
        const double x = (i % nt == 0) ? w : -w;
        std::vector<int> line;
        auto L = [&](double z) {
            const int v = b.Vertex({x, 0, z});
            if (line.empty() || line.back() != v) line.push_back(v);
            return v;
        };
        // Each band is cut at x1 and x2, the registration pins' sides, in the block's margin.
        const double sign = x > 0 ? 1 : -1, x1 = sign * (w - 0.75 * mold.marginMm), x2 = sign * (w - 0.25 * mold.marginMm);
        auto z = [&](int j) { return outer.At(j, i)[2]; };
        auto P1 = [&](int j) { return b.Vertex({x1, 0, z(j)}); };
        auto P2 = [&](int j) { return b.Vertex({x2, 0, z(j)}); };
        const int lb = L(bottom);
        b.Fan({lb, Channel(false, m), I(0, m), O(0, m), P1(0), P2(0), L(0)}, splitNormal);
        for (int j = 0; j + 1 < nz; ++j) {
            const int o0 = O(j, m), o1 = O(j + 1, m), a0 = P1(j), a1 = P1(j + 1), c0 = P2(j), c1 = P2(j + 1);
            const int l0 = L(z(j)), l1 = L(z(j + 1));
            b.FacingQuad(o0, o1, a1, a0, splitNormal);
            b.FacingQuad(c0, c1, l1, l0, splitNormal);
            if (!InPin(j, nz, pinBands)) {
                b.FacingQuad(a0, a1, c1, c0, splitNormal);
            }
        }
        // The pins (shell A, standing out of the face, their tops inset by the clearance so they
        // find their holes) and the holes (shell B, sunk into the face, the pins' feet exactly).
        for (const auto& [ja, jb] : PinRows(nz, pinBands)) {
            const double depth = 0.5 * mold.marginMm, c = upper ? mold.pinClearanceMm : 0;
            const double y = upper ? -depth : -depth;  // A's pins reach into y < 0; B's holes go as deep
            const double inset = sign * c;
            const int t1a = b.Vertex({x1 + inset, y, z(ja) + c}), t2a = b.Vertex({x2 - inset, y, z(ja) + c});
            const int t1b = b.Vertex({x1 + inset, y, z(jb) - c}), t2b = b.Vertex({x2 - inset, y, z(jb) - c});
            const double out = upper ? 1 : -1;  // faces point away from the pin's inside, or into the hole
            const Vec towardAxisX{-sign * out, 0, 0}, awayAxisX{sign * out, 0, 0}, lower{0, 0, -out}, higher{0, 0, out};
            b.FacingQuad(t1a, t2a, t2b, t1b, Vec{0, -out, 0});
            for (int j = ja; j < jb; ++j) {
                b.Facing(t1a, P1(j), P1(j + 1), towardAxisX);
                b.Facing(t2a, P2(j), P2(j + 1), awayAxisX);
            }
            b.Facing(t1a, P1(jb), t1b, towardAxisX);
            b.Facing(t2a, P2(jb), t2b, awayAxisX);
            b.Facing(P1(ja), P2(ja), t2a, lower);
            b.Facing(P1(ja), t2a, t1a, lower);
            b.Facing(P1(jb), P2(jb), t2b, higher);
            b.Facing(P1(jb), t2b, t1b, higher);
            // Prismatoid: depth / 6 (base + 4 middle + top).
            const double wx = std::fabs(x2 - x1), wz = z(jb) - z(ja);
            const double volume = depth / 6 * (wx * wz + 4 * (wx - c) * (wz - c) + (wx - 2 * c) * (wz - 2 * c));
            pins += upper ? volume : -volume;
        }
        // The top band: from the actuator's end up to the block's top.
        const int lt = b.Vertex({x, 0, top});
        b.Fan({lt, L(part.lengthMm), P2(nz - 1), P1(nz - 1), O(nz - 1, m), I(nz - 1, m), Channel(true, m)}, splitNormal);
        L(top);
        lineOf[i % nt] = line;
    }
    // Shell A's back carries the pour mark; the corner edges it shares with the neighbouring sides
    // are cut where the arrow's band begins and ends.
    const double markDepth = std::min(mold.markDepthMm, 0.25 * mold.marginMm);
    const bool marked = upper && markDepth > 0;
    const PourArrow arrow = PourArrowOn(w, bottom, top);
    if (marked)
        for (const int corner : {nt / 8, 3 * nt / 8})
            for (const double z : {bottom, arrow.zA, arrow.zT, top}) lineOf[corner].push_back(b.Vertex(BoxPoint(corner, nt, w, z)));
    // The box's sides in this half, each a rectangle fanned from its centre: its bottom and top edges
    // carry the rays' points, an edge on the split plane (or a cut corner) carries its line.
    for (int side = 0; side < 4; ++side) {
        std::vector<int> samples;
        for (int k = 0; k <= half; ++k)
            if (OnSide(first + k, nt, side)) samples.push_back(first + k);
        if (samples.size() < 2) continue;
        if (marked && side == 1) {
            std::vector<int> bottomEdge, topEdge;
            for (int i : samples) bottomEdge.push_back(b.Vertex(BoxPoint(i, nt, w, bottom)));
            for (auto it = samples.rbegin(); it != samples.rend(); ++it) topEdge.push_back(b.Vertex(BoxPoint(*it, nt, w, top)));
            volumes->markMm3 += EngravedSide(b, bottomEdge, topEdge, w, arrow, markDepth);
            volumes->markDepthMm = markDepth;
            continue;
        }
        std::vector<int> loop;
        for (int i : samples) loop.push_back(b.Vertex(BoxPoint(i, nt, w, bottom)));
        if (lineOf.count(samples.back() % nt))
            for (int v : lineOf[samples.back() % nt]) loop.push_back(v);
        for (auto it = samples.rbegin(); it != samples.rend(); ++it) loop.push_back(b.Vertex(BoxPoint(*it, nt, w, top)));
        if (lineOf.count(samples.front() % nt)) {
            const auto& line = lineOf[samples.front() % nt];
            for (auto it = line.rbegin(); it != line.rend(); ++it) loop.push_back(*it);
        }
        // Drop repeats where the runs meet (a run's end is the next run's start).
        std::vector<int> polygon;
        for (int v : loop)
            if (polygon.empty() || polygon.back() != v) polygon.push_back(v);
        while (polygon.size() > 1 && polygon.front() == polygon.back()) polygon.pop_back();
        Vec centre{0, 0, 0};
        for (int v : polygon)
            for (int c = 0; c < 3; ++c) centre[c] += b.At(v)[c] / polygon.size();
        const Vec normal = side == 0 ? Vec{1, 0, 0} : side == 1 ? Vec{0, 1, 0} : side == 2 ? Vec{-1, 0, 0} : Vec{0, -1, 0};
        centre[side % 2 == 0 ? 0 : 1] = normal[side % 2 == 0 ? 0 : 1] * w;  // exactly on the side's plane
        const int middle = b.Vertex(centre);
        for (size_t k = 0; k < polygon.size(); ++k) b.Facing(middle, polygon[k], polygon[(k + 1) % polygon.size()], normal);
    }
    return b.Take();
}

// Area enclosed by a ring of samples, projected on the xy plane (shoelace).
double RingArea(const Grid& g, int j) {
    double twice = 0;
    for (int i = 0; i < g.nt; ++i) {
        const Vec& a = g.At(j, i);
        const Vec& c = g.At(j, i + 1);
        twice += a[0] * c[1] - c[0] * a[1];
    }
    return twice / 2;
}

}  // namespace

// The perimeter of ring j, mm.
double RingPerimeter(const Grid& g, int j) {
    double perimeter = 0;
    for (int i = 0; i < g.nt; ++i) perimeter += std::sqrt(Dot(Sub(g.At(j, i + 1), g.At(j, i)), Sub(g.At(j, i + 1), g.At(j, i))));
    return perimeter;
}

// How a one-piece core leaves through the better end (CoreExit): at each wall section, the largest
// core section that must pass it on the way to that end, over the section's own perimeter.
CoreExit CoreExitOf(const Grid& inner) {
    const int nz = inner.nz;
    std::vector<double> perimeter(nz);
    for (int j = 0; j < nz; ++j) perimeter[j] = RingPerimeter(inner, j);
    CoreExit best;
    best.stretch = -1;
    for (const bool top : {true, false}) {
        CoreExit exit;
        exit.top = top;
        exit.stretch = 0;
        double widest = 0;
        for (int step = 0; step < nz; ++step) {
            const int j = top ? step : nz - 1 - step;  // from the far end towards the exit
            widest = std::max(widest, perimeter[j]);
            if (const double stretch = widest / perimeter[j]; stretch > exit.stretch)
                exit = {top, stretch, inner.At(j, 0)[2], widest / std::numbers::pi, perimeter[j] / std::numbers::pi};
        }
        if (best.stretch < 0 || exit.stretch < best.stretch) best = exit;
    }
    return best;
}

// A plug for one end of the tube (bottom: z = 0, the collar below; top: mirrored), built bottom-up
// and flipped for the top: collar rings, the insert following the inner end ring, an optional bore.
std::string Fitting(const Grid& inner, const Grid& outer, bool atTop, double port, const FittingDef& f, double insert, const PartDef& part,
                    TriangleMesh* out) {
    const int nt = inner.nt, j = atTop ? inner.nz - 1 : 0;
    double collar = 0, smallest = INFINITY;
    for (int i = 0; i < nt; ++i) {
        collar = std::max(collar, std::hypot(outer.At(j, i)[0], outer.At(j, i)[1]));
        smallest = std::min(smallest, std::hypot(inner.At(j, i)[0], inner.At(j, i)[1]));
    }
    collar += f.collarMarginMm;
    if (port > 0 && port / 2 > smallest - 0.5)
        return Format("a port of %.3g mm does not fit the tube's end, whose inner radius is %.3g mm (leave 0.5 mm of wall)", port, smallest);
    // Local height h: 0 at the tube's end, the insert up to `insert`, the collar down to -collarMm.
    auto place = [&](double x, double y, double h) { return Vec{x, y, atTop ? part.lengthMm - h : h}; };
    Builder b;
    const Vec up{0, 0, atTop ? -1.0 : 1.0}, down{0, 0, atTop ? 1.0 : -1.0};
    const int centreLow = b.Vertex(place(0, 0, -f.collarMm)), centreHigh = b.Vertex(place(0, 0, insert));
    for (int i = 0; i < nt; ++i) {
        const auto [c0, s0] = Direction(i, nt);
        const auto [c1, s1] = Direction(i + 1, nt);
        const Vec& e0 = inner.At(j, i);
        const Vec& e1 = inner.At(j, i + 1);
        const int g0 = b.Vertex(place(collar * c0, collar * s0, -f.collarMm)), g1 = b.Vertex(place(collar * c1, collar * s1, -f.collarMm));
        const int h0 = b.Vertex(place(collar * c0, collar * s0, 0)), h1 = b.Vertex(place(collar * c1, collar * s1, 0));
        const int n0 = b.Vertex(place(e0[0], e0[1], 0)), n1 = b.Vertex(place(e1[0], e1[1], 0));
        const int t0 = b.Vertex(place(e0[0], e0[1], insert)), t1 = b.Vertex(place(e1[0], e1[1], insert));
        const Vec outward{c0 + c1, s0 + s1, 0};
        b.FacingQuad(g0, g1, h1, h0, outward);  // the collar's side
        b.FacingQuad(n0, n1, h1, h0, up);       // the shoulder the actuator's end sits on
        b.FacingQuad(n0, n1, t1, t0, outward);  // the insert
        if (port > 0) {
            const double r = port / 2;
            const int p0 = b.Vertex(place(r * c0, r * s0, -f.collarMm)), p1 = b.Vertex(place(r * c1, r * s1, -f.collarMm));
            const int q0 = b.Vertex(place(r * c0, r * s0, insert)), q1 = b.Vertex(place(r * c1, r * s1, insert));
            b.FacingQuad(p0, p1, g1, g0, down);
            b.FacingQuad(q0, q1, t1, t0, up);
            b.FacingQuad(p0, p1, q1, q0, Vec{-(c0 + c1), -(s0 + s1), 0});
        } else {
            b.Facing(centreLow, g0, g1, down);
            b.Facing(centreHigh, t0, t1, up);
        }
    }
    *out = b.Take();
    return "";
}

std::string BuildPartSolids(const Shape& shape, const PartDef& design, const MoldDef& mold, PartSolids* out, const FittingDef& fittings,
                            const RadiusField& measured) {
    if (!(design.fromFraction >= 0 && design.fromFraction < design.toFraction && design.toFraction <= 1))
        return "a piece spans heights 0 <= from < to <= 1 of the design";
    if (!(design.flangeMm >= 0)) return "a flange's width must not be negative";
    // From here on the part is the piece: its length, its heights from 0 (the design's surface is
    // sampled over the piece's span).
    PartDef part = design;
    part.lengthMm = (design.toFraction - design.fromFraction) * design.lengthMm;
    if (part.angularSamples < 8 || part.angularSamples % 8 != 0) return "the samples around the tube must be a multiple of 8, at least 8";
    if (part.axialSamples < 3) return "at least 3 samples along the tube";
    if (!(part.radiusMm > 0) || !(part.lengthMm > 0) || !(part.thicknessMm > 0)) return "radius, length and wall thickness must be positive";
    if (!(mold.marginMm > 0) || !(mold.endWallMm > 0) || !(mold.handleMm > 0)) return "the mold's margin, end walls and handles must be positive";
    if (!(mold.markDepthMm >= 0)) return "the pour mark's depth must not be negative";
    if (!(mold.sprueDegrees >= 0 && mold.sprueDegrees <= 120) || !(mold.ventDegrees >= 0 && mold.ventDegrees <= 60))
        return "the sprue spans 0 to 120 degrees (0: sized) and each vent 0 to 60";
    if (!(mold.sprueMm > 0)) return "the sprue's width must be positive";
    Grid rest;
    if (std::string error = RestSurface(shape, design, measured, &rest); !error.empty()) return error;
    const std::vector<Vec> normals = Normals(rest);
    for (size_t k = 0; k < normals.size(); ++k)
        if (Dot(normals[k], normals[k]) == 0)
            return Format("the surface has no normal at z = %.4g mm, angle %.4g deg", rest.p[k][2], Degrees(static_cast<int>(k) % rest.nt, rest.nt));
    // The solid's thickness: the wall's, or a first stage's inner layer of it.
    if (part.layerMm < 0 || (part.layerMm > 0 && !(part.layerMm < part.thicknessMm)))
        return Format("a first-stage layer of %.3g mm does not fit a %.3g mm wall (it is the wall's inner part)", part.layerMm, part.thicknessMm);
    const double h = part.layerMm > 0 ? part.layerMm : part.thicknessMm;
    const double innerOffset = part.wall == WallSide::Centred ? -part.thicknessMm / 2 : 0;
    Grid outer = Offset(rest, normals, innerOffset + h);
    const Grid inner = part.wall == WallSide::Centred ? Offset(rest, normals, innerOffset) : rest;
    if (std::string error = CutGuides(part, normals, &outer); !error.empty()) return error;
    // A cut end's bonding flange: the end ring and the one next to it carried out by the flange's
    // width (a rim one band thick, its underside chamfered to the wall).
    if (design.flangeMm > 0)
        for (const bool atTop : {false, true}) {
            if (atTop ? design.toFraction >= 1 : design.fromFraction <= 0) continue;  // the design's own end
            const int e = atTop ? outer.nz - 1 : 0, n = atTop ? e - 1 : 1;
            for (int i = 0; i < outer.nt; ++i) {
                const Vec rim = Beyond(inner.At(e, i), outer.At(e, i), design.flangeMm);
                outer.At(e, i) = {rim[0], rim[1], outer.At(e, i)[2]};
                outer.At(n, i) = {rim[0], rim[1], outer.At(n, i)[2]};
            }
        }
    for (const auto& [grid, which] : {std::pair<const Grid*, const char*>{&outer, "outer"}, std::pair{&inner, "inner"}})
        if (std::string error = FoldError(*grid, rest, which, part); !error.empty()) return error;
    if (std::string error = PinError(outer, part, mold); !error.empty()) return error;
    const int nz = rest.nz, nt = rest.nt;
    // A lost core's drain must leave it a wall of at least a millimetre everywhere.
    double drainMm = 0;
    if (mold.core == CoreKind::Lost) {
        double nearest = std::numeric_limits<double>::infinity();
        Vec where{};
        for (const Vec& p : inner.p)
            if (const double r = std::hypot(p[0], p[1]); r < nearest) nearest = r, where = p;
        drainMm = mold.drainMm > 0 ? mold.drainMm : std::min(4.0, 2 * (nearest - 1));
        if (mold.drainMm > 0 ? nearest < drainMm / 2 + 1 : drainMm < 1)
            return Format("the core is %.3g mm from its axis at z = %.4g mm: too thin for a %.3g mm drain and 1 mm of core around it",
                          nearest, where[2], std::max(drainMm, 1.0));
    }

    PartSolids solids;
    {  // The wall: outer surface out, inner surface in, flat annuli at the ends.
        Builder b;
        for (int j = 0; j + 1 < nz; ++j)
            for (int i = 0; i < nt; ++i) {
                b.Quad(b.Vertex(outer.At(j, i)), b.Vertex(outer.At(j, i + 1)), b.Vertex(outer.At(j + 1, i + 1)), b.Vertex(outer.At(j + 1, i)));
                b.Quad(b.Vertex(inner.At(j, i)), b.Vertex(inner.At(j + 1, i)), b.Vertex(inner.At(j + 1, i + 1)), b.Vertex(inner.At(j, i + 1)));
            }
        for (int i = 0; i < nt; ++i)
            for (const int j : {0, nz - 1}) {
                const Vec normal{0, 0, j == 0 ? -1.0 : 1.0};
                const int o0 = b.Vertex(outer.At(j, i)), o1 = b.Vertex(outer.At(j, i + 1)), i0 = b.Vertex(inner.At(j, i)), i1 = b.Vertex(inner.At(j, i + 1));
                b.FacingQuad(o0, o1, i1, i0, normal);
            }
        solids.actuator = b.Take();
    }
    {  // The wall's half at y >= 0: the same faces over half the turn, closed by the two cut faces.
        Builder b;
        const int half = nt / 2;
        for (int i = 0; i < half; ++i) {
            for (int j = 0; j + 1 < nz; ++j) {
                b.Quad(b.Vertex(outer.At(j, i)), b.Vertex(outer.At(j, i + 1)), b.Vertex(outer.At(j + 1, i + 1)), b.Vertex(outer.At(j + 1, i)));
                b.Quad(b.Vertex(inner.At(j, i)), b.Vertex(inner.At(j + 1, i)), b.Vertex(inner.At(j + 1, i + 1)), b.Vertex(inner.At(j, i + 1)));
            }
            for (const int j : {0, nz - 1}) {
                const Vec normal{0, 0, j == 0 ? -1.0 : 1.0};
                const int o0 = b.Vertex(outer.At(j, i)), o1 = b.Vertex(outer.At(j, i + 1)), i0 = b.Vertex(inner.At(j, i)), i1 = b.Vertex(inner.At(j, i + 1));
                b.FacingQuad(o0, o1, i1, i0, normal);
            }
        }
        for (const int i : {0, half})
            for (int j = 0; j + 1 < nz; ++j) {
                const Vec normal{0, -1, 0};
                const int o0 = b.Vertex(outer.At(j, i)), o1 = b.Vertex(outer.At(j + 1, i)), i0 = b.Vertex(inner.At(j, i)), i1 = b.Vertex(inner.At(j + 1, i));
                b.FacingQuad(o0, o1, i1, i0, normal);
            }
        solids.actuatorCut = b.Take();
    }
    const double handleBottom = -mold.endWallMm - mold.handleMm, handleTop = part.lengthMm + mold.endWallMm + mold.handleMm;
    {  // The core: the inner surface, each end ring drawn straight out through the block as a handle.
        Builder b;
        for (int j = 0; j + 1 < nz; ++j)
            for (int i = 0; i < nt; ++i)
                b.Quad(b.Vertex(inner.At(j, i)), b.Vertex(inner.At(j, i + 1)), b.Vertex(inner.At(j + 1, i + 1)), b.Vertex(inner.At(j + 1, i)));
        // A lost core is bored along its axis, handle to handle: the solvent reaches in and the melt runs out.
        const bool drained = mold.core == CoreKind::Lost;
        const double drain = drainMm / 2;
        auto drainPoint = [&](int i, double z) {
            const auto [c, sn] = Direction(i, nt);
            return Vec{drain * c, drain * sn, z};
        };
        for (const bool atTop : {false, true}) {
            const int j = atTop ? nz - 1 : 0;
            const double z = atTop ? handleTop : handleBottom;
            const Vec endNormal{0, 0, atTop ? 1.0 : -1.0};
            const int centre = drained ? -1 : b.Vertex({0, 0, z});  // a solid end's fan; a drained one is an annulus
            for (int i = 0; i < nt; ++i) {
                const Vec& p0 = inner.At(j, i);
                const Vec& p1 = inner.At(j, i + 1);
                const int r0 = b.Vertex(p0), r1 = b.Vertex(p1), e0 = b.Vertex({p0[0], p0[1], z}), e1 = b.Vertex({p1[0], p1[1], z});
                const Vec outward{p0[0] + p1[0], p0[1] + p1[1], 0};
                b.FacingQuad(e0, e1, r1, r0, outward);
                if (drained) b.FacingQuad(e0, e1, b.Vertex(drainPoint(i + 1, z)), b.Vertex(drainPoint(i, z)), endNormal);
                else b.Facing(centre, e0, e1, endNormal);
            }
        }
        if (drained)
            for (int i = 0; i < nt; ++i) {
                const auto [c0, s0] = Direction(i, nt);
                const auto [c1, s1] = Direction(i + 1, nt);
                b.FacingQuad(b.Vertex(drainPoint(i, handleBottom)), b.Vertex(drainPoint(i + 1, handleBottom)), b.Vertex(drainPoint(i + 1, handleTop)),
                             b.Vertex(drainPoint(i, handleTop)), Vec{-(c0 + c1), -(s0 + s1), 0});  // facing the axis: out of the core
            }
        solids.core = b.Take();
        // The bore's section: the polygon of its samples.
        const double drainArea = drained ? nt / 2.0 * drain * drain * std::sin(2 * std::numbers::pi / nt) : 0;
        solids.coreOutsideBlockMm3 = (RingArea(inner, 0) + RingArea(inner, nz - 1) - 2 * drainArea) * mold.handleMm;
        solids.drainInBlockMm3 = drainArea * (part.lengthMm + 2 * mold.endWallMm);
        solids.drainMm = drainMm;
        solids.coreExit = CoreExitOf(inner);
    }
    // The block: the actuator's widest extent plus the margin, the same in x and y.
    double reach = 0;
    for (const Vec& p : outer.p) reach = std::max({reach, std::fabs(p[0]), std::fabs(p[1])});
    const double w = reach + mold.marginMm;
    // The cavity the silicone fills: its mid-surface ring by ring, and the distance along the wall.
    solids.cavityPerimeterMm.resize(nz);
    solids.cavityPathMm.assign(nz, 0);
    solids.cavityHeightMm.resize(nz);
    Grid middle = inner;
    for (size_t k = 0; k < middle.p.size(); ++k)
        for (int c = 0; c < 3; ++c) middle.p[k][c] = 0.5 * (inner.p[k][c] + outer.p[k][c]);
    solids.midSurfaceMm = middle.p;
    solids.midAround = nt;
    solids.corePerimeterMm.resize(nz);
    for (int j = 0; j < nz; ++j) {
        solids.corePerimeterMm[j] = RingPerimeter(inner, j);
        solids.cavityPerimeterMm[j] = RingPerimeter(middle, j);
        solids.cavityHeightMm[j] = middle.At(j, 0)[2];
        if (j == 0) continue;
        double along = 0;
        for (int i = 0; i < nt; ++i) along += std::sqrt(Dot(Sub(middle.At(j, i), middle.At(j - 1, i)), Sub(middle.At(j, i), middle.At(j - 1, i)))) / nt;
        solids.cavityPathMm[j] = solids.cavityPathMm[j - 1] + along;
    }
    // The slots. The sprue is at least sprueMm across the wall (reaching outward past it) and along
    // it, and wide enough that its resistance to the flow is at most a quarter of the full cavity's.
    // Both are thin gaps: a gap g wide over a length l, w across, resists as l / (w g^3) (plane
    // Poiseuille flow, the viscosity a common factor); the cavity as the sum of its bands' ds / (P h^3).
    Slots slots;
    slots.ventDegrees = mold.ventDegrees;
    const double gap = std::max(h, mold.sprueMm);
    slots.sprueReachMm = gap - h;
    if (slots.sprueReachMm > 0.5 * mold.marginMm)
        return Format("a sprue %.3g mm across reaches %.3g mm past the wall, more than half the mold's margin (%.3g mm): give a wider --margin-mm or a "
                      "smaller --sprue-mm",
                      mold.sprueMm, slots.sprueReachMm, mold.marginMm);
    double cavityResistance = 0;  // mm^-3
    for (int j = 1; j < nz; ++j)
        cavityResistance += (solids.cavityPathMm[j] - solids.cavityPathMm[j - 1]) /
                            (0.5 * (solids.cavityPerimeterMm[j] + solids.cavityPerimeterMm[j - 1]) * h * h * h);
    const Vec& sprueInner = inner.At(0, nt / 4);
    const double sprueRadius = std::hypot(sprueInner[0], sprueInner[1]) + 0.5 * gap;  // the slot's mean radius at 90 degrees
    const double sprueWidthNeeded = std::max(mold.sprueMm, 4 * mold.endWallMm / (gap * gap * gap * cavityResistance));
    slots.sprueDegrees = mold.sprueDegrees > 0 ? mold.sprueDegrees : std::min(120.0, sprueWidthNeeded / sprueRadius * 180 / std::numbers::pi);
    int sprueCells = 0;
    for (int i = 0; i < nt; ++i) sprueCells += IsOpening(false, i, nt, slots);
    solids.sprueDegreesBuilt = 360.0 * sprueCells / nt;
    solids.sprueGapMm = gap;
    solids.sprueMouthMm = {0, sprueRadius, -mold.endWallMm};
    solids.sprueResistanceShare = mold.endWallMm / (solids.sprueDegreesBuilt * std::numbers::pi / 180 * sprueRadius * gap * gap * gap) / cavityResistance;
    solids.shellA = Shell(true, outer, inner, w, part, mold, slots, &solids);
    solids.shellB = Shell(false, outer, inner, w, part, mold, slots, &solids);
    if (fittings.enabled) {
        // The insert runs as far as the tube does not narrow below its end ring (else it would cut the wall).
        double insert = fittings.insertMm > 0 ? fittings.insertMm : std::max(part.clampFraction * part.lengthMm, 2 * part.thicknessMm);
        for (const bool atTop : {false, true}) {
            for (int step = 1; step < nz; ++step) {
                const int j = atTop ? nz - 1 - step : step, end = atTop ? nz - 1 : 0;
                const double h = atTop ? part.lengthMm - inner.At(j, 0)[2] : inner.At(j, 0)[2];
                if (h > insert) break;
                for (int i = 0; i < nt; ++i)
                    if (std::hypot(inner.At(j, i)[0], inner.At(j, i)[1]) < std::hypot(inner.At(end, i)[0], inner.At(end, i)[1]) * (1 - 1e-9)) {
                        insert = std::min(insert, std::max(0.0, h - 1e-6));
                        break;
                    }
            }
        }
        if (insert < part.thicknessMm)
            return Format("the tube narrows within %.3g mm of its ends: no room for a fitting's insert (at least one wall, %.3g mm)", insert, part.thicknessMm);
        if (std::string error = Fitting(inner, outer, false, fittings.portMm, fittings, insert, part, &solids.fittingBottom); !error.empty()) return error;
        Fitting(inner, outer, true, 0, fittings, insert, part, &solids.fittingTop);
    }
    *out = std::move(solids);
    return "";
}

}  // namespace sim
