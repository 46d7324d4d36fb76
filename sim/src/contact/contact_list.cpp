// The contact list (a Verlet list) and the bounds that say how long it holds (docs/models/shell.md
// section 8): the whole surface's affine fit, and the same band by band for a tube that bows.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "contact/contact.h"

namespace sim {

namespace {
constexpr double kListReaches = 1.4;     // the list's pairs: within this many reaches
constexpr double kPatternReaches = 1.8;  // ContactList::wider: within this many
// Bands of one ring on the default walls (40-52 rings): a bend's residual over a window grows as
// its length squared, and with two rings a band the pushed benchmark sine's windows were 0.4-0.8 mm
// off their fits all along the tube; with one, only those at the clamps are. The window pairs grow
// as its square (780 at 40 rings, each a few 3 x 3 products when a step needs it).
constexpr int kMostBands = 64;
// The most of the surface's points a search of the bands no fit vouches for may take: beyond a
// quarter, it costs about what a search of the whole surface does, and a list rebuilt where the
// walls are now will serve the next steps.
constexpr double kMostSearched = 0.25;

// A pseudo-inverse of a spread: a flat or straight set of points fits no motion across itself (any
// fit is a valid bound; this one is the smallest).
Eigen::Matrix3d PseudoInverse(const Eigen::Matrix3d& spread) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(spread);
    const Eigen::Vector3d values = eigen.eigenvalues();
    Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
        if (values[k] > 1e-12 * values.cwiseAbs().maxCoeff()) inverse[k] = 1 / values[k];
    return eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
}

// A lower bound along a straight move on something bounded below by `start` at its start and `end`
// at its end, and changing by at most `change` over the whole move: at a fraction t of the way it
// is at least start - t change and end - (1 - t) change; the least over t of the larger of the two.
double LowestAlong(double start, double end, double change) {
    if (!(change > 0)) return std::min(start, end);
    const double t = std::clamp((start - end + change) / (2 * change), 0.0, 1.0);
    return std::max(start - t * change, end - (1 - t) * change);
}

// The smallest singular value of a 3 x 3 matrix, from below: the square root of the smallest
// eigenvalue of m^T m, less what its closed-form solution may get wrong.
double SmallestStretch(const Eigen::Matrix3d& m) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    const Eigen::Matrix3d gram = m.transpose() * m;
    eigen.computeDirect(gram, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(0.0, eigen.eigenvalues()[0] - 1e-9 * gram.trace()));
}

