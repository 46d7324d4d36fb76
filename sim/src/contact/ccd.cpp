// Continuous collision detection (docs/models/shell.md section 8): additive CCD (Li, Kaufman and
// Jiang 2021, "Codimensional Incremental Potential Contact", section 5). A pair's gap can shrink no
// faster than the sum of its two primitives' largest relative speeds, so it advances in steps that
// cannot close the gap, measuring the true distance after each, until it gets near.
#include <algorithm>
#include <cmath>

#include "contact/contact.h"

namespace sim {
namespace {

// The gap beyond minDistance, d - m, written (d^2 - m^2) / (d + m) as the paper does: exact for
// small gaps where the squared distance is what is known to full precision.
double GapOf(double squared, double minDistance) {
    return (squared - minDistance * minDistance) / (std::sqrt(squared) + minDistance);
}

// Steps are capped: a pair sliding along another at a tiny gap advances by tiny steps; past the cap
// the time reached so far is returned, which is safe.
constexpr int kMaxAdvances = 100000;
// The fraction of its gap a pair keeps: the step is cut at the time the gap would fall below it.
constexpr double kKeptGap = 0.1;

}  // namespace

double PairImpactTime(PairKind kind, const Vector12& x, const Vector12& dx, double minDistanceMm, double tMax) {
    // Only relative motion matters: subtract the mean, then bound each primitive's speed.
    Vector12 p = dx;
    const Eigen::Vector3d mean = (p.segment<3>(0) + p.segment<3>(3) + p.segment<3>(6) + p.segment<3>(9)) / 4;
    for (int k = 0; k < 4; ++k) p.segment<3>(3 * k) -= mean;
    const double n0 = p.segment<3>(0).norm(), n1 = p.segment<3>(3).norm(), n2 = p.segment<3>(6).norm(), n3 = p.segment<3>(9).norm();
    const double speed = kind == PairKind::PointTriangle ? n0 + std::max({n1, n2, n3}) : std::max(n0, n1) + std::max(n2, n3);
    if (speed == 0) return tMax;

    Vector12 y = x;
    double gap = GapOf(SquaredDistance(kind, y, nullptr, nullptr), minDistanceMm);
    if (!(gap > 0)) return 0;
    const double keep = kKeptGap * gap;
    double t = 0;
    double advance = (1 - kKeptGap) * gap / speed;
    for (int n = 0; n < kMaxAdvances; ++n) {
        y += advance * p;
        gap = GapOf(SquaredDistance(kind, y, nullptr, nullptr), minDistanceMm);
        if (t > 0 && gap < keep) return t;
        t += advance;
        if (t >= tMax) return tMax;
        advance = (1 - kKeptGap) * gap / speed;
    }
    return t;
}

double ImpactFreeStep(const ContactSurface& surface, const Positions& x, const Positions& dx, double minDistanceMm,
                      ContactSweep* sweep, double sweepReachMm, double toleranceMm) {
    std::vector<ContactPair> pairs = ContactCandidates(surface, x, &dx, sweep ? std::max(sweepReachMm, minDistanceMm) : minDistanceMm);
    double t = 1;
    for (const ContactPair& pair : pairs)
        t = std::min(t, PairImpactTime(pair.kind, PairCoordinates(pair, x), PairCoordinates(pair, dx), minDistanceMm, t));
    if (sweep) {
        sweep->pairs = std::move(pairs);
        sweep->from = x;
        sweep->move = dx;
        sweep->toleranceMm = toleranceMm;
        double longest = -1;
        for (int v = 0; v < dx.Size(); ++v)
            if (const double l = dx.x[v] * dx.x[v] + dx.y[v] * dx.y[v] + dx.z[v] * dx.z[v]; l > longest) {
                longest = l;
                sweep->fastest = v;
            }
    }
    return t;
}

bool ContactSweep::Covers(const Positions& x) const {
    const int n = x.Size();
    if (from.Size() != n || n == 0) return false;
    // How far along the move x is, from the vertex that moves most; then every vertex's distance
    // from its place at that fraction.
    const int most = fastest;
    const double longest = move.x[most] * move.x[most] + move.y[most] * move.y[most] + move.z[most] * move.z[most];
    double along = 0;
    if (longest > 0)
        along = std::clamp(((x.x[most] - from.x[most]) * move.x[most] + (x.y[most] - from.y[most]) * move.y[most] +
                            (x.z[most] - from.z[most]) * move.z[most]) / longest,
                           0.0, 1.0);
    const double limit = toleranceMm * toleranceMm;
    for (int v = 0; v < n; ++v) {
        const double dx = x.x[v] - from.x[v] - along * move.x[v], dy = x.y[v] - from.y[v] - along * move.y[v],
                     dz = x.z[v] - from.z[v] - along * move.z[v];
        if (!(dx * dx + dy * dy + dz * dz <= limit)) return false;
    }
    return true;
}

}  // namespace sim
