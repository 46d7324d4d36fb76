// The shell models' total energy E = membrane + bending - p (V - V0) - F u (+ anchor), its gradient
// and Hessian over the unknowns, assembled into a sparse matrix whose pattern is built once per
// problem. Per-element Hessians are projected to positive semi-definite for Newton's steps (the
// membrane by a 6 x 6 eigen-solve of its F-Hessian, the bending hinge by its Gauss-Newton part);
// the pressure Hessian is never projected: it carries the limit point.
//
// [SECTION] Pattern
// [SECTION] Volume
// [SECTION] Assembly
// [SECTION] Self-intersection
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <limits>
#include <unordered_map>

#include "shell/shell_problem.h"

namespace sim {
namespace {

Eigen::Vector3d At(const Positions& p, int v) { return {p.x[v], p.y[v], p.z[v]}; }

// The unknown a coordinate maps to, or -1.
int Unknown(const ShellProblem& p, int v, int c) {
    const int d = p.dofOf[3 * v + c];
    return d >= 0 ? d : d == kAxial ? p.axial : d == kTwist ? p.twist : -1;
}

template <size_t N>
std::array<int, 3 * N> UnknownsOfVertices(const ShellProblem& p, const std::array<int, N>& vertices) {
    std::array<int, 3 * N> u{};
    for (size_t k = 0; k < N; ++k)
        for (int c = 0; c < 3; ++c) u[3 * k + c] = Unknown(p, vertices[k], c);
    return u;
}

// Neumaier's compensated sum: the enclosed volume is a small difference of large triple products.
struct CompensatedSum {
    double sum = 0, carry = 0;
    void Add(double v) {
        const double t = sum + v;
        carry += std::fabs(sum) >= std::fabs(v) ? (sum - t) + v : (v - t) + sum;
        sum = t;
    }
    double Value() const { return sum + carry; }
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// [SECTION] Pattern
// ---------------------------------------------------------------------------------------------

namespace {

// The unknowns of the top's parameters that meet every element on the clamp (tip free; else none).
std::vector<int> TopCoupledUnknowns(const ShellProblem& p) {
    std::vector<int> top;
    for (int d : TopUnknowns(p))
        if (d >= 0 && p.rigidTop) top.push_back(d);
    return top;
}

// Whether an element has a corner on the clamp's turn (1) or on the rigid top (2, tip free).
char Turned(const ShellProblem& p, const int* vertices, int count) {
    for (int k = 0; k < count; ++k) {
        if (p.dofOf[3 * vertices[k]] == kTwist) return char(1);
        if (p.dofOf[3 * vertices[k]] == kRigid) return char(2);
    }
    return char(0);
}

// Calls add(row, col) for every entry an element's Hessian puts in the matrix: its unknowns' block,
// and (tip free, a corner on the rigid top) its unknowns' couplings with the top's parameters.
template <typename Add>
void ForEachEntryOf(const ShellProblem& p, const std::vector<int>& top, const int* vertices, int count, Add&& add) {
    int u[12];
    for (int k = 0; k < count; ++k)
        for (int c = 0; c < 3; ++c) u[3 * k + c] = Unknown(p, vertices[k], c);
    for (int i = 0; i < 3 * count; ++i)
        for (int j = 0; j < 3 * count; ++j)
            if (u[i] >= 0 && u[j] >= 0) add(u[i], u[j]);
    if (top.empty() || Turned(p, vertices, count) != 2) return;
    for (int i = 0; i < 3 * count; ++i)
        if (u[i] >= 0)
            for (int t : top) {
                add(u[i], t);
                add(t, u[i]);
            }
}

}  // namespace

int HessianPattern::Slot(int row, int col) const {
    if (row < 0 || col < 0) return -1;
    const int* begin = matrix.innerIndexPtr() + matrix.outerIndexPtr()[col];
    const int* end = matrix.innerIndexPtr() + matrix.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - matrix.innerIndexPtr());
}

HessianPattern::HessianPattern(const ShellProblem& p, const std::vector<ContactPair>& contact) : contactPairs(contact) {
    std::vector<Eigen::Triplet<double>> entries;
    const std::vector<int> top = TopCoupledUnknowns(p);
    const auto add = [&](int row, int col) { entries.emplace_back(row, col, 0.0); };
    for (const auto& t : p.wall) ForEachEntryOf(p, top, t.data(), 3, add);
    for (const auto& t : p.caps) ForEachEntryOf(p, top, t.data(), 3, add);
    for (const auto& h : p.hinges) ForEachEntryOf(p, top, h.data(), 4, add);
    for (const auto& cell : p.fibreCells) ForEachEntryOf(p, top, cell.vertices.data(), 4, add);
    for (const auto& c : contactPairs) ForEachEntryOf(p, top, c.vertices.data(), 4, add);
    std::vector<int> anchored;
    for (int v : p.anchor.vertices)
        for (int c = 0; c < 3; ++c) anchored.push_back(Unknown(p, v, c));
    for (int a : anchored)
        for (int b : anchored)
            if (a >= 0 && b >= 0) add(a, b);
    for (int a : top)
        for (int b : top) add(a, b);
    for (int d = 0; d < p.unknowns; ++d) add(d, d);  // a full diagonal for shifts
    matrix.resize(p.unknowns, p.unknowns);
    matrix.setFromTriplets(entries.begin(), entries.end());
    matrix.makeCompressed();

    auto slots = [&](const int* u, int count, std::vector<int>& into) {
        for (int i = 0; i < count; ++i)
            for (int j = 0; j < count; ++j) into.push_back(Slot(u[i], u[j]));
    };
    for (const auto& t : p.wall) slots(UnknownsOfVertices(p, t).data(), 9, wallSlots);
    for (const auto& t : p.caps) slots(UnknownsOfVertices(p, t).data(), 9, capSlots);
    for (const auto& h : p.hinges) slots(UnknownsOfVertices(p, h).data(), 12, hingeSlots);
    for (const auto& cell : p.fibreCells) slots(UnknownsOfVertices(p, cell.vertices).data(), 12, fibreCellSlots);
    slots(anchored.data(), static_cast<int>(anchored.size()), anchorSlots);
    for (const auto& t : p.wall) wallTurned.push_back(Turned(p, t.data(), 3));
    for (const auto& t : p.caps) capTurned.push_back(Turned(p, t.data(), 3));
    for (const auto& h : p.hinges) hingeTurned.push_back(Turned(p, h.data(), 4));
    for (const auto& cell : p.fibreCells) fibreCellTurned.push_back(Turned(p, cell.vertices.data(), 4));
    PlaceContactAndTop(p, top);
}

// The same matrix as building from scratch, entry for entry: each column's rows are the base's and
// the contact blocks', merged in order, and every base slot moves to where its entry now sits.
// Listing the wall's elements again (hundreds of thousands of entries through a sort) cost a
// third of a collapsing tube's solve, whose list changes at most steps.
HessianPattern::HessianPattern(const HessianPattern& base, const ShellProblem& p, const std::vector<ContactPair>& contact)
    : wallSlots(base.wallSlots), hingeSlots(base.hingeSlots), capSlots(base.capSlots), fibreCellSlots(base.fibreCellSlots),
      anchorSlots(base.anchorSlots), contactPairs(contact), wallTurned(base.wallTurned), capTurned(base.capTurned),
      hingeTurned(base.hingeTurned), fibreCellTurned(base.fibreCellTurned) {
    const int n = p.unknowns;
    const std::vector<int> top = TopCoupledUnknowns(p);
    // The contact blocks' entries, bucketed by column, then sorted and made unique in each.
    std::vector<int> extraBegin(n + 1, 0);
    for (const ContactPair& c : contactPairs) ForEachEntryOf(p, top, c.vertices.data(), 4, [&](int, int col) { ++extraBegin[col + 1]; });
    for (int col = 0; col < n; ++col) extraBegin[col + 1] += extraBegin[col];
    std::vector<int> extraRows(extraBegin[n]);
    std::vector<int> fill(extraBegin.begin(), extraBegin.end() - 1);
    for (const ContactPair& c : contactPairs) ForEachEntryOf(p, top, c.vertices.data(), 4, [&](int row, int col) { extraRows[fill[col]++] = row; });

    const int* baseOuter = base.matrix.outerIndexPtr();
    const int* baseInner = base.matrix.innerIndexPtr();
    std::vector<int> outer(n + 1, 0), inner;
    inner.reserve(base.matrix.nonZeros() + extraRows.size());
    std::vector<int> moved(base.matrix.nonZeros());  // a base entry's index in the new matrix
    for (int col = 0; col < n; ++col) {
        int* first = extraRows.data() + extraBegin[col];
        int* last = extraRows.data() + extraBegin[col + 1];
        std::sort(first, last);
        last = std::unique(first, last);
        int b = baseOuter[col];
        const int bEnd = baseOuter[col + 1];
        while (b < bEnd || first != last) {
            if (first == last || (b < bEnd && baseInner[b] <= *first)) {
                if (first != last && baseInner[b] == *first) ++first;
                moved[b] = static_cast<int>(inner.size());
                inner.push_back(baseInner[b++]);
            } else {
                inner.push_back(*first++);
            }
        }
        outer[col + 1] = static_cast<int>(inner.size());
    }
    const std::vector<double> values(inner.size(), 0.0);
    matrix = Eigen::Map<const Eigen::SparseMatrix<double>>(n, n, static_cast<Eigen::Index>(inner.size()), outer.data(), inner.data(), values.data());
    for (auto* slots : {&wallSlots, &hingeSlots, &capSlots, &fibreCellSlots, &anchorSlots})
        for (int& s : *slots)
            if (s >= 0) s = moved[s];
    PlaceContactAndTop(p, top);
}

void HessianPattern::PlaceContactAndTop(const ShellProblem& p, const std::vector<int>& top) {
    contactSlots.reserve(144 * contactPairs.size());
    for (const auto& c : contactPairs) {
        const auto u = UnknownsOfVertices(p, c.vertices);
        for (int i = 0; i < 12; ++i)
            for (int j = 0; j < 12; ++j) contactSlots.push_back(Slot(u[i], u[j]));
        contactTurned.push_back(Turned(p, c.vertices.data(), 4));
    }
    twistSlot = p.rigidTop ? -1 : Slot(p.twist, p.twist);
    const std::array<int, kTopParameters> topUnknown = TopUnknowns(p);
    for (int k = 0; k < kTopParameters && !top.empty(); ++k) {
        const int t = topUnknown[k];
        for (int l = 0; l < kTopParameters; ++l) topBlockSlots[k][l] = Slot(t, topUnknown[l]);
        if (t < 0) continue;
        for (int i = matrix.outerIndexPtr()[t]; i < matrix.outerIndexPtr()[t + 1]; ++i) {
            const int row = matrix.innerIndexPtr()[i];
            if (std::find(top.begin(), top.end(), row) == top.end()) topCouplings[k].push_back({row, i, Slot(t, row)});
        }
    }
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Volume
// ---------------------------------------------------------------------------------------------

double EnclosedVolume(const ShellProblem& p, const Positions& x) {
    CompensatedSum sum;
    for (const auto* triangles : {&p.wall, &p.caps})
        for (const auto& t : *triangles) sum.Add(At(x, t[0]).dot(At(x, t[1]).cross(At(x, t[2]))));
    return sum.Value() / 6;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Assembly
// ---------------------------------------------------------------------------------------------

EnergyResult AssembleEnergy(const ShellProblem& p, const Eigen::VectorXd& q, const LoadTerms& load, const EnergyTerms& terms, bool wantGradient,
                            HessianPattern* hessian, HessianKind kind) {
    Positions x;
    PositionsOf(p, q, x);
    EnergyResult r;
    // The clamp's turn is not linear in theta: its curvature term needs every force on the clamp.
    wantGradient = wantGradient || (hessian && (p.twist >= 0 || p.rigidTop));
    if (wantGradient) {
        r.gradient = Eigen::VectorXd::Zero(p.unknowns);
        r.volumeGradient = Eigen::VectorXd::Zero(p.unknowns);
    }
    double* values = nullptr;
    if (hessian) {
        values = hessian->matrix.valuePtr();
        std::fill(values, values + hessian->matrix.nonZeros(), 0.0);
    }
    double axialForce = 0;   // dE/du, accumulated from every axial coordinate
    double twistTorque = 0;  // dE/dtheta, from every turned coordinate
    double twistCurvature = 0;  // sum of dE/dx . d2x/dtheta2 over the turned coordinates
    // A turned coordinate's lever dx/dtheta = e_z x x (the axis through x = y = 0), and d2x/dtheta2 = -x
    // in the plane.
    auto lever = [&](int v, int c) { return c == 0 ? -x.y[v] : x.x[v]; };
    // The top clamp as a rigid body (docs/models/shell.md section 12): every force on it summed as a
    // resultant and the matrix sum g_i (X_i - c0)^T, from which dE/dt = the resultant and dE/da_k =
    // <dR/da_k, that matrix> (Frobenius). Kept for the energy (its loads: the reactions) and the
    // volume (its gradient, tip free).
    struct TopSum {
        Eigen::Vector3d force = Eigen::Vector3d::Zero();
        Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
    } topEnergy, topVolume;
    const Eigen::Vector3d c0 = p.topCap >= 0 ? At(p.rest, p.topCap) : Eigen::Vector3d::Zero();
    const std::array<double, kTopParameters> top = p.onTop.empty() ? std::array<double, kTopParameters>{} : TopParameters(p, q);
    const double angles[3] = {top[kTopTiltX], top[kTopTiltY], top[kTopTwist]};
    Eigen::Matrix3d dR[3];  // dR/da_k, k = tilt x, tilt y, twist
    for (int k = 0; k < 3 && !p.onTop.empty(); ++k) dR[k] = TopRotation(angles, k == 0, k == 1, k == 2);
    auto addGradient = [&](Eigen::VectorXd& g, int v, int c, double value, double* axial) {
        const int d = p.dofOf[3 * v + c];
        if (d >= 0) {
            g[d] += value;
            return;
        }
        if (!p.onTop.empty() && p.onTop[v] && (axial || p.rigidTop)) {  // the volume's slopes only for a free tip's unknowns
            TopSum& sum = axial ? topEnergy : topVolume;
            sum.force[c] += value;
            sum.moment.row(c) += value * (Eigen::RowVector3d(p.rest.x[v], p.rest.y[v], p.rest.z[v]) - c0.transpose());
        }
        if (d == kAxial) {
            if (p.axial >= 0) g[p.axial] += value;
            if (axial) *axial += value;
        } else if (d == kTwist) {
            const double torque = lever(v, c) * value;
            if (p.twist >= 0) g[p.twist] += torque;
            if (axial) {  // the energy's gradient (not the volume's)
                twistTorque += torque;
                twistCurvature -= (c == 0 ? x.x[v] : x.y[v]) * value;
            }
        }
    };
    // An element's Hessian over its vertices' coordinates into the unknowns': a turned coordinate's
    // rows and columns scaled by its lever (`turned`: the element has one, from the pattern).
    // Tip free: an element's Hessian H over a clamp vertex's coordinates reaches the top's parameters
    // through J = dx/d(parameters): (unknown, parameter) entries H J into `topColumns`, (parameter,
    // parameter) ones J^T H J into `topBlock`, scattered once at the end.
    Eigen::Matrix<double, Eigen::Dynamic, kTopParameters> topColumns;
    Eigen::Matrix<double, kTopParameters, kTopParameters> topBlock = Eigen::Matrix<double, kTopParameters, kTopParameters>::Zero();
    if (hessian && p.rigidTop) topColumns = Eigen::Matrix<double, Eigen::Dynamic, kTopParameters>::Zero(p.unknowns, kTopParameters);
    auto topJacobianRow = [&](int v, int c) {
        Eigen::Matrix<double, 1, kTopParameters> row = Eigen::Matrix<double, 1, kTopParameters>::Zero();
        row[c] = 1;
        const Eigen::Vector3d Y = Eigen::Vector3d(p.rest.x[v], p.rest.y[v], p.rest.z[v]) - c0;
        for (int k = 0; k < 3; ++k) row[3 + k] = dR[k].row(c).dot(Y);
        return row;
    };
    auto addHessian = [&](const int* slots, const double* local, int count, const int* vertices, char turned) {
        if (turned != 1) {
            for (int i = 0; i < count * count; ++i)
                if (slots[i] >= 0) values[slots[i]] += local[i];
            if (turned == 0) return;
            // The rigid top's part (the slots above skip its coordinates).
            std::array<Eigen::Matrix<double, 1, kTopParameters>, 12> J;
            std::array<int, 12> unknown;
            for (int k = 0; k < count; ++k) {
                const int v = vertices[k / 3], c = k % 3;
                unknown[k] = p.dofOf[3 * v + c] == kRigid ? -2 : Unknown(p, v, c);
                if (unknown[k] == -2) J[k] = topJacobianRow(v, c);
            }
            for (int i = 0; i < count; ++i) {
                if (unknown[i] != -2) continue;
                for (int j = 0; j < count; ++j) {
                    const double h = local[i * count + j];
                    if (unknown[j] == -2) topBlock += J[i].transpose() * (h * J[j]);
                    else if (unknown[j] >= 0) topColumns.row(unknown[j]) += h * J[i];
                }
            }
            return;
        }
        std::array<double, 12> scale{};  // elements only: the anchor (sliding ends) has no turned coordinates
        for (int k = 0; k < count; ++k) {
            const int v = vertices[k / 3], c = k % 3;
            scale[k] = p.dofOf[3 * v + c] == kTwist ? lever(v, c) : 1.0;
        }
        for (int i = 0; i < count * count; ++i)
            if (slots[i] >= 0) values[slots[i]] += local[i] * scale[i / count] * scale[i % count];
    };

    CompensatedSum energy;
    // Membrane and fibres: A0 (Psi(F) + sum over families (k/4)(I4 - 1)^2) per wall triangle.
    const bool withFibres = terms.fibres && !p.fibreFamilies.empty();
    if (terms.membrane || withFibres) {
        for (size_t t = 0; t < p.wall.size(); ++t) {
            const int families = withFibres ? p.fibreFamilies[t] : 0;
            const bool ownFibres = families > 0 && (p.fibreCellOf[t][0] < 0 || (families > 1 && p.fibreCellOf[t][1] < 0));
            if (!terms.membrane && !ownFibres) continue;  // a cell's fibres come below
            const auto& tri = p.wall[t];
            const MembraneRest& rest = p.membrane[t];
            const Matrix32 F = DeformationGradient(p, static_cast<int>(t), x);
            Vector6 gF = Vector6::Zero();
            Matrix6 hF = Matrix6::Zero();
            Vector6* gradientOfF = wantGradient || hessian ? &gF : nullptr;
            Matrix6* hessianOfF = hessian ? &hF : nullptr;
            double density = terms.membrane ? MembraneDensity(p.material, F, gradientOfF, hessianOfF) : 0.0;
            // The fibres' part is positive semi-definite where taut and zero where slack.
            for (int k = 0; k < families; ++k)
                if (p.fibreCellOf[t][k] < 0)  // else read with its cell's, below
                    density += FibreDensity(F, &p.fibreDirections[t][2 * k], p.fibreStiffness, gradientOfF, hessianOfF, kind != HessianKind::Exact);
            energy.Add(rest.area * density);
            if (wantGradient || hessian) {
                // dE/dx_a = A0 sum_alpha g_a[alpha] dPsi/df_alpha.
                if (wantGradient)
                    for (int a = 0; a < 3; ++a)
                        for (int c = 0; c < 3; ++c)
                            addGradient(r.gradient, tri[a], c, rest.area * (rest.g[a][0] * gF[c] + rest.g[a][1] * gF[3 + c]), &axialForce);
            }
            if (hessian) {
                // Projected to positive semi-definite: most elements in tension already are (a 6 x 6
                // Cholesky says so cheaply); the rest go through an eigen-solve with the negative
                // eigenvalues clamped to zero.
                if (kind != HessianKind::Exact && Eigen::LLT<Matrix6>(hF).info() != Eigen::Success) {
                    Eigen::SelfAdjointEigenSolver<Matrix6> eigen(hF);
                    const Vector6 clamped = eigen.eigenvalues().cwiseMax(0.0);
                    hF = eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
                }
                double local[81];
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b)
                        for (int i = 0; i < 3; ++i)
                            for (int j = 0; j < 3; ++j) {
                                double sum = 0;
                                for (int al = 0; al < 2; ++al)
                                    for (int be = 0; be < 2; ++be) sum += rest.g[a][al] * rest.g[b][be] * hF(3 * al + i, 3 * be + j);
                                local[(3 * a + i) * 9 + 3 * b + j] = rest.area * sum;
                            }
                addHessian(&hessian->wallSlots[81 * t], local, 9, tri.data(), hessian->wallTurned[t]);
            }
        }
    }
    // Fibre cells: A (k/4)(|d|^2 - 1)^2 per taut cell, d = sum_v w_v x_v.
    if (withFibres) {
        for (size_t c = 0; c < p.fibreCells.size(); ++c) {
            const FibreCell& cell = p.fibreCells[c];
            const auto& w = cell.weights;
            const Eigen::Vector3d d = FibreVector(cell, x);
            const double I4 = d.squaredNorm(), excess = I4 - 1, scale = cell.area * p.fibreStiffness;
            const bool taut = I4 > 1;
            // At the kink Newton's matrix takes the taut side, as a triangle's fibres do (FibreDensity).
            const bool kinkHessian = hessian && kind != HessianKind::Exact && AtTheKink(I4);
            if (!taut && !kinkHessian) continue;
            if (taut) energy.Add(0.25 * scale * excess * excess);
            if (wantGradient && taut)
                for (int v = 0; v < 4; ++v)
                    for (int i = 0; i < 3; ++i) addGradient(r.gradient, cell.vertices[v], i, scale * excess * w[v] * d[i], &axialForce);
            if (hessian) {
                // A k w_u w_v (2 d d^T + (I4 - 1) 1): positive semi-definite where taut.
                double local[144];
                for (int u = 0; u < 4; ++u)
                    for (int i = 0; i < 3; ++i)
                        for (int v = 0; v < 4; ++v)
                            for (int j = 0; j < 3; ++j)
                                local[(3 * u + i) * 12 + 3 * v + j] =
                                    scale * w[u] * w[v] * (2 * d[i] * d[j] + (taut && i == j ? excess : 0.0));
                addHessian(&hessian->fibreCellSlots[144 * c], local, 12, cell.vertices.data(), hessian->fibreCellTurned[c]);
            }
        }
    }
    // Bending: k (theta - theta0)^2 per hinge.
    if (terms.bending && p.bending) {
        for (size_t k = 0; k < p.hinges.size(); ++k) {
            const auto& h = p.hinges[k];
            Eigen::Matrix<double, 12, 1> xs, gTheta;
            Eigen::Matrix<double, 12, 12> hTheta;
            for (int v = 0; v < 4; ++v) xs.segment<3>(3 * v) = At(x, h[v]);
            const bool exactHessian = hessian && kind == HessianKind::Exact;
            const double theta = HingeAngle(xs, wantGradient || hessian ? &gTheta : nullptr, exactHessian ? &hTheta : nullptr);
            double d = theta - p.hingeRestAngle[k];
            d -= 2 * std::numbers::pi * std::round(d / (2 * std::numbers::pi));  // the short way round
            const double stiffness = p.hingeStiffness[k];
            energy.Add(stiffness * d * d);
            if (wantGradient)
                for (int v = 0; v < 4; ++v)
                    for (int c = 0; c < 3; ++c) addGradient(r.gradient, h[v], c, 2 * stiffness * d * gTheta[3 * v + c], &axialForce);
            if (hessian) {
                // Gauss-Newton (2k g g^T) for Newton's steps: positive semi-definite by construction.
                Eigen::Matrix<double, 12, 12, Eigen::RowMajor> local = 2 * stiffness * gTheta * gTheta.transpose();
                if (exactHessian) local += 2 * stiffness * d * hTheta;
                addHessian(&hessian->hingeSlots[144 * k], local.data(), 12, h.data(), hessian->hingeTurned[k]);
            }
        }
    }
    // Pressure (or sealed gas): -p (V - V0), with V = (1/6) sum x_a . (x_b x x_c) over walls and caps.
    CompensatedSum volumeChange;
    for (const auto* triangles : {&p.wall, &p.caps})
        for (const auto& t : *triangles)
            volumeChange.Add(At(x, t[0]).dot(At(x, t[1]).cross(At(x, t[2]))) - At(p.rest, t[0]).dot(At(p.rest, t[1]).cross(At(p.rest, t[2]))));
    const double deltaV = volumeChange.Value() / 6;
    r.volume = p.restVolume + deltaV;
    const bool gas = load.gasConstant > 0;
    const double pressure = gas ? load.gasConstant / r.volume - load.atmosphere : load.pressure;  // gauge
    if (terms.pressure) {
        if (gas) energy.Add(-load.gasConstant * std::log(r.volume / p.restVolume) + load.atmosphere * deltaV);
        else energy.Add(-load.pressure * deltaV);
    }
    if (wantGradient || hessian) {
        size_t capIndex = 0;
        for (const auto* triangles : {&p.wall, &p.caps}) {
            const bool caps = triangles == &p.caps;
            for (size_t t = 0; t < triangles->size(); ++t) {
                const auto& tri = (*triangles)[t];
                const Eigen::Vector3d a = At(x, tri[0]), b = At(x, tri[1]), c = At(x, tri[2]);
                const Eigen::Vector3d dV[3] = {b.cross(c) / 6, c.cross(a) / 6, a.cross(b) / 6};
                if (wantGradient)
                    for (int k = 0; k < 3; ++k)
                        for (int cc = 0; cc < 3; ++cc) {
                            addGradient(r.volumeGradient, tri[k], cc, dV[k][cc], nullptr);
                            if (terms.pressure) addGradient(r.gradient, tri[k], cc, -pressure * dV[k][cc], &axialForce);
                        }
                if (hessian && terms.pressure && kind != HessianKind::Definite) {
                    // d2V/dx_a dx_b = -[x_c]x / 6 for (a, b) cyclic; its transpose for (b, a).
                    auto cross = [](const Eigen::Vector3d& v) {
                        Eigen::Matrix3d m;
                        m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
                        return m;
                    };
                    Eigen::Matrix<double, 9, 9, Eigen::RowMajor> local = Eigen::Matrix<double, 9, 9, Eigen::RowMajor>::Zero();
                    const Eigen::Vector3d* corner[3] = {&a, &b, &c};
                    for (int k = 0; k < 3; ++k) {
                        const int next = (k + 1) % 3, last = (k + 2) % 3;
                        local.block<3, 3>(3 * k, 3 * next) = -pressure * -cross(*corner[last]) / 6;
                        local.block<3, 3>(3 * next, 3 * k) = -pressure * cross(*corner[last]) / 6;
                    }
                    addHessian(caps ? &hessian->capSlots[81 * capIndex] : &hessian->wallSlots[81 * t], local.data(), 9, tri.data(),
                               caps ? hessian->capTurned[capIndex] : hessian->wallTurned[t]);
                }
                if (caps) ++capIndex;
            }
        }
    }
    // Self-contact: kappa m b(d - h) over the pairs within reach (docs/models/shell.md section 8).
    if (terms.contact && p.contact) {
        std::vector<ContactPair> found;
        const std::vector<ContactPair>* pairs = &found;
        if (terms.contactList && terms.contactList->Covers(x)) pairs = &terms.contactList->pairs;
        else if (!hessian && terms.contactSweep && terms.contactSweep->Covers(x)) pairs = &terms.contactSweep->pairs;
        else found = ContactCandidates(*p.contact, x, nullptr, ContactReachMm(p.barrier));
        CompensatedSum contact;
        for (const ContactPair& pair : *pairs) {
            Vector12 c;
            if (!InReach(pair, x, p.barrier, &c)) continue;
            const double threshold = pair.kind == PairKind::EdgeEdge ? EdgeEdgeMollifierThreshold(PairCoordinates(pair, p.rest)) : 0;
            Vector12 g;
            Matrix12 H;
            const double e = PairBarrierEnergy(pair.kind, c, threshold, p.barrier, wantGradient ? &g : nullptr, hessian ? &H : nullptr,
                                               kind != HessianKind::Exact);
            if (!std::isfinite(e)) {  // a wall at or through another: no state the solver may accept
                r.contactEnergy = std::numeric_limits<double>::infinity();
                continue;
            }
            contact.Add(e);
            if (wantGradient)
                for (int k = 0; k < 12; ++k) addGradient(r.gradient, pair.vertices[k / 3], k % 3, g[k], &axialForce);
            if (hessian) {
                const auto& held = hessian->contactPairs;
                const auto at = std::lower_bound(held.begin(), held.end(), pair);
                if (at == held.end() || !(*at == pair)) continue;  // not in the pattern: the solver keeps them matched
                const size_t index = static_cast<size_t>(at - held.begin());
                const Eigen::Matrix<double, 12, 12, Eigen::RowMajor> local = H;
                addHessian(&hessian->contactSlots[144 * index], local.data(), 12, pair.vertices.data(), hessian->contactTurned[index]);
            }
        }
        if (std::isfinite(r.contactEnergy)) {
            r.contactEnergy = contact.Value();
            energy.Add(r.contactEnergy);
        }
    }
    // Axial force on the top clamp: -F u.
    const double u = p.axial >= 0 ? q[p.axial] : p.heldAxial;
    if (terms.force && load.force != 0) {
        energy.Add(-load.force * u);
        if (wantGradient && p.axial >= 0) r.gradient[p.axial] -= load.force;
        axialForce -= load.force;
    }
    // Torque on the top clamp: -T theta.
    const double theta = p.twist >= 0 ? q[p.twist] : p.heldTwist;
    if (terms.force && load.torque != 0) {
        energy.Add(-load.torque * theta);
        if (wantGradient && p.twist >= 0) r.gradient[p.twist] -= load.torque;
        twistTorque -= load.torque;
    }
    // Anchor against rigid motions: (k/2)(|T|^2 + |R|^2).
    if (terms.anchor && !p.anchor.vertices.empty()) {
        const Anchor& an = p.anchor;
        Eigen::Vector3d T = Eigen::Vector3d::Zero(), R = Eigen::Vector3d::Zero();
        for (int v : an.vertices) {
            const Eigen::Vector3d X = At(p.rest, v), d = At(x, v) - X;
            T += d;
            R += X.cross(d);
        }
        for (int c = 0; c < 3; ++c) {
            if (!an.translation[c]) T[c] = 0;
            if (!an.rotation[c]) R[c] = 0;
        }
        energy.Add(0.5 * an.stiffness * (T.squaredNorm() + R.squaredNorm()));
        // Each selected component s is linear in the coordinates: s = a . x; E = (k/2) sum s^2.
        const int n = static_cast<int>(an.vertices.size());
        std::vector<Eigen::VectorXd> rows;
        for (int c = 0; c < 3; ++c) {
            if (an.translation[c]) {
                Eigen::VectorXd a = Eigen::VectorXd::Zero(3 * n);
                for (int k = 0; k < n; ++k) a[3 * k + c] = 1;
                rows.push_back(a);
            }
            if (an.rotation[c]) {
                Eigen::VectorXd a = Eigen::VectorXd::Zero(3 * n);
                for (int k = 0; k < n; ++k) {
                    const Eigen::Vector3d X = At(p.rest, an.vertices[k]);
                    Eigen::Matrix3d m;
                    m << 0, -X.z(), X.y(), X.z(), 0, -X.x(), -X.y(), X.x(), 0;
                    a.segment<3>(3 * k) = m.row(c).transpose();
                }
                rows.push_back(a);
            }
        }
        std::vector<double> components;
        for (int c = 0; c < 3; ++c) {
            if (an.translation[c]) components.push_back(T[c]);
            if (an.rotation[c]) components.push_back(R[c]);
        }
        if (wantGradient)
            for (size_t s = 0; s < rows.size(); ++s)
                for (int k = 0; k < n; ++k)
                    for (int c = 0; c < 3; ++c) addGradient(r.gradient, an.vertices[k], c, an.stiffness * components[s] * rows[s][3 * k + c], &axialForce);
        if (hessian) {
            Eigen::MatrixXd local = Eigen::MatrixXd::Zero(3 * n, 3 * n);
            for (const auto& a : rows) local += an.stiffness * a * a.transpose();
            Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rowMajor = local;
            addHessian(hessian->anchorSlots.data(), rowMajor.data(), 3 * n, an.vertices.data(), false);  // sliding ends: no turned coordinates
        }
    }
    // The turn's own curvature: exact, or (for Newton's steps) only where it stiffens.
    if (hessian && hessian->twistSlot >= 0) values[hessian->twistSlot] += kind == HessianKind::Exact ? twistCurvature : std::max(0.0, twistCurvature);
    // The top clamp's loads: the resultant along x, y, z and the moments about its tilt and twist axes.
    std::array<double, kTopParameters> topLoads{}, topVolumeSlopes{};
    for (int k = 0; k < 3 && !p.onTop.empty(); ++k) {
        topLoads[k] = topEnergy.force[k];
        topLoads[3 + k] = (dR[k].array() * topEnergy.moment.array()).sum();
        topVolumeSlopes[k] = topVolume.force[k];
        topVolumeSlopes[3 + k] = (dR[k].array() * topVolume.moment.array()).sum();
    }
    if (p.rigidTop) {
        const std::array<int, kTopParameters> unknown = TopUnknowns(p);
        if (wantGradient)
            for (int k = 0; k < kTopParameters; ++k)
                if (unknown[k] >= 0) {
                    r.gradient[unknown[k]] += topLoads[k];
                    r.volumeGradient[unknown[k]] += topVolumeSlopes[k];
                }
        axialForce += topLoads[kTopAxial];
        twistTorque += topLoads[kTopTwist];
        if (hessian) {
            // R's own curvature: sum_i g_i . d2x_i/da_k da_l = <d2R/da_k da_l, sum g_i Y_i^T>; exact, or
            // (for Newton's steps) projected to where it stiffens.
            Eigen::Matrix3d curvature;
            for (int k = 0; k < 3; ++k)
                for (int l = 0; l < 3; ++l) {
                    const int order[3] = {(k == 0) + (l == 0), (k == 1) + (l == 1), (k == 2) + (l == 2)};
                    curvature(k, l) = (TopRotation(angles, order[0], order[1], order[2]).array() * topEnergy.moment.array()).sum();
                }
            if (kind != HessianKind::Exact) {
                Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(curvature);
                curvature = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
            }
            topBlock.bottomRightCorner<3, 3>() += curvature;
            for (int k = 0; k < kTopParameters; ++k) {
                if (unknown[k] < 0) continue;
                for (int l = 0; l < kTopParameters; ++l)
                    if (unknown[l] >= 0) values[hessian->topBlockSlots[k][l]] += topBlock(k, l);
                for (const auto& [row, slot, transposed] : hessian->topCouplings[k]) {
                    values[slot] += topColumns(row, k);
                    values[transposed] += topColumns(row, k);
                }
            }
        }
    }
    r.energy = std::isfinite(r.contactEnergy) ? energy.Value() : r.contactEnergy;
    r.axialForce = axialForce;
    r.twistTorque = twistTorque;
    r.topLoads = topLoads;
    return r;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Self-intersection
// ---------------------------------------------------------------------------------------------
namespace {

// Whether segment [a, b] crosses triangle (p, q, r) (Moller-Trumbore, strict interior).
bool SegmentHitsTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                         const Eigen::Vector3d& r) {
    const Eigen::Vector3d dir = b - a, e1 = q - p, e2 = r - p;
    const Eigen::Vector3d h = dir.cross(e2);
    const double det = e1.dot(h);
    const double scale = e1.norm() * e2.norm() * dir.norm();
    if (std::fabs(det) <= 1e-12 * scale) return false;  // parallel (coplanar contact is not a crossing)
    const double inv = 1 / det;
    const Eigen::Vector3d s = a - p;
    const double u = inv * s.dot(h);
    if (u <= 0 || u >= 1) return false;
    const Eigen::Vector3d qv = s.cross(e1);
    const double v = inv * dir.dot(qv);
    if (v <= 0 || u + v >= 1) return false;
    const double t = inv * e2.dot(qv);
    return t > 0 && t < 1;
}

bool TrianglesIntersect(const std::array<Eigen::Vector3d, 3>& A, const std::array<Eigen::Vector3d, 3>& B) {
    for (int k = 0; k < 3; ++k) {
        if (SegmentHitsTriangle(A[k], A[(k + 1) % 3], B[0], B[1], B[2])) return true;
        if (SegmentHitsTriangle(B[k], B[(k + 1) % 3], A[0], A[1], A[2])) return true;
    }
    return false;
}

}  // namespace

bool SelfIntersects(const ShellProblem& p, const Positions& x) {
    std::vector<std::array<int, 3>> triangles = p.wall;
    triangles.insert(triangles.end(), p.caps.begin(), p.caps.end());
    if (triangles.empty()) return false;
    // A uniform hash grid, cells about the longest edge: each triangle goes into every cell its box touches.
    double cell = 0;
    for (const auto& t : triangles)
        for (int k = 0; k < 3; ++k) cell = std::max(cell, (At(x, t[k]) - At(x, t[(k + 1) % 3])).norm());
    if (!(cell > 0) || !std::isfinite(cell)) return false;
    std::unordered_map<std::uint64_t, std::vector<int>> grid;
    auto key = [](long long i, long long j, long long k) {
        return (static_cast<std::uint64_t>(i & 0x1fffff) << 42) | (static_cast<std::uint64_t>(j & 0x1fffff) << 21) | static_cast<std::uint64_t>(k & 0x1fffff);
    };
    std::vector<Eigen::Vector3d> lows(triangles.size()), highs(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t) {
        Eigen::Vector3d lo = At(x, triangles[t][0]), hi = lo;
        for (int k = 1; k < 3; ++k) {
            lo = lo.cwiseMin(At(x, triangles[t][k]));
            hi = hi.cwiseMax(At(x, triangles[t][k]));
        }
        lows[t] = lo;
        highs[t] = hi;
        for (long long i = std::llround(std::floor(lo.x() / cell)); i <= std::llround(std::floor(hi.x() / cell)); ++i)
            for (long long j = std::llround(std::floor(lo.y() / cell)); j <= std::llround(std::floor(hi.y() / cell)); ++j)
                for (long long k = std::llround(std::floor(lo.z() / cell)); k <= std::llround(std::floor(hi.z() / cell)); ++k)
                    grid[key(i, j, k)].push_back(static_cast<int>(t));
    }
    for (const auto& [unused, members] : grid)
        for (size_t m = 0; m < members.size(); ++m)
            for (size_t n = m + 1; n < members.size(); ++n) {
                const auto& A = triangles[members[m]];
                const auto& B = triangles[members[n]];
                // Boxes apart: most pairs sharing a cell (cheaper than the exact test by far).
                if ((lows[members[m]].array() > highs[members[n]].array()).any() || (lows[members[n]].array() > highs[members[m]].array()).any()) continue;
                bool adjacent = false;
                for (int a : A)
                    for (int b : B) adjacent = adjacent || a == b;
                if (adjacent) continue;
                if (TrianglesIntersect({At(x, A[0]), At(x, A[1]), At(x, A[2])}, {At(x, B[0]), At(x, B[1]), At(x, B[2])})) return true;
            }
    return false;
}

}  // namespace sim
