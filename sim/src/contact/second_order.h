// A number that carries its gradient and Hessian with respect to N inputs (forward mode, second
// order). The contact distances are short rational expressions of four points; written once over
// this type, their exact gradients and Hessians come with them, checked against central differences
// by the verification tests. Fixed sizes: nothing is allocated.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace sim {

template <int N>
struct SecondOrder {
    using Gradient = Eigen::Matrix<double, N, 1>;
    using Hessian = Eigen::Matrix<double, N, N>;
    double value = 0;
    Gradient gradient = Gradient::Zero();
    Hessian hessian = Hessian::Zero();

    SecondOrder() = default;
    SecondOrder(double v) : value(v) {}  // a constant (implicit: constants mix with variables)
    // Input number `index` with value v: its gradient is the index-th unit vector.
    static SecondOrder Input(double v, int index) {
        SecondOrder x(v);
        x.gradient[index] = 1;
        return x;
    }
};

template <int N>
SecondOrder<N> operator+(const SecondOrder<N>& a, const SecondOrder<N>& b) {
    SecondOrder<N> r;
    r.value = a.value + b.value;
    r.gradient = a.gradient + b.gradient;
    r.hessian = a.hessian + b.hessian;
    return r;
}

template <int N>
SecondOrder<N> operator-(const SecondOrder<N>& a, const SecondOrder<N>& b) {
    SecondOrder<N> r;
    r.value = a.value - b.value;
    r.gradient = a.gradient - b.gradient;
    r.hessian = a.hessian - b.hessian;
    return r;
}

// (ab)'' = a'' b + a b'' + a' b'^T + b' a'^T
template <int N>
SecondOrder<N> operator*(const SecondOrder<N>& a, const SecondOrder<N>& b) {
    SecondOrder<N> r;
    r.value = a.value * b.value;
    r.gradient = b.value * a.gradient + a.value * b.gradient;
    const auto cross = a.gradient * b.gradient.transpose();
    r.hessian = b.value * a.hessian + a.value * b.hessian + cross + cross.transpose();
    return r;
}

// a / b = a * (1 / b), with (1/b)' = -b'/b^2 and (1/b)'' = -b''/b^2 + 2 b' b'^T / b^3.
template <int N>
SecondOrder<N> operator/(const SecondOrder<N>& a, const SecondOrder<N>& b) {
    SecondOrder<N> inverse;
    const double v = 1 / b.value;
    inverse.value = v;
    inverse.gradient = -v * v * b.gradient;
    inverse.hessian = -v * v * b.hessian + (2 * v * v * v) * (b.gradient * b.gradient.transpose());
    SecondOrder<N> r = a * inverse;
    r.value = a.value / b.value;  // the same bits as the plain division the energy-only path does
    return r;
}

}  // namespace sim
