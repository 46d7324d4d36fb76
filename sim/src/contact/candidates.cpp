// Which primitives of a surface may touch (docs/models/shell.md section 8): a uniform spatial hash on
// bounding boxes. Boxes are inflated by half the reach each way, so two boxes overlap whenever their
// primitives may be within the reach; the hash is a sorted list of (cell, primitive) entries, which
// makes the result independent of the order anything was inserted in.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>

#include <Eigen/Geometry>

#include "contact/contact.h"

namespace sim {

ContactSurface MakeContactSurface(const Positions& rest, const std::vector<std::array<int, 3>>& triangles,
                                  const std::vector<int>& body, double neighbourMm) {
    ContactSurface s;
    s.triangles = triangles;
    s.rest = rest;
    s.body = body;
    s.neighbourMm = neighbourMm;
    for (const auto& t : triangles)
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            s.edges.push_back({std::min(a, b), std::max(a, b)});
            s.points.push_back(a);
        }
    std::sort(s.edges.begin(), s.edges.end());
    s.edges.erase(std::unique(s.edges.begin(), s.edges.end()), s.edges.end());
    std::sort(s.points.begin(), s.points.end());
    s.points.erase(std::unique(s.points.begin(), s.points.end()), s.points.end());
    if (neighbourMm <= 0) return s;

    // Distances along the edges, by Dijkstra from each vertex out to the radius.
    const int n = rest.Size();
    const auto at = [&](int v) { return Eigen::Vector3d(rest.x[v], rest.y[v], rest.z[v]); };
    std::vector<std::vector<std::pair<int, double>>> adjacent(n);
    double longest = 0;
    for (const auto& e : s.edges) {
        const double length = (at(e[0]) - at(e[1])).norm();
        adjacent[e[0]].push_back({e[1], length});
        adjacent[e[1]].push_back({e[0], length});
        longest = std::max(longest, length);
    }
    const double radius = neighbourMm + longest;
    s.nearAlongWall.resize(n);
    std::vector<double> distance(n, std::numeric_limits<double>::infinity());
    std::vector<int> touched;
    for (int source : s.points) {
        using Item = std::pair<double, int>;
        std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
        distance[source] = 0;
        touched.push_back(source);
        queue.push({0, source});
        while (!queue.empty()) {
            const auto [d, v] = queue.top();
            queue.pop();
            if (d > distance[v]) continue;
            s.nearAlongWall[source].push_back(v);
            for (const auto& [w, length] : adjacent[v])
                if (d + length <= radius && d + length < distance[w]) {
                    if (distance[w] == std::numeric_limits<double>::infinity()) touched.push_back(w);
                    distance[w] = d + length;
                    queue.push({distance[w], w});
                }
        }
        std::sort(s.nearAlongWall[source].begin(), s.nearAlongWall[source].end());
        for (int v : touched) distance[v] = std::numeric_limits<double>::infinity();
        touched.clear();
    }

