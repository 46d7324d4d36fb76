// Which primitives of a surface may touch (docs/models/shell.md section 8): a uniform spatial hash on
// bounding boxes. Boxes are inflated by half the reach each way, so two boxes overlap whenever their
// primitives may be within the reach; the hash is a sorted list of (cell, primitive) entries, which
// makes the result independent of the order anything was inserted in.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "contact/contact.h"

namespace sim {

ContactSurface MakeContactSurface(const Positions& rest, const std::vector<std::array<int, 3>>& triangles,
                                  const std::vector<char>& moves, double neighbourMm) {
    ContactSurface s;
    s.triangles = triangles;
    s.rest = rest;
    s.moves = moves;
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
std::uint64_t CellKey(long i, long j, long k) {
    constexpr long kHalf = 1L << 20;
    const auto pack = [](long c) { return static_cast<std::uint64_t>(std::clamp(c + kHalf, 0L, 2 * kHalf - 1)); };
    return pack(i) << 42 | pack(j) << 21 | pack(k);
}

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

    std::vector<Entry> entries;
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

    const auto movable = [&](const std::array<int, 4>& v) {
        return surface.moves.empty() || surface.moves[v[0]] || surface.moves[v[1]] || surface.moves[v[2]] || surface.moves[v[3]];
    };
    std::vector<ContactPair> pairs;
    for (std::size_t begin = 0; begin < entries.size();) {
        std::size_t end = begin;
        while (end < entries.size() && entries[end].cell == entries[begin].cell) ++end;
        for (std::size_t a = begin; a < end; ++a) {
            const Entry& ea = entries[a];
            for (std::size_t b = a + 1; b < end; ++b) {
                const Entry& eb = entries[b];
                if (ea.kind == kPoint && eb.kind == kTriangle) {
                    const int p = surface.points[ea.index];
                    const auto& t = surface.triangles[eb.index];
                    if (p == t[0] || p == t[1] || p == t[2]) continue;
                    if (!Overlap(pointBoxes[ea.index], triangleBoxes[eb.index])) continue;
                    const ContactPair pair{PairKind::PointTriangle, {p, t[0], t[1], t[2]}};
                    if (movable(pair.vertices)) pairs.push_back(pair);
                } else if (ea.kind == kEdge && eb.kind == kEdge) {
                    const auto &ei = surface.edges[ea.index], &ej = surface.edges[eb.index];
                    if (ei[0] == ej[0] || ei[0] == ej[1] || ei[1] == ej[0] || ei[1] == ej[1]) continue;
                    if (!Overlap(edgeBoxes[ea.index], edgeBoxes[eb.index])) continue;
                    // The lower edge first, so that a pair found in two cells is the same pair.
                    const auto& [lo, hi] = ea.index < eb.index ? std::pair(ei, ej) : std::pair(ej, ei);
                    const ContactPair pair{PairKind::EdgeEdge, {lo[0], lo[1], hi[0], hi[1]}};
                    if (movable(pair.vertices)) pairs.push_back(pair);
                }
            }
        }
        begin = end;
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

    // Neighbours within one wall: primitives already this close at rest.
    if (surface.neighbourMm > 0) {
        const double limit = surface.neighbourMm * surface.neighbourMm;
        std::erase_if(pairs, [&](const ContactPair& pair) {
            return SquaredDistance(pair.kind, PairCoordinates(pair, surface.rest), nullptr, nullptr) < limit;
        });
    }
    return pairs;
}

}  // namespace sim