// ContactList::bands and windowPairs at `built`: bands of at most kMostBands layer ranges, and every
// pair of windows, each bounded by its boxes' distance.
void BuildBands(ContactList& list, const ContactSurface& surface) {
    list.bands.clear();
    list.windowPairs.clear();
    const Positions& x = list.built;
    if (surface.layerCount == 0 || static_cast<int>(surface.layer.size()) != x.Size()) return;
    const int width = (surface.layerCount + kMostBands - 1) / kMostBands;
    list.bands.resize((surface.layerCount + width - 1) / width);
    for (int v : surface.points) list.bands[surface.layer[v] / width].vertices.push_back(v);
    for (ContactList::Band& band : list.bands) {
        band.lo = band.hi = band.centre = Eigen::Vector3d::Zero();
        band.spread = band.spreadInverse = Eigen::Matrix3d::Zero();
        if (band.vertices.empty()) continue;
        band.lo = band.hi = PointOf(x, band.vertices[0]);
        for (int v : band.vertices) {
            band.lo = band.lo.cwiseMin(PointOf(x, v));
            band.hi = band.hi.cwiseMax(PointOf(x, v));
            band.centre += PointOf(x, v);
        }
        band.centre /= double(band.vertices.size());
        for (int v : band.vertices) band.spread += (PointOf(x, v) - band.centre) * (PointOf(x, v) - band.centre).transpose();
        band.spreadInverse = PseudoInverse(band.spread);
    }
    const int count = static_cast<int>(list.bands.size());
    const auto windowBox = [&](int a, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
        lo = list.bands[a].lo, hi = list.bands[a].hi;
        if (a + 1 < count && !list.bands[a + 1].vertices.empty()) {
            lo = lo.cwiseMin(list.bands[a + 1].lo);
            hi = hi.cwiseMax(list.bands[a + 1].hi);
        }
    };
    for (int a = 0; a < count; ++a)
        for (int b = a; b < count; ++b) {
            ContactList::WindowPair w;
            w.bands = {a, a + 1 < count ? a + 1 : -1, b > a + 1 ? b : -1, b + 1 > a + 1 && b + 1 < count ? b + 1 : -1};
            double n = 0;
            w.centre.setZero();
            for (int k : w.bands)
                if (k >= 0) {
                    n += double(list.bands[k].vertices.size());
                    w.centre += double(list.bands[k].vertices.size()) * list.bands[k].centre;
                }
            if (n == 0) continue;
            w.centre /= n;
            Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
            for (int k : w.bands)
                if (k >= 0) {
                    const Eigen::Vector3d d = list.bands[k].centre - w.centre;
                    spread += list.bands[k].spread + double(list.bands[k].vertices.size()) * d * d.transpose();
                }
            w.spreadInverse = PseudoInverse(spread);
            Eigen::Vector3d loA, hiA, loB, hiB;
            windowBox(a, loA, hiA);
            windowBox(b, loB, hiB);
            const double apart = (loA - hiB).cwiseMax(loB - hiA).cwiseMax(0.0).norm();
            w.distanceMm = std::max(list.clearanceMm, apart);
            list.windowPairs.push_back(w);
        }
}

using BandFit = ContactList::BandFit;
BandFit FitBand(const ContactList::Band& band, const Positions& built, const Positions& x) {
    BandFit f;
    if (band.vertices.empty()) return f;
    for (int v : band.vertices) {
        const Eigen::Vector3d u = PointOf(x, v) - PointOf(built, v);
        f.mean += u;
        f.moveSpread += u * (PointOf(built, v) - band.centre).transpose();
    }
    f.mean /= double(band.vertices.size());
    f.strain = f.moveSpread * band.spreadInverse;
    double residual = 0, largest = 0;
    for (int v : band.vertices) {
        const Eigen::Vector3d u = PointOf(x, v) - PointOf(built, v);
        residual = std::max(residual, (u - f.mean - f.strain * (PointOf(built, v) - band.centre)).squaredNorm());
        largest = std::max(largest, u.squaredNorm());
    }
    f.residualMm = std::sqrt(residual);
    f.largestMoveMm = std::sqrt(largest);
    return f;
}

// A pair of windows' affine fit from its bands' (the same least squares over their vertices), and
// how far any vertex of it can be from the fit: a band's own residual, plus how far the two fits
// part over the band's box (an affine difference is largest at a corner).
struct WindowPairFit {
    Eigen::Matrix3d strain;
    Eigen::Vector3d mean;
    double residualMm = 0;
};
WindowPairFit FitWindowPair(const ContactList& list, const ContactList::WindowPair& w, const std::vector<BandFit>& fits) {
    Eigen::Matrix3d moveSpread = Eigen::Matrix3d::Zero();
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    double n = 0;
    for (int k : w.bands)
        if (k >= 0) {
            const double m = double(list.bands[k].vertices.size());
            moveSpread += fits[k].moveSpread + m * fits[k].mean * (list.bands[k].centre - w.centre).transpose();
            mean += m * fits[k].mean;
            n += m;
        }
    mean /= n;
    WindowPairFit f;
    f.mean = mean;
    f.strain = moveSpread * w.spreadInverse;
    for (int k : w.bands) {
        if (k < 0 || list.bands[k].vertices.empty()) continue;
        const ContactList::Band& band = list.bands[k];
        double parting = 0;
        for (int corner = 0; corner < 8; ++corner) {
            const Eigen::Vector3d c((corner & 1) ? band.hi.x() : band.lo.x(), (corner & 2) ? band.hi.y() : band.lo.y(),
                                    (corner & 4) ? band.hi.z() : band.lo.z());
            parting = std::max(parting, (fits[k].mean + fits[k].strain * (c - band.centre) - mean - f.strain * (c - w.centre)).squaredNorm());
        }
        f.residualMm = std::max(f.residualMm, fits[k].residualMm + std::sqrt(parting));
    }
    return f;
}
// The same fit's residual taken vertex by vertex: tighter, and dearer.
double ExactResidual(const ContactList& list, const ContactList::WindowPair& w, const WindowPairFit& fit, const Positions& x) {
    double residual = 0;
    for (int k : w.bands)
        if (k >= 0)
            for (int v : list.bands[k].vertices)
                residual = std::max(residual, (PointOf(x, v) - PointOf(list.built, v) - fit.mean - fit.strain * (PointOf(list.built, v) - w.centre)).squaredNorm());
    return std::sqrt(residual);
}
}  // namespace