    // Neighbour pairs, once: near along the wall (a vertex of one near a vertex of the other) and
    // closer than neighbourMm at rest.
    std::vector<std::vector<int>> trianglesAt(n), edgesAt(n);
    for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
        for (int v : triangles[t]) trianglesAt[v].push_back(t);
    for (int e = 0; e < static_cast<int>(s.edges.size()); ++e)
        for (int v : s.edges[e]) edgesAt[v].push_back(e);
    const double limit = neighbourMm * neighbourMm;
    // Boxes first: most primitives near along the wall are already farther apart than neighbourMm.
    const auto boxOf = [&](const auto& vertices) {
        Eigen::AlignedBox3d box;
        for (int v : vertices) box.extend(at(v));
        return box;
    };
    std::vector<Eigen::AlignedBox3d> triangleBox, edgeBox;
    for (const auto& t : triangles) triangleBox.push_back(boxOf(t));
    for (const auto& e : s.edges) edgeBox.push_back(boxOf(e));
    const auto close = [&](const ContactPair& pair, const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
        return a.squaredExteriorDistance(b) < limit && SquaredDistance(pair.kind, PairCoordinates(pair, rest), nullptr, nullptr) < limit;
    };
    // Each primitive is looked at once per source (a stamp, not a sort of the repeats).
    std::vector<int> stamp(std::max(triangles.size(), s.edges.size()), -1);
    s.neighbourTriangles.resize(n);
    for (int p : s.points) {
        std::vector<int>& found = s.neighbourTriangles[p];
        const Eigen::AlignedBox3d point(at(p));
        for (int v : s.nearAlongWall[p])
            for (int t : trianglesAt[v]) {
                if (stamp[t] == p) continue;
                stamp[t] = p;
                const auto& tri = triangles[t];
                if (p != tri[0] && p != tri[1] && p != tri[2] && close({PairKind::PointTriangle, {p, tri[0], tri[1], tri[2]}}, point, triangleBox[t]))
                    found.push_back(t);
            }
        std::sort(found.begin(), found.end());
    }
    std::fill(stamp.begin(), stamp.end(), -1);
    s.neighbourEdges.resize(s.edges.size());
    for (int e = 0; e < static_cast<int>(s.edges.size()); ++e) {
        std::vector<int>& found = s.neighbourEdges[e];
        const auto& a = s.edges[e];
        for (int end : a)
            for (int v : s.nearAlongWall[end])
                for (int f : edgesAt[v]) {
                    if (stamp[f] == e) continue;
                    stamp[f] = e;
                    const auto& b = s.edges[f];
                    if (a[0] != b[0] && a[0] != b[1] && a[1] != b[0] && a[1] != b[1] &&
                        close({PairKind::EdgeEdge, {a[0], a[1], b[0], b[1]}}, edgeBox[e], edgeBox[f]))
                        found.push_back(f);
                }
        std::sort(found.begin(), found.end());
    }
    return s;
}

