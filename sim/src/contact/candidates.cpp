// Which primitives of a surface may touch (docs/models/shell.md section 8): a uniform spatial hash on
// bounding boxes. Boxes are inflated by half the reach each way, so two boxes overlap whenever their
// primitives may be within the reach. Triangles and edges are hashed; each point queries the
// triangles' cells and each edge the edges', with its neighbours along the wall marked as seen
// before it looks, so a wall's own neighbourhood costs a stamp each rather than a pair test.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>

#include "contact/contact.h"

namespace sim {

namespace {
template <bool kWithinReach = true, typename PointTriangle, typename EdgeEdge>
void ForEachCandidate(const ContactSurface& surface, const Positions& x, const Positions* dx, double reachMm,
                      const std::vector<std::uint8_t>* only, PointTriangle&& pointTriangle, EdgeEdge&& edgeEdge);

// ContactSurface::layer: breadth first along the edges (each vertex's neighbours are
// adjacent[adjacentBegin[v]] to adjacent[adjacentBegin[v + 1]]) from the bottom clamp's vertices
// (body 0), or from the lowest point of each part of the surface that holds none of them.
void LayerSurface(ContactSurface& s, const std::vector<int>& adjacentBegin, const std::vector<std::pair<int, double>>& adjacent) {
    s.layer.assign(s.rest.Size(), -1);
    s.layerCount = 0;
    std::vector<int> queue;
    const auto spread = [&]() {
        for (std::size_t k = 0; k < queue.size(); ++k)
            for (int a = adjacentBegin[queue[k]]; a < adjacentBegin[queue[k] + 1]; ++a)
                if (const int w = adjacent[a].first; s.layer[w] < 0) {
                    s.layer[w] = s.layer[queue[k]] + 1;
                    queue.push_back(w);
                }
        for (int v : queue) s.layerCount = std::max(s.layerCount, s.layer[v] + 1);
        queue.clear();
    };
    for (int v : s.points)
        if (!s.body.empty() && s.body[v] == 0) {
            s.layer[v] = 0;
            queue.push_back(v);
        }
    spread();
    for (int v : s.points)
        if (s.layer[v] < 0) {
            s.layer[v] = 0;
            queue.push_back(v);
            spread();
        }
}
}  // namespace

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

    // The edges from each vertex, with their lengths at rest.
    const int n = rest.Size();
    const auto at = [&](int v) { return PointOf(rest, v); };
    std::vector<int> adjacentBegin(n + 1, 0);
    for (const auto& e : s.edges) {
        ++adjacentBegin[e[0] + 1];
        ++adjacentBegin[e[1] + 1];
    }
    for (int v = 0; v < n; ++v) adjacentBegin[v + 1] += adjacentBegin[v];
    std::vector<std::pair<int, double>> adjacent(adjacentBegin[n]);
    std::vector<int> fill(adjacentBegin.begin(), adjacentBegin.end() - 1);
    double longest = 0;
    for (const auto& e : s.edges) {
        const double length = (at(e[0]) - at(e[1])).norm();
        adjacent[fill[e[0]]++] = {e[1], length};
        adjacent[fill[e[1]]++] = {e[0], length};
        longest = std::max(longest, length);
    }
    LayerSurface(s, adjacentBegin, adjacent);
    if (neighbourMm <= 0) return s;