double ContactList::ClearanceAt(const Positions& x) const { return BoundAt(x).clearanceMm; }

ContactList::StateBound& ContactList::BoundAt(const Positions& x) const {
    static_assert(std::tuple_size_v<decltype(recent)> == 2, "the one not just used is the next to go");
    for (std::size_t k = 0; k < recent.size(); ++k)
        if (recent[k].at.Size() > 0 && recent[k].at == x) {
            recentNext = static_cast<int>(1 - k);  // the other one goes first: a move's two ends stay
            return recent[k];
        }
    StateBound& r = recent[recentNext];
    recentNext = (recentNext + 1) % static_cast<int>(recent.size());
    r.at = x;
    r.fits.clear();
    r.clearanceMm = UncachedClearanceAt(x);
    return r;
}

const std::vector<ContactList::BandFit>& ContactList::BandFitsAt(const Positions& x) const {
    StateBound& r = BoundAt(x);
    if (r.fits.size() != bands.size()) {
        r.fits.resize(bands.size());
        for (std::size_t k = 0; k < bands.size(); ++k) r.fits[k] = FitBand(bands[k], built, x);
    }
    return r.fits;
}

double ContactList::UncachedClearanceAt(const Positions& x) const {
    constexpr double kNone = -std::numeric_limits<double>::infinity();
    const int n = x.Size();
    if (built.Size() != n || n == 0) return kNone;
    // The moves u = x - built, and the least-squares affine motion u ~ A (built - c) + b.
    const auto move = [&](int v) -> Eigen::Vector3d { return {x.x[v] - built.x[v], x.y[v] - built.y[v], x.z[v] - built.z[v]}; };
    const auto offset = [&](int v) -> Eigen::Vector3d { return Eigen::Vector3d(built.x[v], built.y[v], built.z[v]) - builtCentre; };
    Eigen::Vector3d meanMove = Eigen::Vector3d::Zero();
    Eigen::Matrix3d moveSpread = Eigen::Matrix3d::Zero();  // sum of u (built - c)^T
    double largest = 0;
    for (int v = 0; v < n; ++v) {
        const Eigen::Vector3d u = move(v);
        meanMove += u;
        moveSpread += u * offset(v).transpose();
        largest = std::max(largest, u.squaredNorm());
    }
    if (!std::isfinite(largest)) return kNone;
    meanMove /= n;
    const Eigen::Matrix3d strain = moveSpread * builtSpreadInverse;
    double leftOver = 0;
    for (int v = 0; v < n; ++v) leftOver = std::max(leftOver, (move(v) - strain * offset(v) - meanMove).squaredNorm());
    // Any affine map F bounds the distances: |F(p) - F(q)| >= sigma_min(F) |p - q|, and moves of at
    // most m beyond it bring two primitives at most 2 m nearer. The fitted map and the identity (the
    // plain largest move) are both bounds; the larger one holds.
    const double smallestStretch = Eigen::JacobiSVD<Eigen::Matrix3d>(Eigen::Matrix3d::Identity() + strain).singularValues()[2];
    return std::max(clearanceMm - 2 * std::sqrt(largest), smallestStretch * clearanceMm - 2 * std::sqrt(leftOver));
}


