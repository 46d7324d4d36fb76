// Self-contact's pieces against independent answers (docs/models/shell.md section 8): distances
// against brute-force sampling, every derivative against central differences, the spatial hash
// against all pairs, continuous collision detection against dense sampling of thousands of random
// moves, and two pressed plates whose barrier force balances the load.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <Eigen/Geometry>
#include <limits>
#include <random>

#include "contact/contact.h"

namespace sim {
namespace {

Vector12 RandomPair(std::mt19937& rng, double spread) {
    std::uniform_real_distribution<double> u(-spread, spread);
    Vector12 x;
    for (int k = 0; k < 12; ++k) x[k] = u(rng);
    return x;
}

// The distance by sampling both primitives on a fine grid (an upper bound that tends to the truth).
double SampledDistance(PairKind kind, const Vector12& x, int n) {
    const auto point = [&](int v) { return Eigen::Vector3d(x.segment<3>(3 * v)); };
    double best = INFINITY;
    if (kind == PairKind::PointTriangle) {
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                const double a = double(i) / n, b = double(j) / n;
                const Eigen::Vector3d q = point(1) + a * (point(2) - point(1)) + b * (point(3) - point(1));
                best = std::min(best, (point(0) - q).norm());
            }
    } else {
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                const Eigen::Vector3d p = point(0) + (double(i) / n) * (point(1) - point(0));
                const Eigen::Vector3d q = point(2) + (double(j) / n) * (point(3) - point(2));
                best = std::min(best, (p - q).norm());
            }
    }
    return best;
}

TEST(ContactDistance, MatchesSamplingInEveryCase) {
    std::mt19937 rng(7);
    int seen[2][4] = {};
    for (int trial = 0; trial < 2000; ++trial) {
        const PairKind kind = trial % 2 ? PairKind::EdgeEdge : PairKind::PointTriangle;
        const Vector12 x = RandomPair(rng, 1.0);
        const double d = std::sqrt(SquaredDistance(kind, x, nullptr, nullptr));
        const double sampled = SampledDistance(kind, x, 200);
        // Sampling finds a point at most one grid step (0.005 of an edge of length < 3.5) from the
        // closest one, so it is above the truth by less than 0.02.
        EXPECT_LE(d, sampled + 1e-12) << trial;
        EXPECT_GT(d, sampled - 0.02) << trial;
        ++seen[int(kind)][int(ClosestFeaturesOf(kind, x).kind)];
    }
    // Random pairs reach every case the two kinds have.
    for (int c : {0, 1, 2}) EXPECT_GT(seen[0][c], 20) << "point-triangle case " << c;
    for (int c : {0, 1, 3}) EXPECT_GT(seen[1][c], 20) << "edge-edge case " << c;
}

// Central differences of f's gradient g (12) and, through g, of its Hessian.
template <typename F>
void ExpectDerivatives(const F& f, const Vector12& x, double h, double gradientTolerance, double hessianTolerance,
                       const char* what) {
    Vector12 g;
    Matrix12 H;
    f(x, &g, &H);
    const double scale = std::max(1.0, g.cwiseAbs().maxCoeff());
    const double hScale = std::max(1.0, H.cwiseAbs().maxCoeff());
    for (int k = 0; k < 12; ++k) {
        Vector12 plus = x, minus = x;
        plus[k] += h;
        minus[k] -= h;
        Vector12 gp, gm;
        const double fd = (f(plus, &gp, nullptr) - f(minus, &gm, nullptr)) / (2 * h);
        EXPECT_NEAR(fd, g[k], gradientTolerance * scale) << what << " gradient " << k;
        const Vector12 column = (gp - gm) / (2 * h);
        for (int r = 0; r < 12; ++r) EXPECT_NEAR(column[r], H(r, k), hessianTolerance * hScale) << what << " Hessian " << r << "," << k;
    }
    EXPECT_LT((H - H.transpose()).cwiseAbs().maxCoeff(), 1e-12 * hScale) << what;
}

TEST(ContactDistance, DerivativesMatchCentralDifferences) {
    std::mt19937 rng(11);
    int checked = 0;
    for (int trial = 0; trial < 400 && checked < 120; ++trial) {
        const PairKind kind = trial % 2 ? PairKind::EdgeEdge : PairKind::PointTriangle;
        const Vector12 x = RandomPair(rng, 1.0);
        // Away from case boundaries, where the Hessian jumps: the same case a step away every way.
        const DistanceCase c = ClosestFeaturesOf(kind, x).kind;
        bool stable = true;
        for (int k = 0; k < 12 && stable; ++k)
            for (double s : {-1e-4, 1e-4}) {
                Vector12 y = x;
                y[k] += s;
                stable = stable && ClosestFeaturesOf(kind, y).kind == c;
            }
        if (!stable) continue;
        ++checked;
        ExpectDerivatives([&](const Vector12& y, Vector12* g, Matrix12* H) { return SquaredDistance(kind, y, g, H); }, x, 1e-6,
                          1e-8, 1e-6, "squared distance");
    }
    EXPECT_GE(checked, 120);
}

