// The shell models' elements: the incompressible hyperelastic membrane triangle (SHELL.md section 3)
// and the bending hinge (section 4).
//
// The membrane's energy per rest area is Psi(I1, I2) with, for an incompressible sheet,
//   I1 = tr C + 1/det C,  I2 = tr C / det C + det C,  C = F^T F.
// Writing I = tr C = |f1|^2 + |f2|^2 and D = det C = |f1 x f2|^2 (f1, f2 the columns of F), every
// derivative follows by the chain rule through (I, D), whose own derivatives are short:
//   dI = 2 F : dF,  d2I = 2 (identity),
//   dD = 2 n . dn with n = f1 x f2, dn = M df, M = [-[f2]x, [f1]x],
//   d2D = 2 M^T M + [[0, -2[n]x], [2[n]x, 0]].
#include <Eigen/Dense>
#include <cmath>

#include "sim/shell_problem.h"

namespace sim {
namespace {

Eigen::Matrix3d Cross(const Eigen::Vector3d& v) {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

// f(I1, I2) per rest area and its first and second partial derivatives.
struct LawDerivatives {
    double value = 0, d1 = 0, d2 = 0, d11 = 0, d12 = 0, d22 = 0;
};

LawDerivatives Law(const MembraneMaterial& m, double I1, double I2) {
    LawDerivatives f;
    const double h = m.thicknessMm;
    switch (m.law) {
        case MaterialLaw::NeoHookean:
            f.value = 0.5 * m.mu * h * (I1 - 3);
            f.d1 = 0.5 * m.mu * h;
            break;
        case MaterialLaw::MooneyRivlin:
            f.value = h * (m.c10 * (I1 - 3) + m.c01 * (I2 - 3));
            f.d1 = h * m.c10;
            f.d2 = h * m.c01;
            break;
        case MaterialLaw::Yeoh: {
            const double s = I1 - 3;
            f.value = h * (m.c10 * s + m.c20 * s * s + m.c30 * s * s * s);
            f.d1 = h * (m.c10 + 2 * m.c20 * s + 3 * m.c30 * s * s);
            f.d11 = h * (2 * m.c20 + 6 * m.c30 * s);
            break;
        }
    }
    return f;
}

}  // namespace

MembraneRest MakeMembraneRest(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2) {
    // A tangent frame of the rest triangle: t1 along the first edge, t2 in the plane.
    const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0;
    const Eigen::Vector3d normal = e1.cross(e2);
    MembraneRest rest;
    rest.area = 0.5 * normal.norm();
    if (!(rest.area > 0)) return rest;
    const Eigen::Vector3d t1 = e1.normalized(), t2 = normal.normalized().cross(t1);
    Eigen::Matrix2d dm;
    dm << t1.dot(e1), t1.dot(e2), t2.dot(e1), t2.dot(e2);
    const Eigen::Matrix2d inverse = dm.inverse();
    // F = (x1 - x0) r1^T + (x2 - x0) r2^T with r1, r2 the rows of Dm^-1.
    for (int k = 0; k < 2; ++k) {
        rest.g[1][k] = inverse(0, k);
        rest.g[2][k] = inverse(1, k);
        rest.g[0][k] = -inverse(0, k) - inverse(1, k);
    }
    return rest;
}

double MembraneDensity(const MembraneMaterial& material, const Matrix32& F, Vector6* gradient, Matrix6* hessian) {
    const Eigen::Vector3d f1 = F.col(0), f2 = F.col(1);
    const Eigen::Vector3d n = f1.cross(f2);
    const double I = f1.squaredNorm() + f2.squaredNorm();
    const double D = n.squaredNorm();
    const double I1 = I + 1 / D, I2 = I / D + D;
    const LawDerivatives f = Law(material, I1, I2);
    if (!gradient && !hessian) return f.value;

    // Partial derivatives of I1 and I2 with respect to I and D.
    const double i1I = 1, i1D = -1 / (D * D), i1DD = 2 / (D * D * D);
    const double i2I = 1 / D, i2D = 1 - I / (D * D), i2ID = -1 / (D * D), i2DD = 2 * I / (D * D * D);
    const double psiI = f.d1 * i1I + f.d2 * i2I;
    const double psiD = f.d1 * i1D + f.d2 * i2D;

    Vector6 gI, gD;
    gI << 2 * f1, 2 * f2;
    Eigen::Matrix<double, 3, 6> M;
    M << -Cross(f2), Cross(f1);
    gD = 2 * M.transpose() * n;
    if (gradient) *gradient = psiI * gI + psiD * gD;
    if (hessian) {
        const double psiII = f.d11 * i1I * i1I + 2 * f.d12 * i1I * i2I + f.d22 * i2I * i2I;
        const double psiID = f.d11 * i1I * i1D + f.d12 * (i1I * i2D + i2I * i1D) + f.d22 * i2I * i2D + f.d2 * i2ID;
        const double psiDD = f.d11 * i1D * i1D + 2 * f.d12 * i1D * i2D + f.d22 * i2D * i2D + f.d1 * i1DD + f.d2 * i2DD;
        Matrix6 d2D = 2 * M.transpose() * M;
        d2D.block<3, 3>(0, 3) -= 2 * Cross(n);
        d2D.block<3, 3>(3, 0) += 2 * Cross(n);
        *hessian = psiI * 2 * Matrix6::Identity() + psiD * d2D + psiII * gI * gI.transpose() + psiID * (gI * gD.transpose() + gD * gI.transpose()) +
                   psiDD * gD * gD.transpose();
    }
    return f.value;
}

PrincipalValues Principal(const MembraneMaterial& material, const Matrix32& F) {
    const Eigen::Matrix2d C = F.transpose() * F;
    const double trace = C.trace(), det = C.determinant();
    const double root = std::sqrt(std::max(0.0, 0.25 * trace * trace - det));
    const double c1 = 0.5 * trace + root, c2 = std::max(1e-300, 0.5 * trace - root);
    PrincipalValues p;
    p.stretch[0] = std::sqrt(c1);
    p.stretch[1] = std::sqrt(c2);
    // sigma_a = 2 (l_a^2 - l_3^2)(W1 + l_b^2 W2) per unit volume (plane stress, incompressible).
    const double l3sq = 1 / (c1 * c2);
    const double I1 = c1 + c2 + l3sq, I2 = 1 / c1 + 1 / c2 + c1 * c2;
    const LawDerivatives f = Law(material, I1, I2);
    const double w1 = f.d1 / material.thicknessMm, w2 = f.d2 / material.thicknessMm;
    p.stress[0] = 2 * (c1 - l3sq) * (w1 + c2 * w2);
    p.stress[1] = 2 * (c2 - l3sq) * (w1 + c1 * w2);
    return p;
}

namespace {
#include "hinge_angle.inc"
}  // namespace

double HingeAngle(const Eigen::Matrix<double, 12, 1>& x, Eigen::Matrix<double, 12, 1>* gradient, Eigen::Matrix<double, 12, 12>* hessian) {
    double theta = 0;
    Eigen::Matrix<double, 12, 1> g;
    if (hessian) {
        Eigen::Matrix<double, 12, 12, Eigen::RowMajor> h;
        HingeAngleHessian(x.data(), &theta, g.data(), h.data());
        *hessian = h;
    } else if (gradient) {
        HingeAngleGradient(x.data(), &theta, g.data());
    } else {
        // The angle alone: the same formula, without derivatives.
        const Eigen::Vector3d p0 = x.segment<3>(0), p1 = x.segment<3>(3), q = x.segment<3>(6), r = x.segment<3>(9);
        const Eigen::Vector3d e = p1 - p0, nA = e.cross(q - p0), nB = (r - p0).cross(e);
        return std::atan2(nA.cross(nB).dot(e) / e.norm(), nA.dot(nB));
    }
    if (gradient) *gradient = g;
    return theta;
}

}  // namespace sim