    // Distances along the edges, by Dijkstra from a vertex out to a radius: the vertices near it
    // along the wall. The rule's radius (neighbourMm plus the longest edge) is the whole mesh's, and
    // one long edge (a bulge's, 24 mm on the S5.4F shape) made every vertex's ball hold a hundred
    // and more vertices where the pairs close at rest are a few edges apart. So each vertex's ball
    // is first taken out to a radius of its own (neighbourMm plus twice its longest edge), and out
    // to the rule's only for a pair that the first one does not settle. Dijkstra's distance to a
    // vertex within the smaller radius is the same in both (every vertex on its shortest path is
    // nearer still), so the answer is the rule's.
    const double radius = neighbourMm + longest;
    std::vector<double> distance(n, std::numeric_limits<double>::infinity());
    std::vector<int> touched;
    using Item = std::pair<double, int>;
    std::vector<Item> heap;  // a min-heap on distance, reused from source to source
    const auto ball = [&](int source, double within, std::vector<int>& out) {
        distance[source] = 0;
        touched.push_back(source);
        heap.assign(1, {0, source});
        while (!heap.empty()) {
            std::pop_heap(heap.begin(), heap.end(), std::greater<Item>());
            const auto [d, v] = heap.back();
            heap.pop_back();
            if (d > distance[v]) continue;
            out.push_back(v);
            for (int k = adjacentBegin[v]; k < adjacentBegin[v + 1]; ++k) {
                const auto [w, length] = adjacent[k];
                if (d + length <= within && d + length < distance[w]) {
                    if (distance[w] == std::numeric_limits<double>::infinity()) touched.push_back(w);
                    distance[w] = d + length;
                    heap.push_back({distance[w], w});
                    std::push_heap(heap.begin(), heap.end(), std::greater<Item>());
                }
            }
        }
        for (int v : touched) distance[v] = std::numeric_limits<double>::infinity();
        touched.clear();
    };
    // Per vertex: its first ball (nearBegin[v] to nearBegin[v + 1] in `near`), whether that is the
    // rule's whole ball, and the rule's ball when a pair has needed it.
    std::vector<int> nearBegin(n + 1, 0), near;
    std::vector<std::uint8_t> whole(n, 1);
    for (int source = 0; source < n; ++source) {
        nearBegin[source] = static_cast<int>(near.size());
        if (!std::binary_search(s.points.begin(), s.points.end(), source)) continue;
        double incident = 0;
        for (int k = adjacentBegin[source]; k < adjacentBegin[source + 1]; ++k) incident = std::max(incident, adjacent[k].second);
        const double first = neighbourMm + 2 * incident;
        whole[source] = first >= radius;
        ball(source, std::min(first, radius), near);
    }
    nearBegin[n] = static_cast<int>(near.size());
    std::vector<std::vector<int>> wholeBall(n);  // empty until needed (a ball holds its source)