TEST(ContactBarrier, FunctionIsSmoothAtTheActivationDistance) {
    const double sHat = 0.2;
    double b1 = 0, b2 = 0;
    EXPECT_EQ(Barrier(sHat, sHat, &b1, &b2), 0);
    EXPECT_EQ(b1, 0);
    EXPECT_EQ(b2, 0);
    EXPECT_TRUE(std::isinf(Barrier(0, sHat, nullptr, nullptr)));
    for (double s : {1e-4, 0.01, 0.05, 0.1, 0.19}) {
        const double h = 1e-7 * s;
        double d1 = 0, d2 = 0, p1 = 0, m1 = 0;
        Barrier(s, sHat, &d1, &d2);
        const double fd1 = (Barrier(s + h, sHat, &p1, nullptr) - Barrier(s - h, sHat, &m1, nullptr)) / (2 * h);
        EXPECT_NEAR(fd1, d1, 1e-6 * std::max(1.0, std::abs(d1))) << s;
        EXPECT_NEAR((p1 - m1) / (2 * h), d2, 1e-5 * std::max(1.0, std::abs(d2))) << s;
        EXPECT_GT(Barrier(s, sHat, nullptr, nullptr), 0);
        EXPECT_LT(d1, 0);  // pushes the walls apart
    }
}

// A random rigid placement of a pair's 12 coordinates.
Vector12 Placed(const Vector12& x, std::mt19937& rng) {
    const Eigen::Matrix3d rotation = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    (void)rng;
    std::uniform_real_distribution<double> u(-1, 1);
    const Eigen::Vector3d shift(u(rng), u(rng), u(rng));
    Vector12 y;
    for (int k = 0; k < 4; ++k) y.segment<3>(3 * k) = rotation * x.segment<3>(3 * k) + shift;
    return y;
}

// A pair whose distance lies inside the barrier's reach, h + (0.1 to 0.9) s_hat. Near parallel:
// two edges at a small angle, crossing (their lines closest inside both) or overlapping by half
// (an end of one closest to the inside of the other).
Vector12 PairInReach(std::mt19937& rng, PairKind kind, const BarrierDef& def, bool nearParallel) {
    std::uniform_real_distribution<double> u(0.1, 0.9), tilt(0.002, 0.01);
    const double target = def.thicknessMm + u(rng) * def.activationMm;
    const bool crossing = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
    const double t = tilt(rng);
    Vector12 x = RandomPair(rng, 1.0);
    // The second primitive moves along `direction` by `offset`; bisection finds the offset.
    const auto make = [&](double offset) {
        Vector12 y = x;
        if (nearParallel) {
            y << 0, 0, 0, 1, 0, 0, 0, offset, -t, 1, offset, t;
            if (!crossing) y << 0, 0, 0, 1, 0, 0, 0.5, offset, 0, 1.5, offset + 0.05, t;
            return y;
        }
        const int first = kind == PairKind::PointTriangle ? 1 : 2;
        const Eigen::Vector3d direction = (x.segment<3>(3 * first) - x.segment<3>(0)).normalized();
        for (int v = first; v < 4; ++v) y.segment<3>(3 * v) += offset * direction;
        return y;
    };
    double lo = nearParallel ? 0 : -4, hi = 4;
    for (int iteration = 0; iteration < 200; ++iteration) {
        const double mid = (lo + hi) / 2;
        (std::sqrt(SquaredDistance(kind, make(mid), nullptr, nullptr)) < target ? lo : hi) = mid;
    }
    const Vector12 y = nearParallel ? Placed(make(lo), rng) : make(lo);
    if (std::abs(std::sqrt(SquaredDistance(kind, y, nullptr, nullptr)) - target) < 1e-6) return y;
    return PairInReach(rng, kind, def, nearParallel);  // the distance is not monotone in this offset: another pair
}

