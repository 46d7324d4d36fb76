// The distance between a pair's primitives (docs/models/shell.md section 8): which features are
// closest (Ericson's regions for a point and a triangle, clamped parameters for two segments), then
// the squared distance by that case's formula, differentiated exactly through SecondOrder.
#include <algorithm>
#include <cmath>

#include "contact/contact.h"
#include "contact/second_order.h"

namespace sim {
namespace {

template <typename T>
struct Point3 {
    T x, y, z;
};
template <typename T>
Point3<T> operator-(const Point3<T>& a, const Point3<T>& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename T>
T Dot(const Point3<T>& a, const Point3<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
Point3<T> Cross(const Point3<T>& a, const Point3<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// The cases' squared distances over their own points (p[0], p[1], ...).
template <typename T>
T PointPointSquared(const Point3<T>* p) {
    const Point3<T> d = p[0] - p[1];
    return Dot(d, d);
}
// Point p[0] and the line through p[1], p[2]: |(a - p) x (b - p)|^2 / |b - a|^2.
template <typename T>
T PointLineSquared(const Point3<T>* p) {
    const Point3<T> n = Cross(p[1] - p[0], p[2] - p[0]);
    const Point3<T> e = p[2] - p[1];
    return Dot(n, n) / Dot(e, e);
}
// ((u . n)^2 / |n|^2): point p[0] and the plane of p[1..3] (u = p - a, n = (b - a) x (c - a)), or
// the lines p[0] p[1] and p[2] p[3] (u = b0 - a0, n = (a1 - a0) x (b1 - b0)).
template <typename T>
T ProjectedSquared(const Point3<T>& u, const Point3<T>& n) {
    const T un = Dot(u, n);
    return un * un / Dot(n, n);
}
template <typename T>
T PointPlaneSquared(const Point3<T>* p) {
    return ProjectedSquared(p[0] - p[1], Cross(p[2] - p[1], p[3] - p[1]));
}
template <typename T>
T LineLineSquared(const Point3<T>* p) {
    return ProjectedSquared(p[2] - p[0], Cross(p[1] - p[0], p[3] - p[2]));
}

// The case's formula over its points: P of them (2, 3 or 4), in the order of ClosestFeatures::local.
template <int P, typename T>
T CaseSquared(DistanceCase kind, const Point3<T>* p) {
    if constexpr (P == 2) return PointPointSquared(p);
    else if constexpr (P == 3) return PointLineSquared(p);
    else return kind == DistanceCase::PointPlane ? PointPlaneSquared(p) : LineLineSquared(p);
}

int PointCount(DistanceCase kind) {
    switch (kind) {
        case DistanceCase::PointPoint: return 2;
        case DistanceCase::PointEdge: return 3;
        default: return 4;
    }
}

Eigen::Vector3d At(const Vector12& x, int vertex) { return x.segment<3>(3 * vertex); }

// The case's formula over its P points as SecondOrder numbers, scattered back to the pair's 12
// coordinates. A distance does not change when every point moves alike, so the inputs are the
// other points' offsets from the first, d_k = p_k - p_0 (3 (P - 1) of them, not 3 P: a Hessian of
// 9 x 9 numbers carried through the formula, not 12 x 12), and the points' own derivatives follow
// from dd_k/dp_k = I, dd_k/dp_0 = -I.
template <int P>
double DifferentiatedSquared(const ClosestFeatures& features, const Vector12& x, Vector12* gradient, Matrix12* hessian) {
    using Number = SecondOrder<3 * (P - 1)>;
    Point3<Number> p[P];
    const int first = features.local[0];
    p[0] = {Number(0), Number(0), Number(0)};
    for (int k = 1; k < P; ++k) {
        const int v = features.local[k];
        const auto input = [&](int c) { return Number::Input(x[3 * v + c] - x[3 * first + c], 3 * (k - 1) + c); };
        p[k] = {input(0), input(1), input(2)};
    }
    const Number d = CaseSquared<P>(features.kind, p);
    if (gradient) {
        gradient->setZero();
        for (int k = 1; k < P; ++k) {
            const Eigen::Vector3d g = d.gradient.template segment<3>(3 * (k - 1));
            gradient->segment<3>(3 * features.local[k]) = g;
            gradient->segment<3>(3 * first) -= g;
        }
    }
    if (hessian) {
        hessian->setZero();
        for (int k = 1; k < P; ++k)
            for (int l = 1; l < P; ++l) {
                const Eigen::Matrix3d block = d.hessian.template block<3, 3>(3 * (k - 1), 3 * (l - 1));
                hessian->block<3, 3>(3 * features.local[k], 3 * features.local[l]) = block;
                hessian->block<3, 3>(3 * first, 3 * features.local[l]) -= block;
                hessian->block<3, 3>(3 * features.local[k], 3 * first) -= block;
                hessian->block<3, 3>(3 * first, 3 * first) += block;
            }
    }
    return d.value;
}

ClosestFeatures PointTriangleFeatures(const Vector12& x) {
    // Ericson, Real-Time Collision Detection, 5.1.5: the Voronoi regions of a triangle's features.
    const Eigen::Vector3d p = At(x, 0), a = At(x, 1), b = At(x, 2), c = At(x, 3);
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return {DistanceCase::PointPoint, {0, 1}};
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return {DistanceCase::PointPoint, {0, 2}};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return {DistanceCase::PointEdge, {0, 1, 2}};
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return {DistanceCase::PointPoint, {0, 3}};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return {DistanceCase::PointEdge, {0, 1, 3}};
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return {DistanceCase::PointEdge, {0, 2, 3}};
    return {DistanceCase::PointPlane, {0, 1, 2, 3}};
}

ClosestFeatures EdgeEdgeFeatures(const Vector12& x) {
    // Ericson 5.1.9: the closest points' parameters s on a0 a1 and t on b0 b1, clamped to [0, 1].
    const Eigen::Vector3d a0 = At(x, 0), b0 = At(x, 2);
    const Eigen::Vector3d da = At(x, 1) - a0, db = At(x, 3) - b0, r = a0 - b0;
    const double aa = da.squaredNorm(), bb = db.squaredNorm(), ab = da.dot(db);
    const double ar = da.dot(r), br = db.dot(r);
    double s = 0, t = 0;
    const double denominator = aa * bb - ab * ab;  // |da x db|^2: 0 for parallel edges
    if (denominator > 1e-14 * aa * bb) s = std::clamp((ab * br - ar * bb) / denominator, 0.0, 1.0);
    t = (ab * s + br) / bb;
    if (t < 0) {
        t = 0;
        s = std::clamp(-ar / aa, 0.0, 1.0);
    } else if (t > 1) {
        t = 1;
        s = std::clamp((ab - ar) / aa, 0.0, 1.0);
    }
    const bool sInside = s > 0 && s < 1, tInside = t > 0 && t < 1;
    const int aEnd = s >= 1 ? 1 : 0, bEnd = t >= 1 ? 3 : 2;
    if (sInside && tInside) return {DistanceCase::LineLine, {0, 1, 2, 3}};
    if (sInside) return {DistanceCase::PointEdge, {bEnd, 0, 1}};
    if (tInside) return {DistanceCase::PointEdge, {aEnd, 2, 3}};
    return {DistanceCase::PointPoint, {aEnd, bEnd}};
}

}  // namespace

ClosestFeatures ClosestFeaturesOf(PairKind kind, const Vector12& x) {
    return kind == PairKind::PointTriangle ? PointTriangleFeatures(x) : EdgeEdgeFeatures(x);
}

double SquaredDistance(PairKind kind, const Vector12& x, Vector12* gradient, Matrix12* hessian) {
    const ClosestFeatures features = ClosestFeaturesOf(kind, x);
    if (gradient || hessian) {
        switch (PointCount(features.kind)) {
            case 2: return DifferentiatedSquared<2>(features, x, gradient, hessian);
            case 3: return DifferentiatedSquared<3>(features, x, gradient, hessian);
            default: return DifferentiatedSquared<4>(features, x, gradient, hessian);
        }
    }
    // The same offsets from the first point as the differentiated path: the same bits.
    Point3<double> p[4];
    const int first = features.local[0];
    for (int k = 0; k < PointCount(features.kind); ++k) {
        const int v = features.local[k];
        p[k] = {x[3 * v] - x[3 * first], x[3 * v + 1] - x[3 * first + 1], x[3 * v + 2] - x[3 * first + 2]};
    }
    switch (PointCount(features.kind)) {
        case 2: return CaseSquared<2>(features.kind, p);
        case 3: return CaseSquared<3>(features.kind, p);
        default: return CaseSquared<4>(features.kind, p);
    }
}

Vector12 PairCoordinates(const ContactPair& pair, const Positions& x) {
    Vector12 c;
    for (int k = 0; k < 4; ++k) {
        const int v = pair.vertices[k];
        c.segment<3>(3 * k) = Eigen::Vector3d(x.x[v], x.y[v], x.z[v]);
    }
    return c;
}

}  // namespace sim