    // Neighbour pairs: closer than neighbourMm at rest (the hash's query, with no pair left out
    // yet) and near along the wall (a vertex of one near a vertex of the other). Most pairs near
    // along the wall have two vertices closer than neighbourMm, and so are that close themselves:
    // their distance is needed only when no two vertices are. What is near along the wall to the
    // primitive asked about is stamped once per primitive (the hash gives its pairs one after another).
    std::vector<int> nearStamp(n, -1), wholeStamp(n, -1);
    int stamp = -1, markedPoint = -1, markedEdge = -1, wholeMarked = -1;
    std::array<int, 2> marked{};  // the primitive's vertices whose balls are stamped
    int markedCount = 0;
    const auto markNear = [&](std::initializer_list<int> vertices) {
        ++stamp;
        markedCount = 0;
        for (int a : vertices) {
            marked[markedCount++] = a;
            for (int k = nearBegin[a]; k < nearBegin[a + 1]; ++k) nearStamp[near[k]] = stamp;
        }
    };
    const auto nearAlong = [&](int b) {
        if (nearStamp[b] == stamp) return true;
        bool complete = true;
        for (int k = 0; k < markedCount; ++k) complete = complete && whole[marked[k]];
        if (complete) return false;
        if (wholeMarked != stamp) {  // the rule's balls of the primitive's vertices, once per primitive
            wholeMarked = stamp;
            for (int k = 0; k < markedCount; ++k) {
                const int a = marked[k];
                if (whole[a]) {  // its first ball is the rule's
                    for (int j = nearBegin[a]; j < nearBegin[a + 1]; ++j) wholeStamp[near[j]] = stamp;
                    continue;
                }
                if (wholeBall[a].empty()) ball(a, radius, wholeBall[a]);
                for (int v : wholeBall[a]) wholeStamp[v] = stamp;
            }
        }
        return wholeStamp[b] == stamp;
    };
    const double reachSquared = neighbourMm * neighbourMm;
    const auto squaredDistance = [&](const ContactPair& pair) { return SquaredDistance(pair.kind, PairCoordinates(pair, rest), nullptr, nullptr); };
    const auto within = [&](const ContactPair& pair) {
        const int split = pair.kind == PairKind::PointTriangle ? 1 : 2;  // the first primitive's vertices
        for (int i = 0; i < split; ++i)
            for (int j = split; j < 4; ++j)
                if ((at(pair.vertices[i]) - at(pair.vertices[j])).squaredNorm() < reachSquared) return true;
        return squaredDistance(pair) < reachSquared;
    };
    std::vector<std::vector<int>> closeTriangles(n), closeEdges(s.edges.size());
    // The others are walls apart along the wall that are this close at rest: the nearest is kept.
    const auto nearest = [&](const ContactPair& pair) {
        const double squared = squaredDistance(pair);
        if (!(squared < reachSquared)) return;
        const double d = std::sqrt(squared);
        if (d < s.restClearanceMm || (d == s.restClearanceMm && pair < s.restNearest)) {
            s.restClearanceMm = d;
            s.restNearest = pair;
        }
    };
    ForEachCandidate<false>(
        s, rest, nullptr, neighbourMm, nullptr,
        [&](int p, int t) {
            const auto& v = s.triangles[t];
            const ContactPair pair{PairKind::PointTriangle, {p, v[0], v[1], v[2]}};
            if (markedPoint != p) markNear({p}), markedPoint = p, markedEdge = -1;
            if (!(nearAlong(v[0]) || nearAlong(v[1]) || nearAlong(v[2]))) nearest(pair);
            else if (within(pair)) closeTriangles[p].push_back(t);
        },
        [&](int e, int f) {
            const ContactPair pair{PairKind::EdgeEdge, {s.edges[e][0], s.edges[e][1], s.edges[f][0], s.edges[f][1]}};
            if (markedEdge != e) markNear({s.edges[e][0], s.edges[e][1]}), markedEdge = e, markedPoint = -1;
            if (!(nearAlong(s.edges[f][0]) || nearAlong(s.edges[f][1]))) return nearest(pair);
            if (!within(pair)) return;
            closeEdges[e].push_back(f);
            closeEdges[f].push_back(e);
        });
    for (auto* lists : {&closeTriangles, &closeEdges})
        for (auto& list : *lists) std::sort(list.begin(), list.end());
    s.neighbourTriangles = std::move(closeTriangles);
    s.neighbourEdges = std::move(closeEdges);
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

bool Overlap(const Box& a, const Box& b) {
    return a.lo.x() <= b.hi.x() && a.lo.y() <= b.hi.y() && a.lo.z() <= b.hi.z() && b.lo.x() <= a.hi.x() && b.lo.y() <= a.hi.y() &&
           b.lo.z() <= a.hi.z();
}

// Cells are packed 21 bits an axis; boxes beyond about a million cells from the origin are clamped
// onto the grid's border, which only makes the hash coarser there.
constexpr long kHalfGrid = 1L << 20;
std::uint64_t CellKey(long i, long j, long k) {
    const auto pack = [](long c) { return static_cast<std::uint64_t>(std::clamp(c, -kHalfGrid, kHalfGrid - 1) + kHalfGrid); };
    return pack(i) << 42 | pack(j) << 21 | pack(k);
}

// Calls visit(key) for every cell a finite box touches.
template <typename Visit>
void ForEachCell(const Box& b, double cell, Visit&& visit) {
    const Eigen::Array3d lo = (b.lo / cell).array().floor(), hi = (b.hi / cell).array().floor();
    for (double i = lo[0]; i <= hi[0]; ++i)
        for (double j = lo[1]; j <= hi[1]; ++j)
            for (double k = lo[2]; k <= hi[2]; ++k) visit(CellKey(long(i), long(j), long(k)));
}

// The primitives (indices into one kind's boxes) in each cell: an open-addressing table from cell
// keys to dense cell indices, each cell with its range of `items`, filled in index order, so a cell
// lists its primitives in ascending order on every run. Each box's cells are listed once, then
// counted and placed: no sort, no allocation after the first query on a thread, and only the
// table's keys and indices are as long as the table.
class CellGrid {
public:
    void Build(const std::vector<Box>& boxes, double cell) {
        cell_ = cell;
        entries_.clear();
        for (int n = 0; n < static_cast<int>(boxes.size()); ++n)
            if (Finite(boxes[n])) ForEachCell(boxes[n], cell, [&](std::uint64_t key) { entries_.push_back({key, n, 0}); });
        std::size_t size = 16;
        while (size < 2 * entries_.size()) size *= 2;
        mask_ = size - 1;
        keys_.assign(size, kEmpty);
        cellOf_.resize(size);
        begin_.assign(1, 0);
        for (Entry& e : entries_) {
            e.cell = Insert(e.key);
            ++begin_[e.cell + 1];
        }
        const std::size_t cells = begin_.size() - 1;
        for (std::size_t c = 0; c < cells; ++c) begin_[c + 1] += begin_[c];
        fill_.assign(begin_.begin(), begin_.end() - 1);
        items_.resize(entries_.size());
        for (const Entry& e : entries_) items_[fill_[e.cell]++] = e.item;
    }
    // Calls visit(n) for the primitives above `after` in every cell the box touches (a primitive once
    // per cell). A cell lists its primitives in ascending order, so those at or below `after` cost a
    // binary search, not a visit each.
    template <typename Visit>
    void ForEachNear(const Box& b, int after, Visit&& visit) const {
        ForEachCell(b, cell_, [&](std::uint64_t key) {
            const std::size_t c = Find(key);
            if (c == kNone) return;
            const int* first = items_.data() + begin_[c];
            const int* last = items_.data() + begin_[c + 1];
            if (after >= 0) first = std::upper_bound(first, last, after);
            for (; first != last; ++first) visit(*first);
        });
    }
    static bool Finite(const Box& b) { return b.lo.allFinite() && b.hi.allFinite(); }  // a non-finite state is the solver's to report

private:
    static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
    static constexpr std::size_t kNone = ~std::size_t(0);
    std::size_t SlotOf(std::uint64_t key) const { return (key * 0x9E3779B97F4A7C15ULL >> 17) & mask_; }
    // The cell's dense index (a new one for a key not yet in the table).
    int Insert(std::uint64_t key) {
        for (std::size_t slot = SlotOf(key);; slot = (slot + 1) & mask_) {
            if (keys_[slot] == key) return cellOf_[slot];
            if (keys_[slot] == kEmpty) {
                keys_[slot] = key;
                cellOf_[slot] = static_cast<int>(begin_.size() - 1);
                begin_.push_back(0);
                return cellOf_[slot];
            }
        }
    }
    std::size_t Find(std::uint64_t key) const {
        for (std::size_t slot = SlotOf(key);; slot = (slot + 1) & mask_) {
            if (keys_[slot] == key) return cellOf_[slot];
            if (keys_[slot] == kEmpty) return kNone;
        }
    }
    double cell_ = 1;
    std::size_t mask_ = 0;
    std::vector<std::uint64_t> keys_;
    std::vector<int> cellOf_;  // per slot of the table: its cell's dense index (where keys_ holds one)
    struct Entry {
        std::uint64_t key;  // a cell a box touches
        int item;           // the box
        int cell;           // the cell's dense index
    };
    std::vector<Entry> entries_;
    std::vector<int> begin_, fill_, items_;  // per cell: its range of items_
};

// Marks primitives as seen by the current query primitive: stamps instead of clearing a set.
class Stamps {
public:
    void Resize(std::size_t n) {
        if (stamp_.size() < n) stamp_.resize(n, 0);
    }
    // The next query's stamp.
    std::uint32_t Next() {
        if (++current_ == 0) {  // wrapped: old stamps could look current
            std::fill(stamp_.begin(), stamp_.end(), 0);
            current_ = 1;
        }
        return current_;
    }
    // True the first time a primitive is marked with the query's stamp (passed in: a stamp written
    // could otherwise be the member itself as far as the compiler knows, and be read again).
    bool Mark(int n, std::uint32_t stamp) {
        if (stamp_[n] == stamp) return false;
        stamp_[n] = stamp;
        return true;
    }

private:
    std::vector<std::uint32_t> stamp_;
    std::uint32_t current_ = 0;
};

}  // namespace