TEST(ContactBarrier, PairEnergyDerivativesMatchCentralDifferences) {
    std::mt19937 rng(5);
    const BarrierDef def{0.5, 0.1, 3.0};
    int mollified = 0;
    for (int trial = 0; trial < 90; ++trial) {
        const PairKind kind = trial % 3 == 0 ? PairKind::PointTriangle : PairKind::EdgeEdge;
        const bool nearParallel = trial % 3 == 2;
        const Vector12 x = PairInReach(rng, kind, def, nearParallel);
        const ClosestFeatures c = ClosestFeaturesOf(kind, x);
        bool stable = true;
        for (int k = 0; k < 12 && stable; ++k)
            for (double s : {-1e-4, 1e-4}) {
                Vector12 y = x;
                y[k] += s;
                stable = stable && ClosestFeaturesOf(kind, y).kind == c.kind;
            }
        if (!stable) continue;
        // The mollifier's threshold from a rest shape at twice the edges' cross product: mollified
        // when near parallel.
        const double threshold = kind == PairKind::EdgeEdge ? EdgeEdgeMollifierThreshold(x) * (nearParallel ? 1e3 : 1) : 0;
        if (nearParallel) ++mollified;
        ExpectDerivatives([&](const Vector12& y, Vector12* g, Matrix12* H) {
            return PairBarrierEnergy(kind, y, threshold, def, g, H, false);
        }, x, 1e-7, 1e-6, 1e-4, nearParallel ? "mollified edge-edge barrier" : "barrier");
    }
    EXPECT_GT(mollified, 10);
}

TEST(ContactBarrier, ProjectedHessianIsPositiveSemiDefinite) {
    std::mt19937 rng(9);
    const BarrierDef def{0.5, 0.1, 3.0};
    for (int trial = 0; trial < 40; ++trial) {
        const PairKind kind = trial % 2 ? PairKind::EdgeEdge : PairKind::PointTriangle;
        const Vector12 x = PairInReach(rng, kind, def, false);
        Matrix12 exact, projected;
        Vector12 g;
        PairBarrierEnergy(kind, x, 0, def, &g, &exact, false);
        PairBarrierEnergy(kind, x, 0, def, nullptr, &projected, true);
        Eigen::SelfAdjointEigenSolver<Matrix12> e(projected), f(exact);
        EXPECT_GE(e.eigenvalues().minCoeff(), -1e-9 * e.eigenvalues().cwiseAbs().maxCoeff());
        // Only the negative part is removed: the largest eigenvalue (the push apart) is kept.
        EXPECT_NEAR(e.eigenvalues().maxCoeff(), f.eigenvalues().maxCoeff(), 1e-9 * f.eigenvalues().cwiseAbs().maxCoeff());
    }
}

// A crumpled sheet: an n x n grid folded over itself in z, so that far-apart parts of it are close.
struct Sheet {
    Positions x;
    std::vector<std::array<int, 3>> triangles;
};
Sheet FoldedSheet(int n, double size, std::mt19937& rng) {
    Sheet s;
    s.x.Resize(n * n);
    std::uniform_real_distribution<double> jitter(-0.05, 0.05);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double u = size * i / (n - 1), v = size * j / (n - 1);
            const double angle = 3 * M_PI * u / size;  // one and a half turns: layers about 0.4 apart
            const int k = i * n + j;
            s.x.x[k] = (0.3 + 0.1 * angle) * std::cos(angle) + jitter(rng);
            s.x.y[k] = v + jitter(rng);
            s.x.z[k] = (0.3 + 0.1 * angle) * std::sin(angle) + jitter(rng);
        }
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const int a = i * n + j, b = a + n, c = b + 1, d = a + 1;
            s.triangles.push_back({a, b, c});
            s.triangles.push_back({a, c, d});
        }
    return s;
}

// Every pair of the surface that shares no vertex, point-triangle and edge-edge: brute force.
template <typename Visit>
void ForEveryPair(const ContactSurface& surface, Visit&& visit) {
    for (int p : surface.points)
        for (const auto& t : surface.triangles)
            if (p != t[0] && p != t[1] && p != t[2]) visit(ContactPair{PairKind::PointTriangle, {p, t[0], t[1], t[2]}});
    for (std::size_t i = 0; i < surface.edges.size(); ++i)
        for (std::size_t j = i + 1; j < surface.edges.size(); ++j) {
            const auto &a = surface.edges[i], &b = surface.edges[j];
            if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) continue;
            visit(ContactPair{PairKind::EdgeEdge, {a[0], a[1], b[0], b[1]}});
        }
}