namespace {

struct Box {
    Eigen::Vector3d lo, hi;
};

// The box of a primitive's vertices at x (and at x + dx when moving), inflated by `margin`.
template <std::size_t K>
Box BoxOf(const std::array<int, K>& vertices, const Positions& x, const Positions* dx, double margin) {
    Box b{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
          Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
    for (int v : vertices) {
        const Eigen::Vector3d p(x.x[v], x.y[v], x.z[v]);
        b.lo = b.lo.cwiseMin(p);
        b.hi = b.hi.cwiseMax(p);
        if (dx) {
            const Eigen::Vector3d q = p + Eigen::Vector3d(dx->x[v], dx->y[v], dx->z[v]);
            b.lo = b.lo.cwiseMin(q);
            b.hi = b.hi.cwiseMax(q);
        }
    }
    b.lo.array() -= margin;
    b.hi.array() += margin;
    return b;
}

bool Overlap(const Box& a, const Box& b) { return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all(); }

enum Primitive : std::uint8_t { kPoint, kEdge, kTriangle };

struct Entry {
    std::uint64_t cell;
    Primitive kind;
    int index;
    bool operator<(const Entry& o) const {
        return cell != o.cell ? cell < o.cell : kind != o.kind ? kind < o.kind : index < o.index;
    }
};

// Cells are packed 21 bits an axis; boxes beyond about a million cells from the origin are clamped
// onto the grid's border, which only makes the hash coarser there.
constexpr long kHalfGrid = 1L << 20;
std::uint64_t CellKey(long i, long j, long k) {
    const auto pack = [](long c) { return static_cast<std::uint64_t>(std::clamp(c, -kHalfGrid, kHalfGrid - 1) + kHalfGrid); };
    return pack(i) << 42 | pack(j) << 21 | pack(k);
}
// A key's coordinate along an axis (0: x), clamped onto the grid as the key was.
long CellCoordinate(std::uint64_t key, int axis) { return static_cast<long>((key >> (42 - 21 * axis)) & ((1UL << 21) - 1)) - kHalfGrid; }

}  // namespace

std::vector<ContactPair> ContactCandidates(const ContactSurface& surface, const Positions& x, const Positions* dx,
                                           double reachMm) {
    const double margin = reachMm / 2;
    std::vector<Box> pointBoxes, edgeBoxes, triangleBoxes;
    for (int v : surface.points) pointBoxes.push_back(BoxOf(std::array<int, 1>{v}, x, dx, margin));
    for (const auto& e : surface.edges) edgeBoxes.push_back(BoxOf(e, x, dx, margin));
    for (const auto& t : surface.triangles) triangleBoxes.push_back(BoxOf(t, x, dx, margin));

    // Cells about as large as the boxes of edges, so that most primitives fall in a few of them.
    double cell = 0;
    for (const Box& b : edgeBoxes) cell += (b.hi - b.lo).maxCoeff();
    cell = std::max(cell / std::max<std::size_t>(1, edgeBoxes.size()), reachMm);
    if (!(cell > 0) || !std::isfinite(cell)) return {};

    // A wild step (a diverging Newton iterate) makes boxes that span huge numbers of cells: coarsen
    // the grid until the entries are a bounded multiple of the boxes, so the hash cannot blow up.
    const auto cellsOf = [&](const Box& b) {
        const Eigen::Array3d span = (b.hi / cell).array().floor() - (b.lo / cell).array().floor() + 1;
        return span.prod();
    };
    const double boxCount = double(pointBoxes.size() + edgeBoxes.size() + triangleBoxes.size());
    for (;;) {
        double cells = 0;
        for (const auto* boxes : {&pointBoxes, &edgeBoxes, &triangleBoxes})
            for (const Box& b : *boxes)
                if (b.lo.allFinite() && b.hi.allFinite()) cells += cellsOf(b);
        if (cells <= 27 * boxCount + 1e5) break;
        cell *= 2;
    }

    // The scratch of the last query on this thread: a search costs no allocation after the first.
    thread_local std::vector<Entry> entries;
    entries.clear();
    const auto insert = [&](const std::vector<Box>& boxes, Primitive kind) {
        for (int n = 0; n < static_cast<int>(boxes.size()); ++n) {
            const Box& b = boxes[n];
            if (!b.lo.allFinite() || !b.hi.allFinite()) continue;  // a non-finite state is the solver's to report
            const Eigen::Array3d lo = (b.lo / cell).array().floor(), hi = (b.hi / cell).array().floor();
            for (double i = lo[0]; i <= hi[0]; ++i)
                for (double j = lo[1]; j <= hi[1]; ++j)
                    for (double k = lo[2]; k <= hi[2]; ++k)
                        entries.push_back({CellKey(long(i), long(j), long(k)), kind, n});
        }
    };
    insert(pointBoxes, kPoint);
    insert(edgeBoxes, kEdge);
    insert(triangleBoxes, kTriangle);
    std::sort(entries.begin(), entries.end());

    // A pair of boxes shares several cells; it is taken in one, the lowest cell of their overlap,
    // so that no pair is found twice.
    const auto lowestShared = [&](const Box& a, const Box& b, const Entry& e) {
        for (int axis = 0; axis < 3; ++axis)
            if (CellCoordinate(e.cell, axis) != std::clamp(long(std::floor(std::max(a.lo[axis], b.lo[axis]) / cell)), -kHalfGrid, kHalfGrid - 1))
                return false;
        return true;
    };
    // Without a move, pairs farther apart than the reach are left out by their true distance.
    const double reachSquared = reachMm * reachMm;
    const auto within = [&](const ContactPair& pair) {
        return dx || SquaredDistance(pair.kind, PairCoordinates(pair, x), nullptr, nullptr) < reachSquared;
    };
    const auto movable = [&](const std::array<int, 4>& v) {
        if (surface.body.empty()) return true;
        const int b = surface.body[v[0]];
        return b < 0 || surface.body[v[1]] != b || surface.body[v[2]] != b || surface.body[v[3]] != b;
    };
    std::vector<ContactPair> pairs;
    for (std::size_t begin = 0; begin < entries.size();) {
        // A cell's entries: its points, then its edges, then its triangles (the entries' order).
        std::size_t end = begin;
        while (end < entries.size() && entries[end].cell == entries[begin].cell) ++end;
        const auto firstOf = [&](Primitive kind) {
            std::size_t k = begin;
            while (k < end && entries[k].kind < kind) ++k;
            return k;
        };
        const std::size_t edgesBegin = firstOf(kEdge), trianglesBegin = firstOf(kTriangle);
        for (std::size_t a = begin; a < edgesBegin; ++a) {
            const Entry& ea = entries[a];
            const int p = surface.points[ea.index];
            const Box& pa = pointBoxes[ea.index];
            for (std::size_t b = trianglesBegin; b < end; ++b) {
                const Entry& eb = entries[b];
                const auto& t = surface.triangles[eb.index];
                const Box& tb = triangleBoxes[eb.index];
                if (p == t[0] || p == t[1] || p == t[2] || !Overlap(pa, tb) || !lowestShared(pa, tb, ea)) continue;
                if (!surface.neighbourTriangles.empty() &&
                    std::binary_search(surface.neighbourTriangles[p].begin(), surface.neighbourTriangles[p].end(), eb.index))
                    continue;
                const ContactPair pair{PairKind::PointTriangle, {p, t[0], t[1], t[2]}};
                if (movable(pair.vertices) && within(pair)) pairs.push_back(pair);
            }
        }
        for (std::size_t a = edgesBegin; a < trianglesBegin; ++a) {
            const Entry& ea = entries[a];
            const auto& ei = surface.edges[ea.index];
            const Box& ba = edgeBoxes[ea.index];
            for (std::size_t b = a + 1; b < trianglesBegin; ++b) {
                const Entry& eb = entries[b];
                const auto& ej = surface.edges[eb.index];
                const Box& bb = edgeBoxes[eb.index];
                if (ei[0] == ej[0] || ei[0] == ej[1] || ei[1] == ej[0] || ei[1] == ej[1] || !Overlap(ba, bb) || !lowestShared(ba, bb, ea)) continue;
                if (!surface.neighbourEdges.empty() &&
                    std::binary_search(surface.neighbourEdges[ea.index].begin(), surface.neighbourEdges[ea.index].end(), eb.index))
                    continue;
                // The lower edge first (entries are in index order within a cell): one name per pair.
                const ContactPair pair{PairKind::EdgeEdge, {ei[0], ei[1], ej[0], ej[1]}};
                if (movable(pair.vertices) && within(pair)) pairs.push_back(pair);
            }
        }
        begin = end;
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());  // cells beyond the grid's border share keys
    return pairs;
}

double ContactList::Drift(const Positions& x) const {
    if (built.Size() != x.Size()) return std::numeric_limits<double>::infinity();
    double largest = 0;
    for (int v = 0; v < x.Size(); ++v) {
        const double dx = x.x[v] - built.x[v], dy = x.y[v] - built.y[v], dz = x.z[v] - built.z[v];
        largest = std::max(largest, dx * dx + dy * dy + dz * dz);
    }
    return std::isfinite(largest) ? std::sqrt(largest) : std::numeric_limits<double>::infinity();
}

bool ContactList::Covers(const Positions& x) const { return Drift(x) <= marginMm; }

bool UpdateContactList(ContactList& list, const ContactSurface& surface, const BarrierDef& barrier, const Positions& x) {
    if (list.Covers(x)) return false;
    // The pairs within 1.4 reaches: a wider list is rebuilt less often but puts every pair in it into
    // the Hessian's pattern (a collapsed tube: 36,000 pairs at twice the reach, where 2,000 touch).
    // The pairs left out are searched to 2 reaches (a wall's neighbours are left out to there at
    // rest, so on a wall far from contact none is found): the nearest of them sets how far the
    // walls may move before one of them could come within the reach (0.2 to 0.5 reaches).
    const double reach = ContactReachMm(barrier), search = 2 * reach;
    const std::vector<ContactPair> near = ContactCandidates(surface, x, nullptr, search);
    list.built = x;
    list.clearanceMm = search;
    std::vector<ContactPair> pairs;
    for (const ContactPair& pair : near) {
        const double d = std::sqrt(SquaredDistance(pair.kind, PairCoordinates(pair, x), nullptr, nullptr));
        if (d < 1.4 * reach) pairs.push_back(pair);
        else list.clearanceMm = std::min(list.clearanceMm, d);
    }
    list.marginMm = 0.5 * (list.clearanceMm - reach);
    if (pairs == list.pairs) return false;
    list.pairs = std::move(pairs);
    return true;
}

}  // namespace sim
