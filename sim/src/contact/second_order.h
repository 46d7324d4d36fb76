// A number that carries its gradient and Hessian with respect to N inputs (forward mode, second
// order). The contact distances are short rational expressions of four points; written once over
// this type, their exact gradients and Hessians come with them, checked against central differences
// by the verification tests. Fixed sizes: nothing is allocated.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>

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
    // For results every entry of which is written next: no zeros written first.
    struct Uninitialised {};
    explicit SecondOrder(Uninitialised) : gradient(), hessian() {}
    // Input number `index` with value v: its gradient is the index-th unit vector.
    static SecondOrder Input(double v, int index) {
        SecondOrder x(v);
        x.gradient[index] = 1;
        return x;
    }
};

// The operators below are written out entry by entry: Eigen's expressions made temporaries (the
// outer products) and the results' zeros, which were most of a contact pair's cost. Each entry is
// summed in the order of the formulas in the comments, so the bits are those of those formulas.

// a + b and a - b: the operation on the values and on each entry of the derivatives.
template <int N, typename Operation>
SecondOrder<N> EntryWise(const SecondOrder<N>& a, const SecondOrder<N>& b, Operation operation) {
    SecondOrder<N> r{typename SecondOrder<N>::Uninitialised{}};
    r.value = operation(a.value, b.value);
    for (int i = 0; i < N; ++i) r.gradient[i] = operation(a.gradient[i], b.gradient[i]);
    for (int k = 0; k < N * N; ++k) r.hessian.data()[k] = operation(a.hessian.data()[k], b.hessian.data()[k]);
    return r;
}
template <int N>
SecondOrder<N> operator+(const SecondOrder<N>& a, const SecondOrder<N>& b) {
    return EntryWise(a, b, std::plus<>());
}
template <int N>
SecondOrder<N> operator-(const SecondOrder<N>& a, const SecondOrder<N>& b) {
    return EntryWise(a, b, std::minus<>());
}

// (ab)'' = a'' b + a b'' + a' b'^T + b' a'^T
template <int N>
SecondOrder<N> operator*(const SecondOrder<N>& a, const SecondOrder<N>& b) {
    SecondOrder<N> r{typename SecondOrder<N>::Uninitialised{}};
    r.value = a.value * b.value;
    for (int i = 0; i < N; ++i) r.gradient[i] = b.value * a.gradient[i] + a.value * b.gradient[i];
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i)
            r.hessian(i, j) = ((b.value * a.hessian(i, j) + a.value * b.hessian(i, j)) + a.gradient[i] * b.gradient[j]) + a.gradient[j] * b.gradient[i];
    return r;
}

// a / b = a * (1 / b), with (1/b)' = -b'/b^2 and (1/b)'' = -b''/b^2 + (2 b'/b^3) b'^T.
template <int N>
SecondOrder<N> operator/(const SecondOrder<N>& a, const SecondOrder<N>& b) {
    SecondOrder<N> inverse{typename SecondOrder<N>::Uninitialised{}};
    const double v = 1 / b.value, first = -v * v, second = 2 * v * v * v;
    inverse.value = v;
    for (int i = 0; i < N; ++i) inverse.gradient[i] = first * b.gradient[i];
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) inverse.hessian(i, j) = first * b.hessian(i, j) + (second * b.gradient[i]) * b.gradient[j];
    SecondOrder<N> r = a * inverse;
    r.value = a.value / b.value;  // the same bits as the plain division the energy-only path does
    return r;
}

}  // namespace sim