TEST(ContactCandidates, FindEveryPairWithinReach) {
    std::mt19937 rng(3);
    const Sheet sheet = FoldedSheet(14, 3.0, rng);
    const double reach = 0.15;
    const ContactSurface surface = MakeContactSurface(sheet.x, sheet.triangles, {}, 0);
    const std::vector<ContactPair> candidates = ContactCandidates(surface, sheet.x, nullptr, reach);
    EXPECT_TRUE(std::is_sorted(candidates.begin(), candidates.end()));
    // All pairs by brute force.
    int within = 0;
    const auto expectFound = [&](const ContactPair& pair) {
        if (std::sqrt(SquaredDistance(pair.kind, PairCoordinates(pair, sheet.x), nullptr, nullptr)) > reach) return;
        ++within;
        EXPECT_TRUE(std::binary_search(candidates.begin(), candidates.end(), pair));
    };
    ForEveryPair(surface, expectFound);
    EXPECT_GT(within, 100);                            // the folds do come within reach
    EXPECT_LT(candidates.size(), 40u * within + 1000);  // and the hash is not all pairs

    // Neighbours at rest are left out: with the rest shape as it is, every pair within reach at rest is.
    const ContactSurface withNeighbours = MakeContactSurface(sheet.x, sheet.triangles, {}, reach);
    for (const ContactPair& pair : ContactCandidates(withNeighbours, sheet.x, nullptr, reach))
        EXPECT_GE(std::sqrt(SquaredDistance(pair.kind, PairCoordinates(pair, sheet.x), nullptr, nullptr)), reach);
}

TEST(ContactCandidates, RestClearanceIsTheNearestPairApartAlongTheWall) {
    // Two flat sheets 0.3 apart (one above the other, not joined): the nearest pair at rest that is
    // not neighbours is a sheet's point over the other's triangle, 0.3 apart. One sheet alone has
    // only neighbours within reach: no such pair.
    Sheet two;
    const int n = 6;
    two.x.Resize(2 * n * n);
    for (int layer = 0; layer < 2; ++layer)
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const int k = layer * n * n + i * n + j;
                two.x.x[k] = 0.4 * i + 0.05 * layer;
                two.x.y[k] = 0.4 * j;
                two.x.z[k] = 0.3 * layer;
            }
    for (int layer = 0; layer < 2; ++layer)
        for (int i = 0; i + 1 < n; ++i)
            for (int j = 0; j + 1 < n; ++j) {
                const int a = layer * n * n + i * n + j, b = a + n, c = b + 1, d = a + 1;
                two.triangles.push_back({a, b, c});
                two.triangles.push_back({a, c, d});
            }
    const ContactSurface both = MakeContactSurface(two.x, two.triangles, {}, 1.0);
    EXPECT_NEAR(both.restClearanceMm, 0.3, 1e-12);
    const auto& v = both.restNearest.vertices;
    EXPECT_NEAR(std::sqrt(SquaredDistance(both.restNearest.kind, PairCoordinates(both.restNearest, two.x), nullptr, nullptr)), 0.3, 1e-12);
    EXPECT_NE(v[0] < n * n, v[3] < n * n);  // one primitive on each sheet
    Sheet one = two;
    one.triangles.resize(one.triangles.size() / 2);
    EXPECT_TRUE(std::isinf(MakeContactSurface(one.x, one.triangles, {}, 1.0).restClearanceMm));
}

