// The shell models' elements: the incompressible hyperelastic membrane triangle (docs/models/shell.md section 3)
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

#include "shell/shell_problem.h"

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

// The hinge angle's Hessian in closed form (12 x 12, row-major). With e = p1 - p0, a = q - p0 and
// b = r - p0 the angle is atan2(Y, X), where nA x nB = Y e / |e| and nA . nB = X:
//     Y = |e| s,  s = (a x e) . b,      X = (e . a)(e . b) - (e . e)(a . b)   (Binet-Cauchy).
// Both are polynomials (and a norm) in (e, a, b), with simple gradients and Hessians; then
//     H = (X H_Y - Y H_X) / R - [(X^2 - Y^2)(g_X g_Y^T + g_Y g_X^T) + 2 X Y (g_Y g_Y^T - g_X g_X^T)] / R^2,
// R = X^2 + Y^2 (the derivative of (X g_Y - Y g_X) / R, its antisymmetric part dropped: it
// cancels). Over (p0, p1, q, r): d/dp1 = d/de, d/dq = d/da, d/dr = d/db, d/dp0 = -(all three).
void HingeAngleHessian(const double* x, double* hessian) {
    using Vector3 = Eigen::Vector3d;
    using Matrix3 = Eigen::Matrix3d;
    const Vector3 p0(x[0], x[1], x[2]);
    const Vector3 e = Vector3(x[3], x[4], x[5]) - p0, a = Vector3(x[6], x[7], x[8]) - p0, b = Vector3(x[9], x[10], x[11]) - p0;
    const double ea = e.dot(a), eb = e.dot(b), ee = e.dot(e), ab = a.dot(b), length = std::sqrt(ee);
    const Vector3 axe = a.cross(e), unit = e / length;
    const double s = axe.dot(b);
    const double X = ea * eb - ee * ab, Y = length * s, R = X * X + Y * Y;
    // ds over e, a and b; g_X and g_Y over (e, a, b).
    const Vector3 dsE = b.cross(a), dsA = e.cross(b), dsB = axe;
    Eigen::Matrix<double, 9, 1> gX, gY;
    gX << eb * a + ea * b - 2 * ab * e, eb * e - ee * b, ea * e - ee * a;
    gY << s * unit + length * dsE, length * dsA, length * dsB;
    const double c1 = (X * X - Y * Y) / (R * R), c2 = 2 * X * Y / (R * R), cY = X / R, cX = Y / R;
    Eigen::Matrix<double, 9, 9> H = -c1 * (gX * gY.transpose() + gY * gX.transpose()) - c2 * (gY * gY.transpose() - gX * gX.transpose());
    // (X H_Y - Y H_X) / R, block by block (H_X and H_Y vanish on (a, a) and (b, b)):
    //   H_Y = s H_|e| + g_|e| ds^T + ds g_|e|^T + |e| H_s, with H_|e| = (I - u u^T) / |e| on (e, e);
    //   H_s: (e, a) = [b]x, (e, b) = -[a]x, (a, b) = [e]x;
    //   H_X: (e, e) = a b^T + b a^T - 2 (a . b) I, (e, a) = (e . b) I + b e^T - 2 e b^T,
    //        (e, b) = (e . a) I + a e^T - 2 e a^T, (a, b) = e e^T - (e . e) I.
    const Matrix3 I = Matrix3::Identity();
    H.block<3, 3>(0, 0) += cY * (s * (I - unit * unit.transpose()) / length + unit * dsE.transpose() + dsE * unit.transpose()) -
                           cX * (a * b.transpose() + b * a.transpose() - 2 * ab * I);
    const Matrix3 blockEA = cY * (unit * dsA.transpose() + length * Cross(b)) - cX * (eb * I + b * e.transpose() - 2 * e * b.transpose());
    const Matrix3 blockEB = cY * (unit * dsB.transpose() - length * Cross(a)) - cX * (ea * I + a * e.transpose() - 2 * e * a.transpose());
    const Matrix3 blockAB = cY * length * Cross(e) - cX * (e * e.transpose() - ee * I);
    H.block<3, 3>(0, 3) += blockEA;
    H.block<3, 3>(3, 0) += blockEA.transpose();
    H.block<3, 3>(0, 6) += blockEB;
    H.block<3, 3>(6, 0) += blockEB.transpose();
    H.block<3, 3>(3, 6) += blockAB;
    H.block<3, 3>(6, 3) += blockAB.transpose();
    Eigen::Map<Eigen::Matrix<double, 12, 12, Eigen::RowMajor>> h(hessian);
    h.bottomRightCorner<9, 9>() = H;
    for (int v = 0; v < 3; ++v) {
        const Matrix3 column = -(H.block<3, 3>(0, 3 * v) + H.block<3, 3>(3, 3 * v) + H.block<3, 3>(6, 3 * v));
        h.block<3, 3>(0, 3 + 3 * v) = column;
        h.block<3, 3>(3 + 3 * v, 0) = column.transpose();
    }
    h.block<3, 3>(0, 0) = -(h.block<3, 3>(0, 3) + h.block<3, 3>(0, 6) + h.block<3, 3>(0, 9));
}

}  // namespace

double HingeAngle(const Eigen::Matrix<double, 12, 1>& x, Eigen::Matrix<double, 12, 1>* gradient, Eigen::Matrix<double, 12, 12>* hessian) {
    if (!gradient && !hessian) {
        // The angle alone: the same formula, without derivatives.
        const Eigen::Vector3d p0 = x.segment<3>(0), p1 = x.segment<3>(3), q = x.segment<3>(6), r = x.segment<3>(9);
        const Eigen::Vector3d e = p1 - p0, nA = e.cross(q - p0), nB = (r - p0).cross(e);
        return std::atan2(nA.cross(nB).dot(e) / e.norm(), nA.dot(nB));
    }
    double theta = 0;
    Eigen::Matrix<double, 12, 1> g;
    HingeAngleGradient(x.data(), &theta, g.data());
    if (gradient) *gradient = g;
    if (hessian) {
        Eigen::Matrix<double, 12, 12, Eigen::RowMajor> h;
        HingeAngleHessian(x.data(), h.data());
        *hessian = h;
    }
    return theta;
}

}  // namespace sim
