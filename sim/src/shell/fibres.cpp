// Fibre-reinforced walls (docs/models/shell.md section 7): each wall triangle's fibre directions from the fibre
// def, the tension-only fibre energy, and the fibres' state in a deformed wall.
#include <algorithm>
#include <cmath>
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

// Pairs each wall triangle with the next when they share an edge and their fibres are laid alike (the
// same families at the same angles to the meridian; a band's or sector's border keeps its triangles
// apart):
// the staggered tube's two triangles of a strip cell. Why (docs/models/shell.md section 7): two
// families of nearly inextensible fibres put two constraints on each linear triangle, four per
// vertex against its two in-plane freedoms, and a wall held where its fibres are just taut then
// locks; one reading per two triangles leaves the continuum's ratio, as a quadrilateral's one-point
// rule for the stiff term does. A homogeneous strain reads the same either way.
void PairFibreCells(ShellProblem& p, const std::vector<std::array<double, 2>>& anglesDeg) {
    p.fibreCells.clear();
    p.fibreCellOf.assign(p.wall.size(), -1);
    for (size_t t = 0; t + 1 < p.wall.size(); t += 2) {
        const int families = p.fibreFamilies[t];
        if (families == 0 || p.fibreFamilies[t + 1] != families || anglesDeg[t] != anglesDeg[t + 1]) continue;
        const auto& A = p.wall[t];
        const auto& B = p.wall[t + 1];
        int opposite = -1, shared = 0;
        for (int v : B) {
            if (std::find(A.begin(), A.end(), v) != A.end()) ++shared;
            else opposite = v;
        }
        if (shared != 2) continue;
        FibreCell cell;
        cell.vertices = {A[0], A[1], A[2], opposite};
        cell.triangles = {static_cast<int>(t), static_cast<int>(t) + 1};
        cell.families = families;
        cell.area = p.membrane[t].area + p.membrane[t + 1].area;
        for (int k = 0; k < families; ++k) {
            std::array<double, 4> w{};
            for (int side = 0; side < 2; ++side) {
                const int tri = static_cast<int>(t) + side;
                const std::array<double, 3> c = CornerWeights(p, tri, k);
                for (int a = 0; a < 3; ++a) {
                    const int corner = static_cast<int>(std::find(cell.vertices.begin(), cell.vertices.end(), p.wall[tri][a]) - cell.vertices.begin());
                    w[corner] += p.membrane[tri].area / cell.area * c[a];
                }
            }
            // The two facets' rest directions differ by the facets' turn (6 deg at 30 vertices a
            // ring), so their mean is a little shorter than 1.
            Eigen::Vector3d rest = Eigen::Vector3d::Zero();
            for (int v = 0; v < 4; ++v) rest += w[v] * At(p.rest, cell.vertices[v]);
            for (double& weight : w) weight /= rest.norm();
            cell.weights[k] = w;
        }
        p.fibreCellOf[t] = p.fibreCellOf[t + 1] = static_cast<int>(p.fibreCells.size());
        p.fibreCells.push_back(cell);
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
        if (hessian && tautAtKink && I4 > 1 - 1e-12)
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
    p.fibreCellOf.assign(p.wall.size(), -1);
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
    const int c = p.fibreCellOf.empty() ? -1 : p.fibreCellOf[t];
    if (c >= 0) {
        const FibreCell& cell = p.fibreCells[c];
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        for (int v = 0; v < 4; ++v) d += cell.weights[k][v] * At(x, cell.vertices[v]);
        return d;
    }
    const Matrix32 F = DeformationGradient(p, t, x);
    return F.col(0) * p.fibreDirections[t][2 * k] + F.col(1) * p.fibreDirections[t][2 * k + 1];
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