// The neighbours at rest are the rule's (contact.h): pairs closer than neighbourMm whose vertices
// are also within neighbourMm plus the longest edge of each other along the edges. One vertex of
// the folded sheet pulled far out gives the mesh edges of several units, so the rule's radius spans
// a turn of the fold and joins its layers as neighbours, where each vertex's own edges are short:
// the search that takes a small ball first must fall back to the rule's for those pairs.
TEST(ContactCandidates, NeighboursAreThePairsNearAlongTheWallByTheRule) {
    std::mt19937 rng(5);
    Sheet sheet = FoldedSheet(12, 3.0, rng);
    sheet.x.y[0] -= 4;  // a corner pulled out: edges of about 4 from it
    const double neighbourMm = 0.5;
    const ContactSurface surface = MakeContactSurface(sheet.x, sheet.triangles, {}, neighbourMm);
    const int n = sheet.x.Size();
    // Distances along the edges by the plain O(n^2) Dijkstra, from every vertex.
    std::vector<std::vector<int>> adjacent(n);
    double longest = 0;
    for (const auto& e : surface.edges) {
        adjacent[e[0]].push_back(e[1]);
        adjacent[e[1]].push_back(e[0]);
        longest = std::max(longest, (PointOf(sheet.x, e[0]) - PointOf(sheet.x, e[1])).norm());
    }
    ASSERT_GT(longest, 3.5);
    const double radius = neighbourMm + longest;
    std::vector<std::vector<double>> along(n, std::vector<double>(n, std::numeric_limits<double>::infinity()));
    for (int source = 0; source < n; ++source) {
        std::vector<double>& d = along[source];
        std::vector<char> settled(n, 0);
        d[source] = 0;
        for (;;) {
            int u = -1;
            for (int v = 0; v < n; ++v)
                if (!settled[v] && d[v] <= radius && (u < 0 || d[v] < d[u])) u = v;
            if (u < 0) break;
            settled[u] = 1;
            for (int w : adjacent[u]) d[w] = std::min(d[w], d[u] + (PointOf(sheet.x, u) - PointOf(sheet.x, w)).norm());
        }
    }
    const auto close = [&](const ContactPair& pair, int split) {
        for (int i = 0; i < split; ++i)
            for (int j = split; j < 4; ++j)
                if ((PointOf(sheet.x, pair.vertices[i]) - PointOf(sheet.x, pair.vertices[j])).squaredNorm() < neighbourMm * neighbourMm) return true;
        return SquaredDistance(pair.kind, PairCoordinates(pair, sheet.x), nullptr, nullptr) < neighbourMm * neighbourMm;
    };
    const auto nearAlong = [&](const ContactPair& pair, int split) {
        for (int i = 0; i < split; ++i)
            for (int j = split; j < 4; ++j)
                if (along[pair.vertices[i]][pair.vertices[j]] <= radius) return true;
        return false;
    };
    int acrossTheFold = 0;  // neighbours by the rule's radius alone: more than a small ball reaches
    for (int p : surface.points) {
        std::vector<int> expected;
        for (int t = 0; t < static_cast<int>(surface.triangles.size()); ++t) {
            const auto& v = surface.triangles[t];
            if (p == v[0] || p == v[1] || p == v[2]) continue;
            const ContactPair pair{PairKind::PointTriangle, {p, v[0], v[1], v[2]}};
            if (!close(pair, 1) || !nearAlong(pair, 1)) continue;
            expected.push_back(t);
            const double nearest = std::min({along[p][v[0]], along[p][v[1]], along[p][v[2]]});
            acrossTheFold += nearest > neighbourMm + 1.0;
        }
        EXPECT_EQ(surface.neighbourTriangles[p], expected) << "point " << p;
    }
    EXPECT_GT(acrossTheFold, 10) << acrossTheFold;
    for (int e = 0; e < static_cast<int>(surface.edges.size()); ++e) {
        std::vector<int> expected;
        for (int f = 0; f < static_cast<int>(surface.edges.size()); ++f) {
            const auto &a = surface.edges[e], &b = surface.edges[f];
            if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) continue;
            const ContactPair pair{PairKind::EdgeEdge, {a[0], a[1], b[0], b[1]}};
            if (close(pair, 2) && nearAlong(pair, 2)) expected.push_back(f);
        }
        EXPECT_EQ(surface.neighbourEdges[e], expected) << "edge " << e;
    }
}

TEST(ContactCandidates, FindEveryPairThatComesWithinReachOnAMove) {
    // The swept query continuous collision detection relies on: every pair that comes within the
    // reach anywhere along a move (sampled at 41 points) is a candidate.
    std::mt19937 rng(5);
    const Sheet sheet = FoldedSheet(10, 3.0, rng);
    const double reach = 0.1;
    const ContactSurface surface = MakeContactSurface(sheet.x, sheet.triangles, {}, 0);
    Positions move;
    move.Resize(sheet.x.Size());
    std::normal_distribution<double> n(0, 0.08);
    for (int v = 0; v < move.Size(); ++v) {
        move.x[v] = n(rng);
        move.y[v] = n(rng);
        move.z[v] = n(rng);
    }
    const std::vector<ContactPair> candidates = ContactCandidates(surface, sheet.x, &move, reach);
    EXPECT_TRUE(std::is_sorted(candidates.begin(), candidates.end()));
    EXPECT_EQ(std::adjacent_find(candidates.begin(), candidates.end()), candidates.end());
    int reached = 0;
    const auto expectFound = [&](const ContactPair& pair) {
        const Vector12 from = PairCoordinates(pair, sheet.x), step = PairCoordinates(pair, move);
        for (int k = 0; k <= 40; ++k)
            if (SquaredDistance(pair.kind, from + (k / 40.0) * step, nullptr, nullptr) < reach * reach) {
                ++reached;
                EXPECT_TRUE(std::binary_search(candidates.begin(), candidates.end(), pair));
                return;
            }
    };
    ForEveryPair(surface, expectFound);
    EXPECT_GT(reached, 40);  // 68: the move does bring parts of the folds within reach
}