bool ContactList::StaysClear(const Positions& from, const Positions& to, double needMm) const {
    const int n = from.Size();
    if (built.Size() != n || to.Size() != n || n == 0) return false;
    // The whole surface's bound at both ends, carried along the move by its largest vertex move.
    const bool still = &from == &to;
    double largest = 0;
    if (!still)
        for (int v = 0; v < n; ++v) largest = std::max(largest, (PointOf(to, v) - PointOf(from, v)).squaredNorm());
    if (!std::isfinite(largest)) return false;
    const double start = ClearanceAt(from), end = still ? start : ClearanceAt(to);
    if (LowestAlong(start, end, 2 * std::sqrt(largest)) >= needMm) return true;
    // Band by band, but only while no wall is near another. Where walls touch, a list kept longer
    // checks steps over other pairs than a fresh one, and a collapsing tube's fold is a choice
    // between equilibria that its steps' lengths decide (a quick SV4.1 design folds to 4.76 %
    // contraction with this bound there, 6.44 % without): the lists of walls in contact are
    // rebuilt where the whole surface's bound says so.
    if (!pairs.empty() || windowPairs.empty() || !std::isfinite(start) || !std::isfinite(end)) return false;
    if (still && needMm == vouchedNeedMm && from == vouchedAt) return true;

    // Band by band. Along a straight move every vertex's move from `built` is a blend of its moves
    // at the two ends, and so is each fit: a vertex is no farther from the blended fit than the
    // larger of its two residuals, and the fit's stretch changes by at most the change of its strain.
    const std::vector<BandFit> fitsFrom = BandFitsAt(from);
    const std::vector<BandFit> fitsTo = still ? fitsFrom : BandFitsAt(to);
    std::vector<std::uint8_t> unfitted(bands.size(), 0);  // the bands of windows no fit vouches for
    std::size_t unfittedPoints = 0;
    for (const WindowPair& w : windowPairs) {
        double moved = 0;  // the largest move of a vertex in the pair of windows, at either end
        for (int k : w.bands)
            if (k >= 0) moved = std::max({moved, fitsFrom[k].largestMoveMm, fitsTo[k].largestMoveMm});
        if (w.distanceMm - 2 * moved >= needMm) continue;  // too far apart to need a fit
        WindowPairFit a = FitWindowPair(*this, w, fitsFrom), b = still ? a : FitWindowPair(*this, w, fitsTo);
        const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
        const double stretch = std::max(0.0, LowestAlong(SmallestStretch(identity + a.strain), SmallestStretch(identity + b.strain), (b.strain - a.strain).norm()));
        if (stretch * w.distanceMm - 2 * std::max(a.residualMm, b.residualMm) >= needMm) continue;
        a.residualMm = ExactResidual(*this, w, a, from);
        b.residualMm = still ? a.residualMm : ExactResidual(*this, w, b, to);
        if (!(stretch * w.distanceMm - 2 * std::max(a.residualMm, b.residualMm) >= needMm))
            for (int k : w.bands)
                if (k >= 0 && !unfitted[k]) {
                    unfitted[k] = 1;
                    unfittedPoints += bands[k].vertices.size();
                    if (!surface || double(unfittedPoints) > kMostSearched * double(surface->points.size())) return false;
                }
    }
    const bool clear = unfittedPoints == 0 || SearchedClear(unfitted, from, to, needMm);
    if (still && clear) vouchedAt = from, vouchedNeedMm = needMm;
    return clear;
}

