// Fibre-reinforced walls (docs/models/shell.md section 7): each wall triangle's fibre directions from the fibre
// def, the tension-only fibre energy, and the fibres' state in a deformed wall.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <Eigen/Geometry>

#include "shell/shell_problem.h"

namespace sim {

int FamiliesOn(const FibreDef& f) {
    switch (f.layout) {
        case FibreLayout::None: return 0;
        case FibreLayout::Braid: return int(f.plus) + int(f.minus);
        case FibreLayout::Single: return int(f.plus);
        case FibreLayout::Meridian:
        case FibreLayout::Hoop: return 1;
    }
    return 0;
}

namespace {

Eigen::Vector3d At(const Positions& p, int v) { return {p.x[v], p.y[v], p.z[v]}; }

constexpr double kDegree = std::numbers::pi / 180;

// The rest triangle's tangent frame, as MakeMembraneRest builds it: t1 along the first edge.
void RestFrame(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2, Eigen::Vector3d& t1, Eigen::Vector3d& t2,
               Eigen::Vector3d& normal) {
    const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0;
    normal = e1.cross(e2).normalized();
    t1 = e1.normalized();
    t2 = normal.cross(t1);
}

// The meridian (the surface's tangent along the axis: the axis projected onto the triangle's plane)
// and the hoop direction at a triangle.
void MeridianAndHoop(const Eigen::Vector3d& normal, Eigen::Vector3d& meridian, Eigen::Vector3d& hoop) {
    const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    meridian = (axis - axis.dot(normal) * normal).normalized();
    hoop = normal.cross(meridian);  // right-handed about the outward normal: +alpha winds one way
}

// A triangle's deformed fibre vector F a for family k as weights on its corners: F a = sum_a x_a (g_a . a).
std::array<double, 3> CornerWeights(const ShellProblem& p, int t, int k) {
    const MembraneRest& r = p.membrane[t];
    const double* a = &p.fibreDirections[t][2 * k];
    return {r.g[0][0] * a[0] + r.g[0][1] * a[1], r.g[1][0] * a[0] + r.g[1][1] * a[1], r.g[2][0] * a[0] + r.g[2][1] * a[1]};
}

// Fibre cells (docs/models/shell.md section 7). Two families of nearly inextensible fibres put two
// constraints on each linear triangle, four per vertex against its two in-plane freedoms, and a wall
// held where its fibres are just taut then locks; one reading per two triangles leaves the
// continuum's ratio, as a quadrilateral's one-point rule for the stiff term does. A staggered strip
// pairs its triangles two ways, into parallelograms leaning either way, mirror images of each other:
// a family at +alpha is read on one, at -alpha on the other, so that a braid is as mirror-symmetric
// as its mesh (one way for both turned a +-35 deg braid's top 1.4 deg). A family along the meridian
// or the hoop is its own mirror image and keeps its triangles' own readings, as do triangles whose
// neighbour across the edge is laid differently (a band's or a sector's border).
void PairFibreCells(ShellProblem& p, const std::vector<std::array<double, 2>>& anglesDeg) {
    p.fibreCells.clear();
    p.fibreCellOf.assign(p.wall.size(), {-1, -1});
    // Each directed edge (a, b) with its triangle: the triangle across (a, b) is the one of (b, a).
    std::map<std::pair<int, int>, int> triangleOfEdge;
    for (size_t t = 0; t < p.wall.size(); ++t)
        for (int e = 0; e < 3; ++e) triangleOfEdge[{p.wall[t][e], p.wall[t][(e + 1) % 3]}] = static_cast<int>(t);
    // The triangle across edge (corner e, corner e + 1) of triangle t, or -1.
    const auto across = [&](int t, int e) {
        const auto other = triangleOfEdge.find({p.wall[t][(e + 1) % 3], p.wall[t][e]});
        return other == triangleOfEdge.end() ? -1 : other->second;
    };
    for (size_t first = 0; first < p.wall.size(); ++first) {
        const int t = static_cast<int>(first);
        for (int k = 0; k < p.fibreFamilies[t]; ++k) {
            const double angle = anglesDeg[t][k];
            if (angle == 0 || std::fabs(angle) == 90) continue;
            // A strip's (j,i) (j,i+1) (j+1,i) pairs across its edge 1-2 with (j,i+1) (j+1,i+1) (j+1,i)
            // (leaning one way); that one across its edge 0-1 with the next cell's first (the other).
            const bool leansForward = angle > 0;
            if (t % 2 != (leansForward ? 0 : 1)) continue;
            const int u = across(t, leansForward ? 1 : 0);
            if (u < 0 || p.fibreFamilies[u] != p.fibreFamilies[t] || anglesDeg[u] != anglesDeg[t] || p.fibreCellOf[u][k] >= 0) continue;
            FibreCell cell;
            cell.triangles = {t, u};
            cell.family = k;
            cell.vertices = {p.wall[t][0], p.wall[t][1], p.wall[t][2], -1};
            for (int v : p.wall[u])
                if (std::find(p.wall[t].begin(), p.wall[t].end(), v) == p.wall[t].end()) cell.vertices[3] = v;
            cell.area = p.membrane[t].area + p.membrane[u].area;
            for (int tri : cell.triangles) {
                const std::array<double, 3> c = CornerWeights(p, tri, k);
                for (int a = 0; a < 3; ++a) {
                    const int corner = static_cast<int>(std::find(cell.vertices.begin(), cell.vertices.end(), p.wall[tri][a]) - cell.vertices.begin());
                    cell.weights[corner] += p.membrane[tri].area / cell.area * c[a];
                }
            }
            // The two facets' rest directions differ by the facets' turn (6 deg at 30 vertices a
            // ring), so their mean is a little shorter than 1.
            Eigen::Vector3d rest = Eigen::Vector3d::Zero();
            for (int v = 0; v < 4; ++v) rest += cell.weights[v] * At(p.rest, cell.vertices[v]);
            for (double& weight : cell.weights) weight /= rest.norm();
            p.fibreCellOf[t][k] = p.fibreCellOf[u][k] = static_cast<int>(p.fibreCells.size());
            p.fibreCells.push_back(cell);
        }
    }
}

}  // namespace

double FibreAngleDegAt(const FibreDef& f, double heightFraction, double angle) {
    if (!f.bands.empty()) {
        for (const FibreBand& band : f.bands)
            if (heightFraction >= band.from && heightFraction <= band.to) return band.angleDeg;
        return f.bands.back().angleDeg;  // unreachable for a def that passed ShellDefError
    }
    if (!f.sectorAnglesDeg.empty()) {
        double turn = angle / (2 * std::numbers::pi);
        turn -= std::floor(turn);
        const int sectors = static_cast<int>(f.sectorAnglesDeg.size());
        return f.sectorAnglesDeg[static_cast<size_t>(std::min(sectors - 1, static_cast<int>(turn * sectors)))];
    }
    return f.angleDeg;
}

double FibreDensity(const Matrix32& F, const double a[2], double stiffness, Vector6* gradient, Matrix6* hessian, bool tautAtKink) {
    const Eigen::Vector3d d = F.col(0) * a[0] + F.col(1) * a[1];
    const double I4 = d.squaredNorm();
    if (!(I4 > 1)) {  // slack: threads carry no compression
        // At the kink (a thread at its rest length, within round-off: every thread of the rest
        // state), the energy's second derivative jumps from 0 to 2k (F a)(F a)^T. Newton's matrix
        // takes the taut side: the first step from rest then sees the threads it would stretch
        // (without it, a braided tube's first step overshoots 16-fold and its solve takes twice the
        // factorisations). Anywhere else this would slow convergence: a slack thread has no stiffness.
        if (hessian && tautAtKink && AtTheKink(I4))
            for (int al = 0; al < 2; ++al)
                for (int i = 0; i < 3; ++i)
                    for (int be = 0; be < 2; ++be)
                        for (int j = 0; j < 3; ++j) (*hessian)(3 * al + i, 3 * be + j) += stiffness * 2 * a[al] * d[i] * a[be] * d[j];
        return 0;
    }
    const double excess = I4 - 1;
    if (gradient)
        for (int al = 0; al < 2; ++al)
            for (int i = 0; i < 3; ++i) (*gradient)[3 * al + i] += stiffness * excess * a[al] * d[i];
    if (hessian)
        for (int al = 0; al < 2; ++al)
            for (int i = 0; i < 3; ++i)
                for (int be = 0; be < 2; ++be)
                    for (int j = 0; j < 3; ++j)
                        (*hessian)(3 * al + i, 3 * be + j) += stiffness * (2 * a[al] * d[i] * a[be] * d[j] + (i == j ? excess * a[al] * a[be] : 0.0));
    return 0.25 * stiffness * excess * excess;
}

void SetFibres(ShellProblem& p, const FibreDef& f, double lengthMm, std::string* error) {
    if (error) error->clear();
    p.fibreDirections.assign(p.wall.size(), {0, 0, 0, 0});
    p.fibreFamilies.assign(p.wall.size(), 0);
    p.fibreCells.clear();
    p.fibreCellOf.assign(p.wall.size(), {-1, -1});
    p.fibreStiffness = f.stiffnessNPerMm;
    if (f.layout == FibreLayout::None) return;
    std::vector<std::array<double, 2>> anglesDeg(p.wall.size(), {0, 0});  // per triangle and family, to the meridian
    for (size_t t = 0; t < p.wall.size(); ++t) {
        const auto& tri = p.wall[t];
        const Eigen::Vector3d x0 = At(p.rest, tri[0]), x1 = At(p.rest, tri[1]), x2 = At(p.rest, tri[2]);
        Eigen::Vector3d t1, t2, normal, meridian, hoop;
        RestFrame(x0, x1, x2, t1, t2, normal);
        const Eigen::Vector3d centroid = (x0 + x1 + x2) / 3;
        MeridianAndHoop(normal, meridian, hoop);
        if (!meridian.allFinite()) {
            if (error) *error = "a wall triangle faces along the axis: its meridian, and so its fibre direction, is undefined";
            return;
        }
        double angle = 0;
        switch (f.layout) {
            case FibreLayout::Meridian: angle = 0; break;
            case FibreLayout::Hoop: angle = 90; break;
            default: angle = FibreAngleDegAt(f, centroid.z() / lengthMm, std::atan2(centroid.y(), centroid.x()));
        }
        std::vector<double> angles;  // FamiliesOn's rule
        if (f.layout == FibreLayout::Braid) {
            if (f.plus) angles.push_back(angle);
            if (f.minus) angles.push_back(-angle);
        } else if (f.layout != FibreLayout::Single || f.plus) {
            angles.push_back(angle);
        }
        for (size_t k = 0; k < angles.size(); ++k) {
            const Eigen::Vector3d a = std::cos(angles[k] * kDegree) * meridian + std::sin(angles[k] * kDegree) * hoop;
            p.fibreDirections[t][2 * k] = a.dot(t1);
            p.fibreDirections[t][2 * k + 1] = a.dot(t2);
        }
        p.fibreFamilies[t] = static_cast<int>(angles.size());
        for (size_t k = 0; k < angles.size(); ++k) anglesDeg[t][k] = angles[k];
    }
    PairFibreCells(p, anglesDeg);
}

Eigen::Vector3d FibreVector(const ShellProblem& p, int t, int k, const Positions& x) {
    const int c = p.fibreCellOf.empty() ? -1 : p.fibreCellOf[t][k];
    if (c >= 0) return FibreVector(p.fibreCells[c], x);
    const Matrix32 F = DeformationGradient(p, t, x);
    return F.col(0) * p.fibreDirections[t][2 * k] + F.col(1) * p.fibreDirections[t][2 * k + 1];
}

Eigen::Vector3d FibreVector(const FibreCell& cell, const Positions& x) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (int v = 0; v < 4; ++v) d += cell.weights[v] * At(x, cell.vertices[v]);
    return d;
}

FibreState FibreStates(const ShellProblem& p, const Positions& x) {
    FibreState s;
    for (size_t t = 0; t < p.wall.size(); ++t) {
        if (p.fibreFamilies.empty() || p.fibreFamilies[t] == 0) continue;
        const auto& tri = p.wall[t];
        const Eigen::Vector3d centroid = (At(x, tri[0]) + At(x, tri[1]) + At(x, tri[2])) / 3;
        const Eigen::Vector3d radial = Eigen::Vector3d(centroid.x(), centroid.y(), 0).normalized();
        const Eigen::Vector3d around = Eigen::Vector3d::UnitZ().cross(radial);
        const double restHeight = (p.rest.z[tri[0]] + p.rest.z[tri[1]] + p.rest.z[tri[2]]) / 3;
        for (int k = 0; k < p.fibreFamilies[t]; ++k) {
            const Eigen::Vector3d d = FibreVector(p, static_cast<int>(t), k, x);
            s.stretch.push_back(d.norm());
            s.angleDeg.push_back(std::atan2(std::fabs(d.dot(around)), std::fabs(d.z())) / kDegree);
            s.restHeightMm.push_back(restHeight);
        }
    }
    return s;
}

}  // namespace sim