TEST(ContactList, ClearanceBoundsEveryPairLeftOutUnderAnyMove) {
    // The list is trusted while ClearanceAt says no pair left out can be within the reach: check the
    // bound against every pair's true distance under random affine motions (stretch up to 1.6 and
    // down to 0.7, shear, turn, shift) with random moves on top.
    std::mt19937 rng(11);
    const Sheet sheet = FoldedSheet(10, 3.0, rng);
    const ContactSurface surface = MakeContactSurface(sheet.x, sheet.triangles, {}, 0);
    const BarrierDef barrier{.thicknessMm = 0.1, .activationMm = 0.05};
    ContactList list;
    UpdateContactList(list, surface, barrier, sheet.x);
    ASSERT_GT(list.clearanceMm, ContactReachMm(barrier));
    std::uniform_real_distribution<double> stretch(0.7, 1.6), shear(-0.3, 0.3), shift(-5, 5), noise(-1, 1);
    int covered = 0;
    for (int trial = 0; trial < 200; ++trial) {
        Eigen::Matrix3d f = Eigen::AngleAxisd(shift(rng), Eigen::Vector3d(noise(rng), noise(rng), noise(rng)).normalized()).toRotationMatrix();
        f = f * Eigen::Vector3d(stretch(rng), stretch(rng), stretch(rng)).asDiagonal();
        f(0, 1) += shear(rng);
        f(1, 2) += shear(rng);
        const Eigen::Vector3d b(shift(rng), shift(rng), shift(rng));
        const double wobble = (trial % 4) * 0.02;  // 0 to 0.06 on top of the affine motion
        Positions x = sheet.x;
        for (int v = 0; v < x.Size(); ++v) {
            const Eigen::Vector3d p = f * Eigen::Vector3d(x.x[v], x.y[v], x.z[v]) + b;
            x.x[v] = p.x() + wobble * noise(rng);
            x.y[v] = p.y() + wobble * noise(rng);
            x.z[v] = p.z() + wobble * noise(rng);
        }
        const double bound = list.ClearanceAt(x);
        covered += list.Covers(x);
        ForEveryPair(surface, [&](const ContactPair& pair) {
            if (std::binary_search(list.pairs.begin(), list.pairs.end(), pair)) return;
            EXPECT_GE(std::sqrt(SquaredDistance(pair.kind, PairCoordinates(pair, x), nullptr, nullptr)), bound - 1e-12) << "trial " << trial;
        });
    }
    // The affine part is what keeps a swelling, turning sheet covered: every move above is far
    // larger than the clearance, yet the stiffer motions keep the list.
    EXPECT_GT(covered, 10);
    // And positions it was not built on are never covered.
    Positions fewer = sheet.x;
    fewer.x.pop_back(), fewer.y.pop_back(), fewer.z.pop_back();
    EXPECT_FALSE(list.Covers(fewer));
}

// A tube of `rings` rings of n vertices (radius 5, length 24), its bottom ring a clamp (body 0).
struct Tube {
    Positions x;
    std::vector<std::array<int, 3>> triangles;
    std::vector<int> body;
};
Tube ClampedTube(int n, int rings) {
    Tube t;
    t.x.Resize(n * rings);
    t.body.assign(n * rings, -1);
    for (int j = 0; j < rings; ++j)
        for (int i = 0; i < n; ++i) {
            const double angle = 2 * M_PI * (i + 0.5 * j) / n;
            t.x.x[j * n + i] = 5 * std::cos(angle);
            t.x.y[j * n + i] = 5 * std::sin(angle);
            t.x.z[j * n + i] = 24.0 * j / (rings - 1);
            if (j == 0) t.body[i] = 0;
        }
    for (int j = 0; j + 1 < rings; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
            t.triangles.push_back({a, b, c});
            t.triangles.push_back({b, d, c});
        }
    return t;
}

// The point a fraction t of the way along the straight move from `from` to `to`.
Positions Along(const Positions& from, const Positions& to, double t) {
    Positions x = from;
    for (int v = 0; v < x.Size(); ++v) {
        x.x[v] += t * (to.x[v] - from.x[v]);
        x.y[v] += t * (to.y[v] - from.y[v]);
        x.z[v] += t * (to.z[v] - from.z[v]);
    }
    return x;
}

