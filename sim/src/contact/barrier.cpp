// One pair's barrier energy (docs/models/shell.md section 8): kappa m b(d - h), with the chain rule
// from the squared distance's derivatives to the energy's, and the projection Newton needs.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <type_traits>

#include "contact/contact.h"
#include "contact/second_order.h"

namespace sim {

double Barrier(double s, double sHat, double* first, double* second) {
    if (first) *first = 0;
    if (second) *second = 0;
    if (s >= sHat) return 0;
    if (s <= 0) return std::numeric_limits<double>::infinity();
    const double t = s - sHat, log = std::log(s / sHat);
    if (first) *first = -2 * t * log - t * t / s;
    if (second) *second = -2 * log - 4 * t / s + t * t / (s * s);
    return -t * t * log;
}

double EdgeEdgeMollifierThreshold(const Vector12& rest) {
    return 1e-3 * (rest.segment<3>(3) - rest.segment<3>(0)).squaredNorm() * (rest.segment<3>(9) - rest.segment<3>(6)).squaredNorm();
}

double EdgeEdgeMollifier(double crossSquared, double threshold) {
    if (!(crossSquared < threshold)) return 1;
    const double r = crossSquared / threshold;
    return (2 - r) * r;
}

namespace {

// c = |e_a x e_b|^2 over the edge-edge pair's 12 coordinates, as a plain number or (Number =
// SecondOrder<12>) with its derivatives: one formula, so both give the same bits for c.
template <typename Number>
Number CrossSquared(const Vector12& x) {
    const auto input = [&](int index) {
        if constexpr (std::is_same_v<Number, double>) return x[index];
        else return Number::Input(x[index], index);
    };
    Number e[2][3];
    for (int k = 0; k < 3; ++k) {
        e[0][k] = input(3 + k) - input(k);
        e[1][k] = input(9 + k) - input(6 + k);
    }
    const Number cx = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    const Number cy = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    const Number cz = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    return cx * cx + cy * cy + cz * cz;
}

}  // namespace

double PairBarrierEnergy(PairKind kind, const Vector12& x, double mollifierThreshold, const BarrierDef& barrier,
                         Vector12* gradient, Matrix12* hessian, bool project) {
    const bool derivatives = gradient || hessian;
    Vector12 g2;
    Matrix12 h2;
    const double d2 = SquaredDistance(kind, x, derivatives ? &g2 : nullptr, hessian ? &h2 : nullptr);
    const double d = std::sqrt(d2);
    double b1 = 0, b2 = 0;
    const double b = barrier.stiffness * Barrier(d - barrier.thicknessMm, barrier.activationMm, &b1, &b2);
    b1 *= barrier.stiffness;
    b2 *= barrier.stiffness;
    if (gradient) gradient->setZero();
    if (hessian) hessian->setZero();
    if (b == 0 || !std::isfinite(b)) return b;

    // d = sqrt(d2): grad d = grad d2 / (2d), hess d = hess d2 / (2d) - grad d2 grad d2^T / (4 d^3).
    Vector12 gb = Vector12::Zero();
    Matrix12 hb = Matrix12::Zero();
    if (derivatives) {
        const Vector12 gd = g2 / (2 * d);
        gb = b1 * gd;
        if (hessian) hb = b2 * gd * gd.transpose() + b1 * (h2 / (2 * d) - g2 * g2.transpose() / (4 * d * d * d));
    }
    double energy = b;
    // The mollifier acts on nearly parallel edges only. Most pairs are not, and the cross
    // product's derivatives (a 12 x 12 Hessian carried through the formula) are taken only where it
    // acts: taken for every edge-edge pair, they were a quarter of a collapsed tube's time.
    if (kind == PairKind::EdgeEdge) {
        const double cross = CrossSquared<double>(x);
        if (cross < mollifierThreshold) {
            const double r = cross / mollifierThreshold;
            const double m = EdgeEdgeMollifier(cross, mollifierThreshold);
            energy = m * b;
            if (derivatives) {
                const SecondOrder<12> c = CrossSquared<SecondOrder<12>>(x);
                const double m1 = (2 - 2 * r) / mollifierThreshold;  // dm/dc
                const double m2 = -2 / (mollifierThreshold * mollifierThreshold);
                const Vector12 gm = m1 * c.gradient;
                if (hessian) {
                    const Matrix12 hm = m1 * c.hessian + m2 * c.gradient * c.gradient.transpose();
                    hb = m * hb + b * hm + gm * gb.transpose() + gb * gm.transpose();
                }
                gb = m * gb + b * gm;
            }
        }
    }
    if (gradient) *gradient = gb;
    if (hessian) {
        if (project) {
            Eigen::SelfAdjointEigenSolver<Matrix12> eigen(hb);
            const Eigen::Matrix<double, 12, 1> values = eigen.eigenvalues().cwiseMax(0.0);
            hb = eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
        }
        *hessian = hb;
    }
    return energy;
}

ContactSummary SummariseContact(const ContactSurface& surface, const BarrierDef& barrier, const Positions& x) {
    ContactSummary summary;
    summary.minGapMm = std::numeric_limits<double>::infinity();
    const double reach = ContactReachMm(barrier);
    for (const ContactPair& pair : ContactCandidates(surface, x, nullptr, 2 * reach)) {
        const Vector12 c = PairCoordinates(pair, x);
        const double d = std::sqrt(SquaredDistance(pair.kind, c, nullptr, nullptr));
        summary.minGapMm = std::min(summary.minGapMm, d - barrier.thicknessMm);
        if (d >= reach) continue;
        ++summary.activePairs;
        double first = 0;
        Barrier(d - barrier.thicknessMm, barrier.activationMm, &first, nullptr);
        const double m = pair.kind == PairKind::EdgeEdge
                             ? EdgeEdgeMollifier((c.segment<3>(3) - c.segment<3>(0)).cross(c.segment<3>(9) - c.segment<3>(6)).squaredNorm(),
                                                 EdgeEdgeMollifierThreshold(PairCoordinates(pair, surface.rest)))
                             : 1.0;
        summary.forceN += barrier.stiffness * m * std::abs(first);
    }
    return summary;
}

}  // namespace sim
