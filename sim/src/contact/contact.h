// Self-contact of the shell models' walls (docs/models/shell.md section 8): the walls' mid-surfaces
// keep at least a wall thickness apart, held there by a log barrier on point-triangle and edge-edge
// distances (the incremental potential contact of Li et al. 2020, offset by the wall's thickness as
// in their codimensional follow-up), with steps clipped by continuous collision detection so that no
// step ever passes through a wall.
//
// Units: millimetres and newtons; energies in N mm.
//
// [SECTION] Pairs and distances: the closest features of a pair and its squared distance, exactly
//           differentiated
// [SECTION] Barrier: b(s) on the gap s = d - h, the edge-edge mollifier, one pair's energy
// [SECTION] Surfaces and candidates: which primitives may touch (a spatial hash)
// [SECTION] Continuous collision detection: the largest step no pair crosses
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "sim/mesh.h"

namespace sim {

// ---------------------------------------------------------------------------------------------
// [SECTION] Pairs and distances
// ---------------------------------------------------------------------------------------------

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

// A pair that may touch: a point and a triangle (p, a, b, c) or two edges (a0, a1, b0, b1). Its
// 12 coordinates are its four vertices' x, y, z in this order.
enum class PairKind : std::uint8_t { PointTriangle, EdgeEdge };
struct ContactPair {
    PairKind kind = PairKind::PointTriangle;
    std::array<int, 4> vertices{};
    friend bool operator<(const ContactPair& a, const ContactPair& b) {
        return a.kind != b.kind ? a.kind < b.kind : a.vertices < b.vertices;
    }
    friend bool operator==(const ContactPair& a, const ContactPair& b) { return a.kind == b.kind && a.vertices == b.vertices; }
};

// Where a pair's closest points lie, which decides the formula of its distance: two vertices; a
// vertex and the inside of an edge; a vertex and the inside of the triangle (its plane); the insides
// of two edges (their lines).
enum class DistanceCase : std::uint8_t { PointPoint, PointEdge, PointPlane, LineLine };
struct ClosestFeatures {
    DistanceCase kind = DistanceCase::PointPoint;
    std::array<int, 4> local{};  // the pair's vertices (0-3) that the case's formula takes, in its order
};
ClosestFeatures ClosestFeaturesOf(PairKind kind, const Vector12& x);

// The squared distance (mm^2) between a pair's primitives at x, and its gradient and Hessian over the
// 12 coordinates with the closest features held at x's (each distance is smooth within its case and
// the cases meet continuously). Either pointer may be null.
double SquaredDistance(PairKind kind, const Vector12& x, Vector12* gradient, Matrix12* hessian);

// The pair's 12 coordinates at positions x.
Vector12 PairCoordinates(const ContactPair& pair, const Positions& x);
// Vertex v of positions x.
inline Eigen::Vector3d PointOf(const Positions& x, int v) { return {x.x[v], x.y[v], x.z[v]}; }
// The straight move from `from` to `to`, vertex by vertex (what a swept query and CCD take).
inline Positions MoveBetween(const Positions& from, const Positions& to) {
    Positions move = to;
    for (int v = 0; v < move.Size(); ++v) {
        move.x[v] -= from.x[v];
        move.y[v] -= from.y[v];
        move.z[v] -= from.z[v];
    }
    return move;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Barrier
// ---------------------------------------------------------------------------------------------

struct BarrierDef {
    double thicknessMm = 1;    // h: the mid-surfaces' distance when the walls touch
    double activationMm = 0.1; // s-hat: the barrier acts on gaps s = d - h below it
    double stiffness = 1;      // kappa, N mm
};

// IPC's barrier b(s) = -(s - s_hat)^2 ln(s / s_hat) for 0 < s < s_hat, else 0; with its first and
// second derivatives (either pointer may be null). Infinite at s <= 0.
double Barrier(double s, double sHat, double* first, double* second);

// The edge-edge mollifier: near-parallel edges' line distance has no unique closest points, so
// their barrier fades with c = |e_a x e_b|^2 below threshold = 1e-3 |E_a|^2 |E_b|^2 (rest lengths):
// m = (2 - c / threshold) c / threshold there, 1 above.
double EdgeEdgeMollifierThreshold(const Vector12& rest);
// m of c = |e_a x e_b|^2 at that threshold.
double EdgeEdgeMollifier(double crossSquared, double threshold);

// One pair's barrier energy kappa m b(d - h) at x (m = 1 for point-triangle pairs), with its gradient
// and Hessian (exact, or with project, projected to positive semi-definite for Newton's matrix).
// `mollifierThreshold` is the edge-edge pair's, from its rest coordinates.
double PairBarrierEnergy(PairKind kind, const Vector12& x, double mollifierThreshold, const BarrierDef& barrier,
                         Vector12* gradient, Matrix12* hessian, bool project);

// ---------------------------------------------------------------------------------------------
// [SECTION] Surfaces and candidates
// ---------------------------------------------------------------------------------------------

// The surface that may touch itself: triangles (the wall and the end caps), their unique edges, and
// which vertices ride on a rigid body (a clamp): a pair whose four vertices ride on one keeps its
// distance and is skipped.
//
// Neighbours within one wall are not contact: a pair closer than neighbourMm at rest whose vertices
// are also near each other along the mesh's edges (within neighbourMm plus the longest edge) is never
// a candidate. The second condition keeps the two sides of a narrow neck, close at rest but half a
// circumference apart along the wall, as walls that may touch.
struct ContactSurface {
    std::vector<std::array<int, 3>> triangles;
    std::vector<std::array<int, 2>> edges;   // each once, lower vertex first
    std::vector<int> points;                 // vertices of the triangles, ascending
    std::vector<int> body;                   // per vertex of the mesh: its rigid body (0, 1, ...) or -1 (empty: none)
    Positions rest;
    double neighbourMm = 0;
    // The neighbours, found once: per vertex the triangles (indices into `triangles`), per edge the
    // edges (indices into `edges`), ascending.
    std::vector<std::vector<int>> neighbourTriangles, neighbourEdges;
    // The nearest pair at rest that is not neighbours, if one is within neighbourMm (a rest shape
    // whose walls already touch), and its distance (infinite when none is).
    ContactPair restNearest;
    double restClearanceMm = std::numeric_limits<double>::infinity();
    // Per vertex of the mesh, its layer: how many edges from the bottom clamp (from the surface's
    // first point where there is none), -1 off the surface. The two ends of an edge are at most a
    // layer apart, so a triangle's vertices lie in two consecutive layers. On a tube, a ring.
    std::vector<int> layer;
    int layerCount = 0;
};
ContactSurface MakeContactSurface(const Positions& rest, const std::vector<std::array<int, 3>>& triangles,
                                  const std::vector<int>& body, double neighbourMm);

// The pairs whose primitives may be within reachMm of each other (a uniform spatial hash on their
// bounding boxes), or, with dx, at any point while x moves to x + dx. Pairs that share a vertex,
// neighbours and pairs on one rigid body are left out; with `only` (per vertex of the mesh), so are
// primitives with a vertex outside it (a search of one stretch of wall). Sorted, each once: the same
// list on every run.
std::vector<ContactPair> ContactCandidates(const ContactSurface& surface, const Positions& x, const Positions* dx,
                                           double reachMm, const std::vector<std::uint8_t>* only = nullptr);

// The distance at which pairs act: a wall thickness and the barrier's reach beyond it.
inline double ContactReachMm(const BarrierDef& barrier) { return barrier.thicknessMm + barrier.activationMm; }

// True when a pair acts at x: its primitives within the reach (the one test of every sum over
// pairs, and of whether a new pair needs a place in the Hessian). Its coordinates at x, which its
// barrier takes, go to *coordinates when given.
inline bool InReach(const ContactPair& pair, const Positions& x, const BarrierDef& barrier, Vector12* coordinates = nullptr) {
    const Vector12 c = PairCoordinates(pair, x);
    if (coordinates) *coordinates = c;
    const double reach = ContactReachMm(barrier);
    return SquaredDistance(pair.kind, c, nullptr, nullptr) < reach * reach;
}

// The pairs an assembly sums over (a Verlet list): the candidates within 1.4 reaches of the
// positions it was built at. It holds every pair within the reach for as long as no pair left out
// can have come that near, so a Newton solve rebuilds it (and its Hessian's pattern) only when the
// walls have moved far enough for that.
//
// How near a pair left out can have come is bounded from the distance of the nearest of them at
// `built` (clearanceMm, searched out to two reaches) and the vertices' moves since: an affine motion
// (a tube swelling and shortening) changes every distance by at most its strain, and what is left of
// the moves by at most twice the largest. The same bound lets continuous collision detection look at
// the list's pairs alone while the walls cannot have come nearer: a tube inflating far from contact
// pays for a search now and then, not at every step.
//
// A tube that bows (a held state pushed sideways) moves no way an affine map fits, so while no wall
// is near another (an empty list) the bound is also taken band by band: bands of the surface's
// layers (rings), each pair of windows (two consecutive bands, which hold every primitive) fitted
// with its own affine motion and bounded from its own distance at `built` (its bands' boxes apart,
// at least clearanceMm). A bend fits each short stretch of tube, and stretches far apart need no
// fit. The few windows no affine motion fits (where a wall leaves its clamp and bulges or tilts
// within a few rings) are searched on their own: a search of those rings instead of the whole wall.
struct ContactList {
    std::vector<ContactPair> pairs;
    // The candidates within 1.8 reaches of `built` (pairs included): what a Hessian pattern that is
    // to outlast this list holds, so that the lists built after it as walls slide along each other
    // fall inside the pattern, and the factors' analysis and the last factor carry over.
    std::vector<ContactPair> wider;
    Positions built;
    const ContactSurface* surface = nullptr;  // what it was built on
    double reachMm = 0;      // the list holds every pair within this while Covers
    double clearanceMm = 0;  // every pair not in the list was at least this far apart at `built`
    // The built positions' centroid and the pseudo-inverse of their spread about it (sum of
    // (x - c)(x - c)^T): what fitting an affine motion to the moves since needs.
    Eigen::Vector3d builtCentre = Eigen::Vector3d::Zero();
    Eigen::Matrix3d builtSpreadInverse = Eigen::Matrix3d::Zero();
    // The bands at `built`: their surface vertices, boxes, and centroids and spreads (as above).
    struct Band {
        std::vector<int> vertices;
        Eigen::Vector3d lo, hi, centre;
        Eigen::Matrix3d spread, spreadInverse;
    };
    // A pair of windows: its bands (-1 past the last), its centroid and spread's pseudo-inverse, and
    // a lower bound on the distance at `built` of every pair left out whose primitives lie in it.
    struct WindowPair {
        std::array<int, 4> bands{};
        Eigen::Vector3d centre;
        Eigen::Matrix3d spreadInverse;
        double distanceMm = 0;
    };
    std::vector<Band> bands;
    std::vector<WindowPair> windowPairs;
    // The last state the bands vouched for, and for what distance: a solve asks again at every
    // assembly at that state (a cache, not part of the list's meaning).
    mutable Positions vouchedAt;
    mutable double vouchedNeedMm = 0;
    // One band's moves since `built` fitted affinely at a state: u ~ mean + strain (built - centre).
    struct BandFit {
        Eigen::Matrix3d moveSpread = Eigen::Matrix3d::Zero();  // sum of u (built - centre)^T
        Eigen::Matrix3d strain = Eigen::Matrix3d::Zero();
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        double residualMm = 0;  // the largest |u - fit| over the band's vertices
        double largestMoveMm = 0;
    };
    // What the bounds found at the last two states asked about (ClearanceAt's bound, the bands'
    // fits once taken): a Newton solve asks about the same state several times (its trial, then
    // the step to it, then the assembly there: four times in five on the S5.4F shape). A cache,
    // emptied when the list is rebuilt.
    struct StateBound {
        Positions at;
        double clearanceMm = 0;
        std::vector<BandFit> fits;  // empty until the bands are asked
    };
    mutable std::array<StateBound, 2> recent;
    mutable int recentNext = 0;
    // A lower bound on the distance at x of every pair not in the list (-infinity for positions the
    // list was not built on or that are not finite), from the whole surface's affine fit alone.
    double ClearanceAt(const Positions& x) const;
    double UncachedClearanceAt(const Positions& x) const;  // the same, computed afresh
    // The state's entry in `recent` (computed when it holds none), and the bands' fits there.
    StateBound& BoundAt(const Positions& x) const;
    const std::vector<BandFit>& BandFitsAt(const Positions& x) const;
    // True when no pair left out comes within needMm at any point of the straight move from `from`
    // to `to` (the whole surface's bound at both ends first, then band by band).
    bool StaysClear(const Positions& from, const Positions& to, double needMm) const;
    bool Covers(const Positions& x) const { return StaysClear(x, x, reachMm); }
    // True when no pair of primitives whose vertices all lie in the marked bands (searchBands, one
    // flag a band) comes within needMm on the straight move from `from` to `to`, by a search of those
    // primitives alone (a swept one, each pair found checked by continuous collision detection).
    // False, without a search, when they hold more than a quarter of the surface's points (that
    // costs what a fresh list does) or the list knows no surface.
    bool SearchedClear(const std::vector<std::uint8_t>& searchBands, const Positions& from, const Positions& to, double needMm) const;
};
// Rebuilds the list at x when it does not cover x. True when its pairs changed.
bool UpdateContactList(ContactList& list, const ContactSurface& surface, const BarrierDef& barrier, const Positions& x);

// What contact does at positions x: the pairs within the barrier's reach, the smallest gap between
// the walls (d - h over the pairs within the list's reach; infinite when none is), and the walls'
// contact force, the sum of the active pairs' normal forces kappa m |b'(s)| (N).
struct ContactSummary {
    int activePairs = 0;
    double minGapMm = 0;
    double forceN = 0;
};
ContactSummary SummariseContact(const ContactSurface& surface, const BarrierDef& barrier, const Positions& x);

// ---------------------------------------------------------------------------------------------
// [SECTION] Continuous collision detection
// ---------------------------------------------------------------------------------------------

// Additive continuous collision detection (Li et al. 2021) for one pair moving from x to x + t dx:
// the largest t in [0, tMax] found safe, at which the pair is still at least minDistanceMm apart
// and has kept at least a tenth of its gap beyond it. tMax when it never comes that close. x must
// start farther apart than minDistanceMm.
double PairImpactTime(PairKind kind, const Vector12& x, const Vector12& dx, double minDistanceMm, double tMax);

// The pairs that may come within a reach anywhere on a straight move from `from` by `move` (a swept
// query): an assembly at a point of that move, a line search's trial, sums over them instead of
// searching again. A point covered may stray toleranceMm from the move (a turning clamp's vertices
// move on arcs): the pairs were searched toleranceMm beyond each side of the reach.
struct ContactSweep {
    std::vector<ContactPair> pairs;
    Positions from, move;
    int fastest = 0;  // the vertex that moves most: how far along the move a state is, is read off it
    double toleranceMm = 0;
    bool Covers(const Positions& x) const;
};

// The largest fraction t in [0, 1] of the move x -> x + dx that no pair of the surface crosses
// (min over ContactCandidates of the swept move within minDistanceMm). With sweep, the swept
// query looks out to sweepReachMm (at least minDistanceMm) and keeps its pairs there, covering the
// move for that reach less toleranceMm each side.
double ImpactFreeStep(const ContactSurface& surface, const Positions& x, const Positions& dx, double minDistanceMm,
                      ContactSweep* sweep = nullptr, double sweepReachMm = 0, double toleranceMm = 0);

}  // namespace sim