TEST(ContactList, BandBoundHoldsAlongEveryMoveOfABendingTube) {
    // A held tube pushed sideways bows: no affine map fits that, and the list's bound is then
    // taken band by band, and where no band's fit holds, by a search of those bands alone. Check it
    // against the true distance of every pair that comes within the distance it vouches for (the
    // spatial hash, checked against all pairs above, finds them) along random moves between bowed,
    // tilted, pinched and rippled states, and that it does vouch for bows the whole surface's fit
    // cannot.
    constexpr int kAround = 24;
    const Tube tube = ClampedTube(kAround, 16);
    const BarrierDef barrier{.thicknessMm = 1, .activationMm = 0.1};
    const double reach = ContactReachMm(barrier);
    const ContactSurface surface = MakeContactSurface(tube.x, tube.triangles, tube.body, 2 * reach);
    ASSERT_EQ(surface.layerCount, 16);
    ContactList list;
    UpdateContactList(list, surface, barrier, tube.x);
    ASSERT_TRUE(list.pairs.empty());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0, 1), sign(-1, 1);
    // A state: a bow of up to 12 mm (zero at the clamp), each ring turned about a horizontal axis by
    // up to 0.2 rad times its height, a swelling, in half of them all of it within two rings of the
    // clamp (a wall leaving its clamp: no affine motion fits those rings), sometimes with a pinch
    // there that brings its opposite walls within a wall of each other, a pinch toward the top
    // that brings the opposite walls near each other, a ripple around the rings that brings
    // vertices two apart (2.6 mm) near each other, and wrinkles of up to 0.3 mm.
    const auto state = [&](bool mayPinchAtClamp) {
        const double bow = 12 * sign(rng), tilt = 0.2 * sign(rng), swell = 0.3 * unit(rng), wrinkle = 0.15 * unit(rng);
        const double pinch = unit(rng) < 0.5 ? 0.0 : 0.6 * unit(rng), ripple = 0.6 * unit(rng);
        const double swellRings = unit(rng) < 0.5 ? 2.0 : 15.0;
        const double clampPinch = mayPinchAtClamp && unit(rng) < 0.5 ? 0.7 + 0.3 * unit(rng) : 0.0;
        Positions x = tube.x;
        for (int v = 0; v < x.Size(); ++v) {
            const double s = x.z[v] / 24;
            if (s == 0) continue;  // the clamp
            const double around = std::atan2(x.y[v], x.x[v]) + ripple * std::sin(M_PI * (v % kAround) / 2) / 5;
            x.x[v] = 5 * std::cos(around), x.y[v] = 5 * std::sin(around);
            const double along = bow * std::sin(M_PI * s / 2) * std::sin(M_PI * s / 2), turn = tilt * s * s;
            const double swelling = 1 + swell * std::min(1.0, s * 15 / swellRings);
            const double px = swelling * x.x[v], pz = x.z[v];
            x.x[v] = px * std::cos(turn) + along + wrinkle * sign(rng);
            x.y[v] = swelling * (1 - pinch * s * s) * (1 - clampPinch * std::min(1.0, s * 15 / swellRings)) * x.y[v] + wrinkle * sign(rng);
            x.z[v] = pz - px * std::sin(turn) + wrinkle * sign(rng);
        }
        return x;
    };
    // The same list with no surface to search: its fits alone vouch.
    ContactList fitsAlone = list;
    fitsAlone.surface = nullptr;
    int vouched = 0, onlyBands = 0, onlySearched = 0;
    double slack = std::numeric_limits<double>::infinity();  // the nearest pair left out, less what was vouched for
    for (int trial = 0; trial < 400; ++trial) {
        const Positions from = state(false), to = trial % 2 ? from : state(false);
        const double need = trial % 3 ? reach : barrier.thicknessMm;
        if (!list.StaysClear(from, to, need)) continue;
        ++vouched;
        onlyBands += !(std::min(list.ClearanceAt(from), list.ClearanceAt(to)) >= need);
        onlySearched += !fitsAlone.StaysClear(from, to, need);
        for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
            const Positions x = Along(from, to, t);
            for (const ContactPair& pair : ContactCandidates(surface, x, nullptr, 2 * need)) {
                if (std::binary_search(list.pairs.begin(), list.pairs.end(), pair)) continue;
                const double d = std::sqrt(SquaredDistance(pair.kind, PairCoordinates(pair, x), nullptr, nullptr));
                EXPECT_GE(d, need) << "trial " << trial << " t " << t;
                slack = std::min(slack, d - need);
            }
        }
    }
    EXPECT_GT(vouched, 20);
    EXPECT_GT(onlyBands, 10);  // bows the whole tube's fit could not vouch for
    EXPECT_GT(onlySearched, 10);  // and states whose rings by the clamp only a search could
    EXPECT_LT(slack, 0.6);     // and pairs did come near what it vouched for
    std::printf("vouched %d, beyond the whole fit %d, by a search %d, nearest %.3f mm beyond\n", vouched, onlyBands, onlySearched, slack);

    // The search of a few rings by itself, on states that may pinch those rings shut: what it
    // vouches for holds for every pair of theirs, and it refuses where walls come near.
    int searchVouched = 0, searchRefused = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Positions from = state(true), to = trial % 2 ? from : state(true);
        const double need = trial % 3 ? reach : barrier.thicknessMm;
        std::vector<std::uint8_t> bands(list.bands.size(), 0), only(from.Size(), 0);
        const int first = trial % 3, count = 1 + trial % 4;
        for (int k = first; k < first + count; ++k) {
            bands[k] = 1;
            for (int v : list.bands[k].vertices) only[v] = 1;
        }
        if (!list.SearchedClear(bands, from, to, need)) {
            ++searchRefused;
            continue;
        }
        ++searchVouched;
        for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
            const Positions x = Along(from, to, t);
            for (const ContactPair& pair : ContactCandidates(surface, x, nullptr, 2 * need, &only))
                EXPECT_GE(std::sqrt(SquaredDistance(pair.kind, PairCoordinates(pair, x), nullptr, nullptr)), need) << "trial " << trial << " t " << t;
        }
    }
    EXPECT_GT(searchVouched, 50);
    EXPECT_GT(searchRefused, 50);
    std::printf("a search of 1-4 rings by the clamp: vouched %d, refused %d\n", searchVouched, searchRefused);
}