namespace {

// Every candidate pair once: pointTriangle(p, t) with a point and a triangle's index, edgeEdge(e, f)
// with two edges' indices (e < f); in no particular order. Without kWithinReach, every pair whose
// boxes overlap: the caller tells those within the reach itself.
template <bool kWithinReach, typename PointTriangle, typename EdgeEdge>
void ForEachCandidate(const ContactSurface& surface, const Positions& x, const Positions* dx, double reachMm,
                      const std::vector<std::uint8_t>* only, PointTriangle&& pointTriangle, EdgeEdge&& edgeEdge) {
    // Boxes inflated by half the reach each way: two overlap whenever their primitives may be
    // within the reach (of each other's swept boxes, with dx).
    const double margin = reachMm / 2;
    std::vector<Box> pointBoxes, edgeBoxes, triangleBoxes;
    pointBoxes.reserve(surface.points.size());
    edgeBoxes.reserve(surface.edges.size());
    triangleBoxes.reserve(surface.triangles.size());
    // Primitives outside the stretch searched (with `only`) get a box that no cell holds.
    const Box none{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
    const auto boxOf = [&](const auto& vertices) {
        if (only && std::any_of(vertices.begin(), vertices.end(), [&](int v) { return !(*only)[v]; })) return none;
        return BoxOf(vertices, x, dx, margin);
    };
    for (int v : surface.points) pointBoxes.push_back(boxOf(std::array<int, 1>{v}));
    for (const auto& e : surface.edges) edgeBoxes.push_back(boxOf(e));
    for (const auto& t : surface.triangles) triangleBoxes.push_back(boxOf(t));

    // Cells about as large as the boxes of edges: a query box touches a few cells. (Half as large
    // cost more in cells visited than they saved in primitives looked at: 219 against 201 ms for
    // shell_bench's sine with contact on.)
    double cell = 0;
    std::size_t sized = 0;
    for (const Box& b : edgeBoxes)
        if (!only || CellGrid::Finite(b)) cell += (b.hi - b.lo).maxCoeff(), ++sized;  // a non-finite state searches nothing
    cell = std::max(cell / std::max<std::size_t>(1, sized), reachMm);
    if (!(cell > 0) || !std::isfinite(cell)) return;
    // A wild step (a diverging Newton iterate) makes boxes that span huge numbers of cells: coarsen
    // the grid until the cells touched are a bounded multiple of the boxes, so the hash cannot blow up.
    const auto cellsOf = [&](const Box& b) {
        const Eigen::Array3d span = (b.hi / cell).array().floor() - (b.lo / cell).array().floor() + 1;
        return span.prod();
    };
    const double boxCount = double(pointBoxes.size() + edgeBoxes.size() + triangleBoxes.size());
    for (;;) {
        double cells = 0;
        for (const auto* boxes : {&pointBoxes, &edgeBoxes, &triangleBoxes})
            for (const Box& b : *boxes)
                if (CellGrid::Finite(b)) cells += cellsOf(b);
        if (cells <= 27 * boxCount + 1e5) break;
        cell *= 2;
    }

    // The scratch of the last query on this thread: a search costs no allocation after the first.
    thread_local CellGrid triangleGrid, edgeGrid;
    thread_local Stamps seen;
    triangleGrid.Build(triangleBoxes, cell);
    edgeGrid.Build(edgeBoxes, cell);
    seen.Resize(std::max(surface.triangles.size(), surface.edges.size()));

    // Pairs farther apart than the reach are left out by their true distance, and on a move by how
    // near it can bring them: a point of one primitive and a point of the other are weighted sums of
    // their vertices, so they close in by at most the largest difference between a move of one's
    // vertex and a move of the other's. (Parts of a wall moving together, a ballooning bulb's,
    // overlap in their swept boxes but not in this.)
    const double reachSquared = reachMm * reachMm;
    const auto within = [&](const ContactPair& pair) {
        const double squared = SquaredDistance(pair.kind, PairCoordinates(pair, x), nullptr, nullptr);
        if (squared < reachSquared) return true;
        if (!dx) return false;
        const Vector12 move = PairCoordinates(pair, *dx);
        const int split = pair.kind == PairKind::PointTriangle ? 1 : 2;  // the first primitive's vertices
        double closing = 0;
        for (int i = 0; i < split; ++i)
            for (int j = split; j < 4; ++j) closing = std::max(closing, (move.segment<3>(3 * i) - move.segment<3>(3 * j)).squaredNorm());
        return std::sqrt(squared) - std::sqrt(closing) < reachMm;
    };
    const auto movable = [&](const std::array<int, 4>& v) {
        if (surface.body.empty()) return true;
        const int b = surface.body[v[0]];
        return b < 0 || surface.body[v[1]] != b || surface.body[v[2]] != b || surface.body[v[3]] != b;
    };
    // Each point against the triangles near it; its neighbours are marked seen first.
    for (int a = 0; a < static_cast<int>(surface.points.size()); ++a) {
        const Box& box = pointBoxes[a];
        if (!CellGrid::Finite(box)) continue;
        const int p = surface.points[a];
        const std::uint32_t stamp = seen.Next();
        if (!surface.neighbourTriangles.empty())
            for (int t : surface.neighbourTriangles[p]) seen.Mark(t, stamp);
        triangleGrid.ForEachNear(box, -1, [&](int n) {
            if (!seen.Mark(n, stamp) || !Overlap(box, triangleBoxes[n])) return;
            const auto& t = surface.triangles[n];
            if (p == t[0] || p == t[1] || p == t[2]) return;
            const ContactPair pair{PairKind::PointTriangle, {p, t[0], t[1], t[2]}};
            if (movable(pair.vertices) && (!kWithinReach || within(pair))) pointTriangle(p, n);
        });
    }
    // Each edge against the edges after it (one name per pair: the lower edge first).
    for (int e = 0; e < static_cast<int>(surface.edges.size()); ++e) {
        const Box& box = edgeBoxes[e];
        if (!CellGrid::Finite(box)) continue;
        const auto& ei = surface.edges[e];
        const std::uint32_t stamp = seen.Next();
        if (!surface.neighbourEdges.empty()) {
            const std::vector<int>& neighbours = surface.neighbourEdges[e];
            for (auto f = std::upper_bound(neighbours.begin(), neighbours.end(), e); f != neighbours.end(); ++f) seen.Mark(*f, stamp);
        }
        edgeGrid.ForEachNear(box, e, [&](int f) {
            if (!seen.Mark(f, stamp) || !Overlap(box, edgeBoxes[f])) return;
            const auto& ej = surface.edges[f];
            if (ei[0] == ej[0] || ei[0] == ej[1] || ei[1] == ej[0] || ei[1] == ej[1]) return;
            const ContactPair pair{PairKind::EdgeEdge, {ei[0], ei[1], ej[0], ej[1]}};
            if (movable(pair.vertices) && (!kWithinReach || within(pair))) edgeEdge(e, f);
        });
    }
}

}  // namespace

std::vector<ContactPair> ContactCandidates(const ContactSurface& surface, const Positions& x, const Positions* dx,
                                           double reachMm, const std::vector<std::uint8_t>* only) {
    std::vector<ContactPair> pairs;
    ForEachCandidate(
        surface, x, dx, reachMm, only,
        [&](int p, int n) {
            const auto& t = surface.triangles[n];
            pairs.push_back({PairKind::PointTriangle, {p, t[0], t[1], t[2]}});
        },
        [&](int e, int f) {
            const auto &a = surface.edges[e], &b = surface.edges[f];
            pairs.push_back({PairKind::EdgeEdge, {a[0], a[1], b[0], b[1]}});
        });
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace sim