bool ContactList::SearchedClear(const std::vector<std::uint8_t>& searchBands, const Positions& from, const Positions& to, double needMm) const {
    std::size_t searched = 0;
    for (std::size_t k = 0; k < bands.size(); ++k)
        if (searchBands[k]) searched += bands[k].vertices.size();
    if (searched == 0) return true;
    if (!surface || double(searched) > kMostSearched * double(surface->points.size())) return false;
    std::vector<std::uint8_t> only(from.Size(), 0);
    for (std::size_t k = 0; k < bands.size(); ++k)
        if (searchBands[k])
            for (int v : bands[k].vertices) only[v] = 1;
    if (&from == &to) return ContactCandidates(*surface, from, nullptr, needMm, &only).empty();
    const Positions move = MoveBetween(from, to);
    for (const ContactPair& pair : ContactCandidates(*surface, from, &move, needMm, &only)) {
        const Vector12 start = PairCoordinates(pair, from);
        if (!(SquaredDistance(pair.kind, start, nullptr, nullptr) > needMm * needMm)) return false;
        if (PairImpactTime(pair.kind, start, PairCoordinates(pair, move), needMm, 1.0) < 1.0) return false;
    }
    return true;
}

bool UpdateContactList(ContactList& list, const ContactSurface& surface, const BarrierDef& barrier, const Positions& x) {
    if (list.Covers(x)) return false;
    const auto setBuilt = [&](double clearanceMm) {
        list.built = x;
        list.surface = &surface;
        list.vouchedAt = Positions{};
        for (ContactList::StateBound& r : list.recent) r = ContactList::StateBound{};
        list.reachMm = ContactReachMm(barrier);
        list.clearanceMm = clearanceMm;
        list.builtCentre.setZero();
        for (int v = 0; v < x.Size(); ++v) list.builtCentre += Eigen::Vector3d(x.x[v], x.y[v], x.z[v]);
        list.builtCentre /= std::max(1, x.Size());
        Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
        for (int v = 0; v < x.Size(); ++v) {
            const Eigen::Vector3d r = Eigen::Vector3d(x.x[v], x.y[v], x.z[v]) - list.builtCentre;
            spread += r * r.transpose();
        }
        list.builtSpreadInverse = PseudoInverse(spread);
        BuildBands(list, surface);
    };
    // The pairs within 1.4 reaches: a wider list is rebuilt less often but puts every pair in it into
    // the Hessian's pattern (a collapsed tube: 36,000 pairs at twice the reach, where 2,000 touch).
    // The pairs left out are searched to 2 reaches (a wall's neighbours are left out to there at
    // rest, so on a wall far from contact none is found): the nearest of them sets how far the
    // walls may move before one of them could come within the reach (0.2 to 0.5 reaches).
    const double reach = ContactReachMm(barrier), search = 2 * reach;
    // At rest the surface's own query has already looked this far: when the nearest pair it found is
    // beyond the list's reach, the list is empty and that pair sets its clearance (a first list with
    // no search of its own).
    if (list.built.Size() == 0 && surface.neighbourMm >= search && surface.restClearanceMm >= kListReaches * reach && x == surface.rest) {
        setBuilt(std::min(search, surface.restClearanceMm));
        list.pairs.clear();
        list.wider.clear();
        return false;
    }
    const std::vector<ContactPair> near = ContactCandidates(surface, x, nullptr, search);
    double clearance = search;
    std::vector<ContactPair> pairs;
    list.wider.clear();
    for (const ContactPair& pair : near) {
        const double d = std::sqrt(SquaredDistance(pair.kind, PairCoordinates(pair, x), nullptr, nullptr));
        if (d < kListReaches * reach) pairs.push_back(pair);
        else clearance = std::min(clearance, d);
        if (d < kPatternReaches * reach) list.wider.push_back(pair);
    }
    setBuilt(clearance);
    if (pairs == list.pairs) return false;
    list.pairs = std::move(pairs);
    return true;
}

}  // namespace sim