TEST(ContactCcd, NoRandomStepCrossesAWall) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0, 1);
    const double wall = 0.2;
    int collisions = 0, steps = 0;
    std::vector<double> ratios;  // cut step over the first contact's time
    for (int trial = 0; trial < 4000; ++trial) {
        const PairKind kind = trial % 2 ? PairKind::EdgeEdge : PairKind::PointTriangle;
        const Vector12 x = RandomPair(rng, 1.0);
        if (std::sqrt(SquaredDistance(kind, x, nullptr, nullptr)) <= wall * 1.01) continue;
        Vector12 dx = RandomPair(rng, 1.5);
        ++steps;
        const double t = PairImpactTime(kind, x, dx, wall, 1.0);
        ASSERT_GE(t, 0);
        ASSERT_LE(t, 1);
        // Dense sampling of [0, t]: never closer than the wall.
        for (int k = 0; k <= 400; ++k) {
            const double s = t * k / 400;
            ASSERT_GT(std::sqrt(SquaredDistance(kind, x + s * dx, nullptr, nullptr)), wall) << trial << " at " << s;
        }
        // Sampling the whole move: a step cut short is cut before the first contact, and not far before.
        double first = 2;
        for (int k = 0; k <= 2000; ++k)
            if (std::sqrt(SquaredDistance(kind, x + (k / 2000.0) * dx, nullptr, nullptr)) <= wall) {
                first = k / 2000.0;
                break;
            }
        if (first <= 1) {
            ++collisions;
            EXPECT_LT(t, first) << trial;
            ratios.push_back(t / first);
        }
        if (t < 1 && first > 1) {
            // A cut with no contact: the pair came within a tenth of its gap's worth of the wall.
            const double gapAtStart = std::sqrt(SquaredDistance(kind, x, nullptr, nullptr)) - wall;
            double closest = INFINITY;
            for (int k = 0; k <= 2000; ++k) closest = std::min(closest, std::sqrt(SquaredDistance(kind, x + (k / 2000.0) * dx, nullptr, nullptr)) - wall);
            EXPECT_LT(closest, 0.2 * gapAtStart + 1e-3) << trial;
        }
    }
    EXPECT_GT(steps, 3000);
    EXPECT_GT(collisions, 300);
    // Conservative, not timid: where the move does reach the wall, the step is cut near it.
    std::sort(ratios.begin(), ratios.end());
    std::printf("cut step / first contact: 10 %% %.3f, median %.3f, 90 %% %.3f\n", ratios[ratios.size() / 10],
                ratios[ratios.size() / 2], ratios[9 * ratios.size() / 10]);
    EXPECT_GT(ratios[ratios.size() / 2], 0.8);
    EXPECT_GT(ratios[ratios.size() / 10], 0.5);
}

}  // namespace
}  // namespace sim
