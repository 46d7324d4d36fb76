// Static equilibrium of the shell models (docs/models/shell.md section 6) and what an evaluation reports
// (section 10).
//
// [SECTION] Factorisation: 3 x 3 vertex blocks; pattern and analysis kept per thread and topology
// [SECTION] Newton: projected Hessian, steps by conjugate gradients on an earlier factor (a fresh
//           factorisation when they are slow, with a growing diagonal shift on failure),
//           backtracking line search on E, round-off guard; a trust region where the exact
//           Hessian shows negative curvature
// [SECTION] Loads: pressure steps with bisection, sealed gas, volume control, axial force
// [SECTION] Evaluation: outputs, statuses
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>

#include "sim/batch.h"
#include "sim/material_fit.h"
#include "shell/block_ldlt.h"
#include "shell/shell_problem.h"

namespace sim {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// ---------------------------------------------------------------------------------------------
// [SECTION] Factorisation
// ---------------------------------------------------------------------------------------------

struct Counters {
    int iterations = 0;
    int factorizations = 0;
};

// An LDL^T factor in vertex blocks whose symbolic analysis is done once for a pattern and reused.
class Factor {
public:
    // Factorises H (+ shift I); `places` gives each unknown's vertex block. False when a pivot is
    // not positive (for a matrix that must be positive definite) or the factorisation failed.
    bool Compute(const SparseMatrix& H, const std::vector<int>& places, double shift, bool requirePositive, Counters& counters) {
        if (!ldlt_.Analysed()) ldlt_.Analyse(H, places);
        ++counters.factorizations;
        if (!ldlt_.Factorise(H, shift)) return false;
        return !requirePositive || ldlt_.SmallestPivot() > 0;
    }
    Eigen::VectorXd Solve(const Eigen::VectorXd& b) const { return ldlt_.Solve(b); }
    double SmallestPivot() const { return ldlt_.SmallestPivot(); }
    // Negative pivots: by Sylvester's law of inertia, the number of negative eigenvalues.
    int NegativePivots() const { return ldlt_.NegativePivots(); }
    Eigen::VectorXd NegativeCurvatureDirection() const { return ldlt_.NegativeCurvatureDirection(); }

private:
    BlockLdlt ldlt_;
};

// ---------------------------------------------------------------------------------------------
// [SECTION] Newton
// ---------------------------------------------------------------------------------------------

enum class NewtonEnd {
    Converged,
    NotConverged,
    NonFinite,
    Runaway,     // the volume passed its limit: no equilibrium nearby (past the pressure maximum)
    OverBudget,  // the evaluation's Newton budget (SolverDef::newtonBudget) is spent
};

// What a solve needs that depends on the mesh's topology alone: the Hessian's pattern and the
// factors' symbolic analysis. Building and ordering the pattern costs about as much as a
// factorisation, and the evaluations a thread runs one after another (a sweep, a population) nearly
// always share one mesh, so each thread keeps the last one (docs/models/shell.md section 11). Results do not
// depend on it: every factor is computed afresh before it is read.
struct Workspace {
    // The topology: what the pattern is built from.
    std::vector<int> dofOf, anchored;
    std::vector<std::array<int, 3>> wall, caps;
    std::vector<std::array<int, 4>> hinges;
    std::vector<std::array<int, 4>> fibreCellCorners;
    int unknowns = 0, axial = -1;

    std::vector<int> places;      // each unknown's place in the factors' vertex blocks
    HessianPattern withoutContact;  // the pattern with no contact pair: what a contact list's pattern is merged into
    HessianPattern pattern;       // Newton's Hessian (projected, exact or definite, as each step needs)
    Factor factor;
    HessianPattern exactPattern;  // the exact Hessian (inertia, stiffness, volume control), factorised apart
    Factor exactFactor;           // so that Newton's last factor stays to precondition with

    explicit Workspace(const ShellProblem& p)
        : dofOf(p.dofOf), anchored(p.anchor.vertices), wall(p.wall), caps(p.caps), hinges(p.hinges), unknowns(p.unknowns), axial(p.axial),
          places(VertexBlockPlaces(p)), withoutContact(p), pattern(withoutContact), exactPattern(withoutContact) {
        for (const FibreCell& cell : p.fibreCells) fibreCellCorners.push_back(cell.vertices);
    }
    bool Fits(const ShellProblem& p) const {
        const auto sameCorners = [](const std::array<int, 4>& corners, const FibreCell& cell) { return corners == cell.vertices; };
        return unknowns == p.unknowns && axial == p.axial && dofOf == p.dofOf && anchored == p.anchor.vertices && wall == p.wall &&
               caps == p.caps && hinges == p.hinges &&
               std::equal(fibreCellCorners.begin(), fibreCellCorners.end(), p.fibreCells.begin(), p.fibreCells.end(), sameCorners);
    }
    // A new pattern for both Hessians: the factors' analysis was for the old one.
    void Use(const HessianPattern& next) {
        pattern = next;
        exactPattern = next;
        factor = Factor();
        exactFactor = Factor();
    }
};

// This thread's last workspace: taken by a solver while it runs (a solver inside another builds its own).
thread_local std::unique_ptr<Workspace> tLastWorkspace;

std::unique_ptr<Workspace> TakeWorkspace(const ShellProblem& p) {
    std::unique_ptr<Workspace> w = std::move(tLastWorkspace);
    if (w && w->Fits(p)) {
        if (!w->pattern.contactPairs.empty()) w->Use(w->withoutContact);  // the last solve's walls touched
        return w;
    }
    return std::make_unique<Workspace>(p);
}

struct Solver {
    const ShellProblem& problem;
    const SolverDef& def;
    std::unique_ptr<Workspace> workspace;
    HessianPattern& pattern;
    Factor* factor;       // Newton's: the workspace's two, swapped when the exact one is the fresher preconditioner
    HessianPattern& exactPattern;
    Factor* exactFactor;
    Counters counters;
    bool holdAxial = false;   // u is held at its current value (the blocked test)
    double forceTolerance;    // N
    EnergyTerms terms;
    // Newton's steps by preconditioned conjugate gradients (PreconditionedStep).
    static constexpr double kStepResidual = 1e-4;  // of the gradient's norm: the step's linear residual
    static constexpr int kMaxStepIterations = 30;  // then a fresh factorisation is cheaper
    bool preconditioner = false;                   // `factor` holds a positive definite factor to precondition with
    bool refresh = false;                          // the last preconditioned step was slow: factorise next time
    bool exactSteps = false;                       // Newton's steps on the exact Hessian first (see Minimise)
    bool direct = false;                           // factorise at every step (see Minimise)
    int factorAge = 0;                             // Newton steps taken since `factor` was computed
    // Trust-region steps (TrustRegionStep): the radius carries over from step to step and load to
    // load, as the curvature it was fitted to does.
    static constexpr double kFirstTrustRadius = 0.1;  // of the mean edge: the saddle escape's step
    static constexpr int kTrustTries = 10;            // radii tried from one state, each a quarter of the last
    double trustRadiusMm = 0;                         // 0: not yet needed

    Solver(const ShellProblem& p, const SolverDef& d)
        : problem(p), def(d), workspace(TakeWorkspace(p)), pattern(workspace->pattern), factor(&workspace->factor),
          exactPattern(workspace->exactPattern), exactFactor(&workspace->exactFactor) {
        forceTolerance = d.tolerance * MembraneMaterialShearModulus(p.material) * p.material.thicknessMm * p.meanEdgeMm;
        if (p.contact) {
            terms.contactList = &contactList;
            terms.contactSweep = &contactSweep;
        }
    }

    // Self-contact (docs/models/shell.md section 8). The pairs every assembly sums come from one
    // list, rebuilt when the walls have moved too far for it. The Hessian's pattern holds the
    // list's pairs and those a little beyond (ContactList::wider), and is kept while each new list
    // falls inside it: walls sliding along each other change their list at most steps, and a new
    // pattern each time meant a fresh analysis and factor (SV4.1's best: 244 new patterns, 76 now,
    // 1.45x faster). With no wall near another the list stays empty and the pattern as it is. Nor
    // does a list change the pattern while none of its pairs outside it is within the barrier's
    // reach at q (every assembly with a Hessian follows a refresh at its own q): such pairs add no
    // term, and a new pattern resets Newton's factors. A contracting wall brings points of itself
    // within the list's reach (axially compressed rings) long before any touch, and each such list
    // had made the factor denser (a McKibben muscle with contact on took twice as long, with no pair
    // ever in reach; docs/performance.md).
    ContactList contactList;
    void RefreshContact(const Eigen::VectorXd& q) {
        if (!problem.contact) return;
        Positions x;
        PositionsOf(problem, q, x);
        UpdateContactList(contactList, *problem.contact, problem.barrier, x);
        sweptFrom.resize(0);
        const auto& held = pattern.contactPairs;
        const bool outsideInReach = std::any_of(contactList.pairs.begin(), contactList.pairs.end(), [&](const ContactPair& pair) {
            return !std::binary_search(held.begin(), held.end(), pair) && InReach(pair, x, problem.barrier);
        });
        if (!outsideInReach) return;
        workspace->Use(HessianPattern(workspace->withoutContact, problem, contactList.wider));
        preconditioner = false;
        refresh = false;
        direct = false;
        factorAge = 0;
    }
    // The largest fraction of the step from q that no wall crosses (1 with contact off): continuous
    // collision detection on the straight move of every vertex. When the list cannot vouch for the
    // step, the swept query that finds the pairs to check also looks out to the barrier's reach, and
    // its pairs are kept for assemblies at states along the step (a trust-region step's trial, the
    // saddle escape's), which would otherwise each search afresh. Newton's line search asks after
    // its trial is accepted, for the accepted move.
    ContactSweep contactSweep;
    static constexpr double kSweepTolerance = 0.1;  // of the reach: how far a trial may stray from the straight move
    double ImpactFree(const Eigen::VectorXd& q, const Eigen::VectorXd& step) {
        if (!problem.contact) return 1;
        Positions from, end;
        PositionsOf(problem, q, from);
        PositionsOf(problem, q + step, end);
        const Positions move = MoveBetween(from, end);
        const double h = problem.barrier.thicknessMm;
        // When no pair left out of the list can come within a wall's thickness on the way, the
        // list's pairs are the only ones to check.
        if (contactList.StaysClear(from, end, h)) {
            double free = 1;
            for (const ContactPair& pair : contactList.pairs)
                free = std::min(free, PairImpactTime(pair.kind, PairCoordinates(pair, from), PairCoordinates(pair, move), h, free));
            return free;
        }
        if (sweptFrom.size() == q.size() && sweptStep.size() == step.size() && sweptFrom == q && sweptStep == step) return sweptFree;
        const double reach = ContactReachMm(problem.barrier), tolerance = kSweepTolerance * reach;
        sweptFree = ImpactFreeStep(*problem.contact, from, move, h, &contactSweep, reach + 2 * tolerance, tolerance);
        sweptFrom = q;
        sweptStep = step;
        return sweptFree;
    }
    // The last swept query's step and answer, while the list it was asked beside stands (a line
    // search that sweeps its step before judging it asks again after).
    Eigen::VectorXd sweptFrom, sweptStep;
    double sweptFree = 1;
    // Before a line search judges its trial q + step: when the list does not cover the trial, the
    // trial's assembly would search for its pairs and the accepted step be swept after; a step of
    // moderate length is swept first instead, and the trial's assembly takes the sweep's pairs. (A
    // run-away step, hundreds of millimetres that halving cuts back, is left to the search.)
    static constexpr double kSweepFirstReaches = 20;
    bool RunAway(double longestMoveMm) const { return !(longestMoveMm <= kSweepFirstReaches * ContactReachMm(problem.barrier)); }
    void SweepFirst(const Eigen::VectorXd& q, const Eigen::VectorXd& step, double longestMoveMm) {
        if (!problem.contact || RunAway(longestMoveMm)) return;
        Positions next;
        PositionsOf(problem, q + step, next);
        if (!contactList.Covers(next)) ImpactFree(q, step);
    }
    // True when a trial at `next` can be judged without its contact pairs and is rejected: the
    // barrier only adds energy, so a trial whose other terms already miss `bound` misses it with
    // the barrier too. Asked only where the trial's assembly would otherwise search the whole wall
    // for its pairs (no list or sweep covers it): a run-away step's halvings each did, and most of
    // them are rejected (8 of the 10 such searches of the S5.4F shape's evaluation). The margin, far
    // above a compensated sum's rounding, keeps every verdict the whole energy's. Only a run-away
    // step (its largest coordinate move, longestMoveMm, beyond the sweep-first length) or a halved
    // one is judged so: a step of moderate length is mostly taken, and the assembly without contact
    // would be spent on it for nothing.
    bool RejectedWithoutContact(const Eigen::VectorXd& next, double longestMoveMm, bool halved, const LoadTerms& load, double bound) {
        if (!problem.contact || !(halved || RunAway(longestMoveMm))) return false;
        Positions x;
        PositionsOf(problem, next, x);
        if (contactList.Covers(x) || contactSweep.Covers(x)) return false;
        EnergyTerms withoutContact = terms;
        withoutContact.contact = false;
        const double energy = AssembleEnergy(problem, next, load, withoutContact, false, nullptr, HessianKind::Projected).energy;
        return !(energy <= bound + 1e-9 * (1 + std::fabs(bound)));
    }
    ~Solver() { tLastWorkspace = std::move(workspace); }
    // Counts one Newton iteration; true (and overBudget) when the evaluation's budget is already spent.
    // Every stage's Newton loops spend from the one budget, so no design costs more than it allows.
    bool overBudget = false;
    bool SpendIteration() {
        if (def.newtonBudget > 0 && counters.iterations >= def.newtonBudget) overBudget = true;
        else ++counters.iterations;
        return overBudget;
    }
    Solver(const Solver&) = delete;
    Solver& operator=(const Solver&) = delete;

    // The largest force on a free vertex (and on the top clamp, unless held).
    double LargestForce(const Eigen::VectorXd& g) const {
        double largest = 0;
        for (int v = 0; v < problem.vertexCount(); ++v) {
            double sum = 0;
            for (int c = 0; c < 3; ++c) {
                const int d = problem.dofOf[3 * v + c];
                if (d >= 0) sum += g[d] * g[d];
            }
            largest = std::max(largest, std::sqrt(sum));
        }
        if (problem.axial >= 0 && !holdAxial) largest = std::max(largest, std::fabs(g[problem.axial]));
        if (problem.twist >= 0) largest = std::max(largest, std::fabs(g[problem.twist]) / problem.twistLeverMm);  // torque as a force at the clamp
        for (int k = 0; k < 2; ++k) {  // tip free: the lateral force, and the tilting moment as a force at the clamp
            if (problem.lateral[k] >= 0) largest = std::max(largest, std::fabs(g[problem.lateral[k]]));
            if (problem.tilt[k] >= 0) largest = std::max(largest, std::fabs(g[problem.tilt[k]]) / problem.twistLeverMm);
        }
        return largest;
    }

    void HoldGradient(Eigen::VectorXd& g) const {
        if (holdAxial && problem.axial >= 0) g[problem.axial] = 0;
    }
    void HoldMatrix(SparseMatrix& H) const {
        if (!holdAxial || problem.axial < 0) return;
        // Dirichlet by elimination: the held unknown's row and column become the identity.
        for (int col = 0; col < H.outerSize(); ++col)
            for (SparseMatrix::InnerIterator it(H, col); it; ++it)
                if (it.row() == problem.axial || it.col() == problem.axial) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
    }

    // (H + c w w^T) v: the sealed gas's term beside the sparse matrix, never formed.
    static Eigen::VectorXd WithRankOne(const SparseMatrix& H, double c, const Eigen::VectorXd& w, const Eigen::VectorXd& v) {
        Eigen::VectorXd Hv = H * v;
        if (c != 0) Hv += (c * w.dot(v)) * w;
        return Hv;
    }

    // Solves (H + c w w^T) x = b by Sherman-Morrison on the sparse factor (the sealed gas's term).
    Eigen::VectorXd SolveWithRankOne(const Eigen::VectorXd& b, double c, const Eigen::VectorXd& w) const {
        Eigen::VectorXd x = factor->Solve(b);
        if (c == 0) return x;
        const Eigen::VectorXd y = factor->Solve(w);
        return x - (c * w.dot(x) / (1 + c * w.dot(y))) * y;
    }

    // The Newton step by conjugate gradients on (H + c w w^T) s = -g, preconditioned by `factor`, the
    // factorisation of an earlier (nearby) state's matrix: a factorisation costs about 35
    // back-substitutions, and a factor a few Newton iterations or a load step old still clusters the
    // spectrum tightly. Solved, or why not; `used` counts the iterations.
    enum class Linear { Solved, Indefinite, Slow, NonFinite };  // Indefinite: negative curvature met; Slow: iterations ran out
    Linear PreconditionedStep(const SparseMatrix& H, double c, const Eigen::VectorXd& w, const Eigen::VectorXd& g, Eigen::VectorXd& step, int* used,
                            int maxIterations = kMaxStepIterations) {
        step = Eigen::VectorXd::Zero(g.size());
        Eigen::VectorXd r = -g;
        Eigen::VectorXd z = factor->Solve(r);
        Eigen::VectorXd p = z, Ap;
        double rz = r.dot(z);
        // Relative to the gradient, but never below a tenth of the convergence tolerance: the step
        // that ends a solve needs no more than that.
        const double target = std::max(kStepResidual * g.norm(), 0.1 * forceTolerance);
        for (int k = 1; k <= maxIterations; ++k) {
            *used = k;
            Ap = WithRankOne(H, c, w, p);
            const double curvature = p.dot(Ap);
            if (!(curvature > 0) || !(rz > 0)) return Linear::Indefinite;
            const double alpha = rz / curvature;
            step += alpha * p;
            r -= alpha * Ap;
            if (r.norm() <= target) return step.allFinite() ? Linear::Solved : Linear::NonFinite;
            z = factor->Solve(r);
            const double next = r.dot(z);
            p = z + (next / rz) * p;
            rz = next;
        }
        return Linear::Slow;
    }
    // Steihaug and Toint's truncated conjugate gradients on the model m(s) = g.s + s.(H + c w w^T)s / 2
    // within |s| <= radius, preconditioned by `factor`: conjugate gradients until the step leaves the
    // region or meets negative curvature, then on to the boundary. Every iterate lowers the model, so
    // the step is one of descent; `predicted` is the model's decrease (> 0).
    Eigen::VectorXd TruncatedStep(const SparseMatrix& H, double c, const Eigen::VectorXd& w, const Eigen::VectorXd& g, double radius,
                                  double* predicted) const {
        Eigen::VectorXd s = Eigen::VectorXd::Zero(g.size());
        Eigen::VectorXd r = -g;
        Eigen::VectorXd z = factor->Solve(r);
        Eigen::VectorXd p = z, Ap;
        double rz = r.dot(z);
        const double target = std::max(kStepResidual * g.norm(), 0.1 * forceTolerance);
        // s + tau p on the boundary, tau >= 0.
        auto toBoundary = [&] {
            const double a = p.squaredNorm(), b = s.dot(p), outside = s.squaredNorm() - radius * radius;
            s += ((-b + std::sqrt(b * b - a * outside)) / a) * p;
        };
        for (int k = 1; k <= kMaxStepIterations; ++k) {
            Ap = WithRankOne(H, c, w, p);
            const double curvature = p.dot(Ap);
            if (!(curvature > 0)) {
                toBoundary();
                break;
            }
            const double alpha = rz / curvature;
            if ((s + alpha * p).norm() >= radius) {
                toBoundary();
                break;
            }
            s += alpha * p;
            r -= alpha * Ap;
            if (r.norm() <= target) break;
            z = factor->Solve(r);
            const double next = r.dot(z);
            p = z + (next / rz) * p;
            rz = next;
        }
        *predicted = -(g.dot(s) + 0.5 * s.dot(WithRankOne(H, c, w, s)));
        return s;
    }

    // A trust-region step from q on the exact Hessian H that has shown negative curvature: Newton's
    // steps on the projected Hessian (positive definite by construction) walk off a saddle at a
    // fixed ratio per step (1.5 on a fibre design: 25 iterations, each with a fresh factor), and the
    // unstable path curves within a tenth of an edge, so no straight step along the negative
    // curvature serves. Here the radius grows while the model predicts the energy well and shrinks
    // when it does not. True with the step and its state (energy and gradient assembled) when one
    // lowered E; false after kTrustTries radii (the caller's other steps then stand).
    bool TrustRegionStep(const Eigen::VectorXd& q, const LoadTerms& load, const EnergyResult& r, double c, const Eigen::VectorXd& w,
                         const SparseMatrix& H, Eigen::VectorXd& step, EnergyResult& reached) {
        if (trustRadiusMm == 0) trustRadiusMm = kFirstTrustRadius * problem.meanEdgeMm;
        for (int attempt = 0; attempt < kTrustTries; ++attempt) {
            double predicted = 0;
            Eigen::VectorXd s = TruncatedStep(H, c, w, r.gradient, trustRadiusMm, &predicted);
            if (!s.allFinite() || !(predicted > 0)) return false;
            if (const double free = ImpactFree(q, s); free < 1) {  // a wall in the way: as far as it allows
                s *= free;
                predicted = -(r.gradient.dot(s) + 0.5 * s.dot(WithRankOne(H, c, w, s)));
                if (!(predicted > 0)) return false;
            }
            EnergyResult trial = AssembleEnergy(problem, q + s, load, terms, true, nullptr, HessianKind::Projected);
            const double agreement = (r.energy - trial.energy) / predicted;  // actual decrease / predicted
            const bool onBoundary = s.norm() > 0.99 * trustRadiusMm;
            if (!(agreement >= 0.25)) trustRadiusMm *= 0.25;  // NaN too
            else if (agreement > 0.75 && onBoundary) trustRadiusMm *= 2;
            if (std::isfinite(trial.energy) && trial.gradient.allFinite() && agreement > 1e-4) {
                step = std::move(s);
                reached = std::move(trial);
                return true;
            }
        }
        return false;
    }

    // A step from a fresh factorisation of H (+ the gas's rank-one term): a descent direction, or
    // empty. When H is not definite, the pressure's part is left out, which is positive
    // semi-definite by construction; a tiny growing shift takes care of what is singular.
    Eigen::VectorXd FactorisedStep(const Eigen::VectorXd& q, const LoadTerms& load, const EnergyResult& r, double gasTerm, const Eigen::VectorXd& w,
                                   SparseMatrix& H, bool definite) {
        Eigen::VectorXd step;
        double shift = 0;
        for (int attempt = 0; attempt < 12; ++attempt) {
            preconditioner = factor->Compute(H, workspace->places, shift, true, counters);
            factorAge = 0;
            if (preconditioner) {
                step = -SolveWithRankOne(r.gradient, gasTerm, w);
                if (step.allFinite() && step.dot(r.gradient) < 0) return step;
            }
            if (!definite) {
                definite = true;
                AssembleEnergy(problem, q, load, terms, false, &pattern, HessianKind::Definite);  // H is pattern.matrix
                HoldMatrix(H);
                continue;
            }
            const double scale = H.diagonal().cwiseAbs().maxCoeff();
            shift = shift == 0 ? 1e-10 * scale : 10 * shift;
        }
        return Eigen::VectorXd();
    }

    // Minimises the total energy at `load` from q (in place), in at most `maxIterations` iterations
    // (def.maxIterations when 0); Runaway once the volume passes `volumeLimit` or falls below `volumeFloor`.
    NewtonEnd Minimise(Eigen::VectorXd& q, const LoadTerms& load, double volumeLimit = std::numeric_limits<double>::infinity(),
                       double volumeFloor = -std::numeric_limits<double>::infinity(), int maxIterations = 0) {
        // The gradient at q; the Hessian is assembled only when a step is to be taken from q. The
        // contact list first: the assembly would otherwise search for its pairs, and the list
        // search again at the first step.
        RefreshContact(q);
        EnergyResult r = AssembleEnergy(problem, q, load, terms, true, nullptr, HessianKind::Projected);
        for (int iteration = 0; iteration < (maxIterations > 0 ? maxIterations : def.maxIterations); ++iteration) {
            if (SpendIteration()) return NewtonEnd::OverBudget;
            if (!std::isfinite(r.energy) || !r.gradient.allFinite()) return NewtonEnd::NonFinite;
            if (r.volume > volumeLimit || r.volume < volumeFloor) return NewtonEnd::Runaway;
            HoldGradient(r.gradient);
            if (LargestForce(r.gradient) < forceTolerance) return NewtonEnd::Converged;
            RefreshContact(q);
            const double gasTerm = load.gasConstant > 0 ? load.gasConstant / (r.volume * r.volume) : 0;
            Eigen::VectorXd w = r.volumeGradient;
            HoldGradient(w);
            // Newton's step, by conjugate gradients on an earlier factor when there is one, else (or
            // when they are slow) from a fresh factorisation. On the projected Hessian (elastic parts
            // positive semi-definite by construction, the pressure's exact), until a whole step shows
            // it converging linearly: it clamps compressed membrane parts and leaves out the hinges'
            // curvature term, and on curved or wrinkled walls needs 100-1,800 iterations where the
            // exact one needs 30-70. From then on the exact Hessian first: where conjugate gradients
            // meet negative curvature on it (a saddle, a buckle), a trust-region step on it; the
            // projected one's when that fails, or when the exact one's are slow.
            Eigen::VectorXd step;
            EnergyResult trusted;    // a trust-region step's state, energy and gradient assembled
            bool trustStep = false;  // step is a trust-region step: taken whole, no line search
            bool projected = false;       // pattern.matrix holds the projected Hessian at q
            bool exactAssembled = false;  // ... or the exact one
            auto assemble = [&](HessianKind kind) {
                AssembleEnergy(problem, q, load, terms, false, &pattern, kind);
                HoldMatrix(pattern.matrix);
                projected = kind == HessianKind::Projected;
                exactAssembled = kind == HessianKind::Exact;
            };
            if (!preconditioner) {
                // The solve's first factorisation: of the Hessian without the pressure's part. From
                // the rest state the whole one is rarely definite, and a factorisation that fails
                // costs as much as one that succeeds. It preconditions the whole Hessian, or gives
                // the step itself.
                assemble(HessianKind::Projected);
                AssembleEnergy(problem, q, load, terms, false, &exactPattern, HessianKind::Definite);
                HoldMatrix(exactPattern.matrix);
                const Eigen::VectorXd fallback = FactorisedStep(q, load, r, gasTerm, w, exactPattern.matrix, true);
                int used = 0;
                if (preconditioner && !(PreconditionedStep(pattern.matrix, gasTerm, w, r.gradient, step, &used) == Linear::Solved && step.dot(r.gradient) < 0))
                    step = fallback;
                refresh = used > kMaxStepIterations / 2;
            } else if (!refresh && !direct) {
                int used = 0;
                for (HessianKind kind : {HessianKind::Exact, HessianKind::Projected}) {
                    if (kind == HessianKind::Exact && !exactSteps) continue;
                    assemble(kind);
                    const Linear end = PreconditionedStep(pattern.matrix, gasTerm, w, r.gradient, step, &used);
                    if (end == Linear::Solved && step.dot(r.gradient) < 0) break;
                    step.resize(0);
                    if (kind == HessianKind::Exact && end == Linear::Indefinite &&
                        (trustStep = TrustRegionStep(q, load, r, gasTerm, w, pattern.matrix, step, trusted)))
                        break;
                    if (end != Linear::Indefinite) break;  // too slow (or not finite): the projected one would be too
                }
                refresh = step.size() == 0 || used > kMaxStepIterations / 2;
                // Not even a factor one step old preconditions this matrix: far from equilibrium,
                // with threads going taut and slack, it changes faster than a factor pays back.
                // Factorise at every step until Newton settles.
                if (step.size() == 0 && factorAge <= 1) direct = true;
            }
            if (step.size() == 0 && exactSteps) {
                // Exact steps want a fresh factor: of the exact Hessian itself when it is positive
                // definite (near a stable state it mostly is). Its step is Newton's own, and its
                // factor preconditions the next steps better than the projected one's would; one
                // assembly and no conjugate gradients instead of two and up to ten.
                refresh = false;
                if (!exactAssembled) assemble(HessianKind::Exact);
                preconditioner = factor->Compute(pattern.matrix, workspace->places, 0, true, counters);
                factorAge = 0;
                if (preconditioner) {
                    Eigen::VectorXd exact = -SolveWithRankOne(r.gradient, gasTerm, w);
                    if (exact.allFinite() && exact.dot(r.gradient) < 0) step = std::move(exact);
                }
            }
            if (step.size() == 0) {
                refresh = false;
                if (!projected) assemble(HessianKind::Projected);
                step = FactorisedStep(q, load, r, gasTerm, w, pattern.matrix, false);
                // Exact steps: the fresh factor of the projected Hessian preconditions the exact one
                // at the same state, for a few iterations at most; else the projected step stands.
                if (exactSteps && step.size() != 0 && preconditioner) {
                    assemble(HessianKind::Exact);
                    Eigen::VectorXd exact;
                    int used = 0;
                    if (PreconditionedStep(pattern.matrix, gasTerm, w, r.gradient, exact, &used, kMaxStepIterations / 3) == Linear::Solved &&
                        exact.dot(r.gradient) < 0)
                        step = std::move(exact);
                }
            }
            if (step.size() == 0) return NewtonEnd::NotConverged;
            // Backtracking on E (a trust-region step has been judged already). When the predicted
            // decrease is below round-off, energy can no longer judge the step: take it whole (a
            // clamped tube would otherwise stall near 5e-10).
            const double lastGradientNorm = r.gradient.norm();  // held
            const double slope = step.dot(r.gradient);
            const bool roundOff = std::fabs(slope) < 1e-13 * std::max(1.0, std::fabs(r.energy));
            // No step passes a wall through another: the step the energy accepts is cut back to
            // the first contact on its way, and judged again there. (Checking the accepted move,
            // not the whole step first, keeps the cost of a run-away step, hundreds of millimetres
            // that the halving cuts to a few, from a sweep over the whole tube; where no wall is in
            // the way the steps are those of contact off.)
            double alpha = 1;
            Eigen::VectorXd next;
            const double stepLongest = problem.contact ? step.lpNorm<Eigen::Infinity>() : 0;  // the trials ask RejectedWithoutContact
            bool accepted = trustStep;
            if (trustStep) {
                next = q + step;
                r = std::move(trusted);
            }
            for (int halving = 0; halving < 40 && !accepted; ++halving) {
                next = q + alpha * step;
                if (halving == 0) SweepFirst(q, step, stepLongest);  // alpha is 1 here
                if (!roundOff && RejectedWithoutContact(next, alpha * stepLongest, halving > 0, load, r.energy + 1e-4 * alpha * slope)) {
                    alpha *= 0.5;
                    continue;
                }
                // With the gradient: the next iteration's (most steps are taken whole).
                EnergyResult trial = AssembleEnergy(problem, next, load, terms, true, nullptr, HessianKind::Projected);
                if (roundOff || (std::isfinite(trial.energy) && trial.energy <= r.energy + 1e-4 * alpha * slope)) {
                    if (const double free = ImpactFree(q, alpha * step); free < 1) {
                        alpha *= free;
                        continue;
                    }
                    r = std::move(trial);
                    accepted = true;
                    break;
                }
                alpha *= 0.5;
            }
            if (!accepted) return NewtonEnd::NotConverged;
            // A whole step that left more than a quarter of the force: the projected Hessian is
            // converging linearly; exact steps from here on (for the rest of the evaluation).
            HoldGradient(r.gradient);
            if (alpha == 1 && !exactSteps) exactSteps = r.gradient.norm() > 0.25 * lastGradientNorm;
            // Newton settled (a whole step took away nine tenths of the force): preconditioned steps again.
            if (direct && alpha == 1 && r.gradient.norm() < 0.1 * lastGradientNorm) direct = false;
            ++factorAge;
            const double moved = (alpha * step).lpNorm<Eigen::Infinity>();
            const double largest = (next - UnknownsOf(problem, problem.rest)).lpNorm<Eigen::Infinity>();
            q = std::move(next);
            if (moved < 1e-12 * std::max(largest, problem.meanEdgeMm)) return NewtonEnd::Converged;
            // Walls in contact: a pair's distance changes formula where its closest points pass from
            // a triangle's inside to an edge, and its Hessian jumps there, so Newton can cycle about
            // such a state with a force left above the tolerance (steps of 2e-7 mm, 3e-8 N on a
            // collapsed tube). Converged, as IPC judges it, by the step: one that energy can no
            // longer judge and that moves no vertex a millionth of an edge.
            if (roundOff && r.contactEnergy > 0 && moved < 1e-6 * problem.meanEdgeMm) return NewtonEnd::Converged;
        }
        return NewtonEnd::NotConverged;
    }

    // Bordered Newton on (q, p) for a prescribed volume: the gradient vanishes and V = target.
    NewtonEnd AtVolume(Eigen::VectorXd& q, double& p, double target, const LoadTerms& ends = {}) {
        for (int iteration = 0; iteration < def.maxIterations; ++iteration) {
            LoadTerms l = ends;  // the force and torque on the top clamp
            l.pressure = p;
            if (SpendIteration()) return NewtonEnd::OverBudget;
            RefreshContact(q);
            EnergyResult r = AssembleEnergy(problem, q, l, terms, true, &exactPattern, HessianKind::Exact);
            if (!r.gradient.allFinite() || !std::isfinite(r.volume)) return NewtonEnd::NonFinite;
            HoldGradient(r.gradient);
            HoldMatrix(exactPattern.matrix);
            const double volumeError = r.volume - target;
            if (LargestForce(r.gradient) < forceTolerance && std::fabs(volumeError) < 1e-10 * problem.restVolume) return NewtonEnd::Converged;
            if (!exactFactor->Compute(exactPattern.matrix, workspace->places, 0, false, counters)) return NewtonEnd::NotConverged;
            Eigen::VectorXd w = r.volumeGradient;
            HoldGradient(w);
            // [K -w; -w^T 0][dq; dp] = -[g; -(V - target)]: with a = K^-1 g, b = K^-1 w,
            // dq = -a + dp b and w^T dq = -(V - target).
            const Eigen::VectorXd a = exactFactor->Solve(r.gradient), b = exactFactor->Solve(w);
            const double dp = (w.dot(a) - volumeError) / w.dot(b);
            const Eigen::VectorXd dq = -a + dp * b;
            if (!dq.allFinite() || !std::isfinite(dp)) return NewtonEnd::NonFinite;
            const double free = ImpactFree(q, dq);
            q += free * dq;
            p += free * dp;
        }
        return NewtonEnd::NotConverged;
    }

    // Makes the exact Hessian's factor (just computed, positive definite) Newton's preconditioner: it
    // is fresher than Newton's own.
    void PreconditionWithExact() {
        if (!(exactFactor->SmallestPivot() > 0)) return;
        std::swap(factor, exactFactor);
        preconditioner = true;
        refresh = false;
        direct = false;
        factorAge = 0;
    }

    // The exact Hessian at q, factorised (indefinite allowed); its negative pivots.
    int ExactInertia(const Eigen::VectorXd& q, const LoadTerms& load, EnergyResult* r) {
        RefreshContact(q);
        *r = AssembleEnergy(problem, q, load, terms, true, &exactPattern, HessianKind::Exact);
        HoldGradient(r->gradient);
        HoldMatrix(exactPattern.matrix);
        if (!exactFactor->Compute(exactPattern.matrix, workspace->places, 0, false, counters)) return -1;
        return exactFactor->NegativePivots();
    }
    // Is the equilibrium q stable? The count of directions in which it is not (the exact Hessian's
    // negative pivots, each confirmed; below), with its factor left in exactFactor; -1 when it
    // cannot be factorised. Newton's steps find stationary points, and on a wavy wall they can end
    // on a saddle beside a stable state at the same load: then step down along the negative
    // curvature and minimise again, with a load step's budget (def.maxIterations): a smaller one of
    // its own made the verdict depend on it (a fibre design whose stable state lies 100 iterations
    // away was a limit point with 50). Newton may end on another saddle on the way down; it is
    // stepped off in turn, kEscapes times at most. A stable state within volumeLimit replaces q
    // (then *escaped, if given); otherwise q stays, with its own inertia.
    static constexpr int kEscapes = 3;
    static constexpr int kInverseIterations = 8;  // a back-substitution each
    static constexpr double kConfirmedCurvature = 1e-9;  // of the Hessian's median diagonal entry
    int StableState(Eigen::VectorXd& q, const LoadTerms& load, double volumeLimit, EnergyResult* exact, bool* escaped = nullptr) {
        if (escaped) *escaped = false;
        int negative = ExactInertia(q, load, exact);
        if (negative <= 0) return negative;  // most states: nothing to copy or confirm
        Eigen::VectorXd from = q;  // the state examined (its factor and matrix in exactFactor, exactPattern)
        EnergyResult fromExact = *exact;
        bool moved = false;        // exactFactor is no longer q's
        for (int escape = 0; negative > 0; ++escape) {
            Eigen::VectorXd down = exactFactor->NegativeCurvatureDirection();
            HoldGradient(down);
            if (down.size() != q.size() || !down.allFinite() || !(down.lpNorm<Eigen::Infinity>() > 0)) break;
            down /= down.lpNorm<Eigen::Infinity>();
            // Unpivoted LDL^T can give a pivot near zero the wrong sign. A wall at its buckling load
            // has such pivots, and there the energy grows as a step's fourth power whichever way it
            // goes: a negative pivot counts only when a direction of negative curvature shows it.
            // The factor's own direction, spread by L^-T, may be mostly stiff modes; a few inverse
            // iterations on H turn it toward the eigenvector whose eigenvalue is nearest zero.
            const SparseMatrix& H = exactPattern.matrix;
            auto curvature = [&](const Eigen::VectorXd& d) { return d.allFinite() ? d.dot(H * d) / d.squaredNorm() : 0.0; };
            Eigen::VectorXd refined = down;
            for (int k = 0; k < kInverseIterations; ++k) {
                refined = exactFactor->Solve(refined);
                HoldGradient(refined);
                refined /= refined.lpNorm<Eigen::Infinity>();
            }
            Eigen::VectorXd diagonal = H.diagonal().cwiseAbs();  // its median: the wall's stiffness (a folded
            std::nth_element(diagonal.begin(), diagonal.begin() + diagonal.size() / 2, diagonal.end());  // triangle's can be 1e9 times that)
            if (!(std::min(curvature(down), curvature(refined)) < -kConfirmedCurvature * diagonal[diagonal.size() / 2])) {
                negative = 0;
                break;
            }
            if (escape == kEscapes) break;
            // A tenth of an edge along the factor's direction, the way the energy falls, or else the
            // other way: Newton can come down to a stable state from there too (a fibre design of
            // reproduce's part 2, +2.2 %, is found only so; not with the energy required to fall).
            down *= 0.1 * problem.meanEdgeMm;
            if (!(AssembleEnergy(problem, from + down, load, terms, false, nullptr, HessianKind::Projected).energy < fromExact.energy)) down = -down;
            Eigen::VectorXd trial = from + ImpactFree(from, down) * down;
            const NewtonEnd end = Minimise(trial, load, volumeLimit);
            Positions x;
            PositionsOf(problem, trial, x);
            if (!(end == NewtonEnd::Converged && EnclosedVolume(problem, x) <= volumeLimit)) break;  // limit: infinite for a force load
            EnergyResult reached;
            const int reachedNegative = ExactInertia(trial, load, &reached);
            moved = true;
            if (reachedNegative < 0) break;
            from = std::move(trial);
            fromExact = std::move(reached);
            negative = reachedNegative;
        }
        if (negative == 0) {
            if (escaped) *escaped = moved;
            q = std::move(from);
            *exact = std::move(fromExact);
            return 0;
        }
        return moved ? ExactInertia(q, load, exact) : negative;  // q's factor again, for what follows
    }

    // The direction in which a stable state is softest: the eigenvector of the exact Hessian's
    // smallest eigenvalue, by inverse iteration on its factor (exactFactor, positive definite) from
    // an equal move of every unknown, so the same on every run; scaled to 1 at its largest. Empty
    // when exactFactor is not positive definite.
    static constexpr int kSoftestIterations = 8;  // 2 to 30 find the same bowed state of the +/-70 deg braid
    Eigen::VectorXd SoftestDirection() {
        if (!(exactFactor->SmallestPivot() > 0)) return {};
        Eigen::VectorXd d = Eigen::VectorXd::Ones(problem.unknowns);
        HoldGradient(d);
        for (int k = 0; k < kSoftestIterations; ++k) {
            d = exactFactor->Solve(d);  // the held unknown stays 0: HoldMatrix decoupled its row and column
            const double largest = d.lpNorm<Eigen::Infinity>();
            if (!d.allFinite() || !(largest > 0)) return {};
            d /= largest;
        }
        return d;
    }
};

// ---------------------------------------------------------------------------------------------
// [SECTION] Evaluation
// ---------------------------------------------------------------------------------------------

double Contraction(const ShellProblem& p, const Eigen::VectorXd& q, double length) {
    const double u = p.axial >= 0 ? q[p.axial] : p.heldAxial;
    return (0.0 - 100 * u) / length;  // +0, not -0, when the clamp is held
}

void MaxStretchAndStress(const ShellProblem& p, const Positions& x, double* stretch, double* stress) {
    *stretch = 0;
    *stress = 0;
    for (size_t t = 0; t < p.wall.size(); ++t) {
        const PrincipalValues v = Principal(p.material, DeformationGradient(p, static_cast<int>(t), x));
        *stretch = std::max(*stretch, v.stretch[0]);
        *stress = std::max(*stress, v.stress[0]);
    }
}

// The fibres' largest and mean strain, and their mean angle to the axis over the middle third of the
// tube (away from the clamps: where a braided tube is an ideal McKibben muscle).
void FibreOutputs(const ShellProblem& p, const Positions& x, double length, ShellOutputs& out) {
    const FibreState state = FibreStates(p, x);
    if (state.stretch.empty()) return;
    double largest = -INFINITY, sum = 0, angles = 0;
    int middle = 0;
    for (size_t k = 0; k < state.stretch.size(); ++k) {
        largest = std::max(largest, state.stretch[k] - 1);
        sum += state.stretch[k] - 1;
        if (state.restHeightMm[k] >= length / 3 && state.restHeightMm[k] <= 2 * length / 3) {
            angles += state.angleDeg[k];
            ++middle;
        }
    }
    out.maxFibreStrain = largest;
    out.meanFibreStrain = sum / static_cast<double>(state.stretch.size());
    out.fibreAngleDeg = middle ? angles / middle : NAN;
}

// A state whose volume passes this multiple of the last converged one has left the load path: no
// equilibrium nearby (past the pressure maximum), or a snap through to a distant branch.
constexpr double kRunawayVolume = 3;
// Under vacuum, a converged step that loses this fraction of the rest volume at once has collapsed:
// a round tube loses about 1 % of its volume over the whole path to its collapse (0.02 % in the
// smallest step), and the step onto the collapsed branch 3 % or more.
constexpr double kCollapseDrop = 0.01;
// A long tube's ring buckling is a stable bifurcation: past it the buckled branch gives up volume
// about 50 times faster per kilopascal than the round one (R 5 mm, L 100 mm, h 1 mm: 46,000 against
// 815 mm^3/kPa), one small step at a time, with no jump and no unstable state. A converged step that
// loses volume at more than this multiple of the last step's rate has left the round branch. (The
// tangent at the last state is no reference: near the bifurcation it already sees the soft mode.)
constexpr double kCollapseCompliance = 3;


}  // namespace

namespace {
// The status a Newton solve that did not converge ends an evaluation with.
Status StatusOf(NewtonEnd end) {
    switch (end) {
        case NewtonEnd::Converged: return Status::Ok;
        case NewtonEnd::NonFinite: return Status::NonFinite;
        case NewtonEnd::OverBudget: return Status::BudgetExceeded;
        case NewtonEnd::NotConverged:
        case NewtonEnd::Runaway: break;
    }
    return Status::NotConverged;
}
}  // namespace

Status SolveStatic(const ShellProblem& problem, const LoadTerms& load, const SolverDef& def, Eigen::VectorXd& q, bool holdAxial, int* iterations) {
    Solver solver(problem, def);
    solver.holdAxial = holdAxial;
    const NewtonEnd end = solver.Minimise(q, load);
    if (iterations) *iterations = solver.counters.iterations;
    return StatusOf(end);
}

Status SolveVolume(const ShellProblem& problem, const SolverDef& def, double volume, Eigen::VectorXd& q, double& pressure, int* iterations) {
    Solver solver(problem, def);
    const NewtonEnd end = solver.AtVolume(q, pressure, volume);
    if (iterations) *iterations = solver.counters.iterations;
    return StatusOf(end);
}

namespace {

// A state's verdict on the wall's stretch: past the allowed stretch, or past where the law is stable
// (only a law with a negative higher constant can lose stability: its slopes otherwise only rise).
Status StretchStatus(const MaterialDef& m, double maxStretch, double limit) {
    if (maxStretch > limit) return Status::OverStretched;
    if ((m.c01Kpa < 0 || m.c20Kpa < 0 || m.c30Kpa < 0) && StableStretch(m, maxStretch) < maxStretch) return Status::MaterialUnstable;
    return Status::Ok;
}


// One evaluation as it passes through the stages of EvaluateShell: the tube, its solver, the state
// q and the outputs each stage writes.
struct TubeEvaluation {
    const ShellDef& def;
    const LoadDef& load;
    const ShellProblem& problem;
    ShellOutputs& out;
    Solver solver;
    Eigen::VectorXd q;
    Positions x;  // scratch: q's positions
    double length;

    TubeEvaluation(const ShellDef& d, const ShellProblem& p, ShellOutputs& o)
        : def(d), load(d.load), problem(p), out(o), solver(p, d.solver), q(UnknownsOf(p, p.rest)), length(d.geometry.lengthMm) {
        solver.holdAxial = load.kind == ShellLoad::Blocked;
    }

    // The load parameter at fraction s of the target: the pressure (or gas, or volume: stepped by
    // FollowLoadPath), with the end force and torque on the top clamp, all in proportion.
    LoadTerms LoadAt(double s) const {
        LoadTerms l;
        switch (load.kind) {
            case ShellLoad::Inflate:
            case ShellLoad::Blocked: l.pressure = s * load.pressureKpa * 1e-3; break;
            case ShellLoad::Gas: l.gasConstant = (l.atmosphere + s * load.pressureKpa * 1e-3) * problem.restVolume; break;
            case ShellLoad::Force:
            case ShellLoad::Volume: break;
        }
        if (load.kind != ShellLoad::Blocked) l.force = s * load.forceN;
        if (def.ends.twist == TwistEnd::Loaded) l.torque = s * def.ends.torqueNMm;
        return l;
    }
    // The held stroke at fraction s (the blocked test): u, mm (0 for the blocking force).
    double HeldAxialAt(double s) const { return -s * (load.strokeMm != 0 ? load.strokeMm : load.strokePercent * 1e-2 * length); }
    // The gauge pressure at fraction s of the target: a sealed gas's follows its volume (of the
    // current state q); a prescribed one is s times the target, exactly the target at s = 1.
    double GaugeKpa(double s) {
        const LoadTerms l = LoadAt(s);
        if (l.gasConstant > 0) {
            PositionsOf(problem, q, x);
            return (l.gasConstant / EnclosedVolume(problem, x) - l.atmosphere) * 1e3;
        }
        return load.kind == ShellLoad::Force ? 0.0 : s * load.pressureKpa;
    }
    // The state q with its top clamp moved to u: the free wall carried along the axis with it, each
    // free vertex by the fraction of the way from the bottom end to the top end that it stands at
    // rest (an affine stretch or compression). Moving the clamp alone crushes or pulls the ring
    // beside it by the whole move (millimetres), and Newton can come down from there into a folded
    // state (the +/-70 deg braid held at its rest length from half its stroke, 60 x 59: through
    // itself), or crawl between threads going taut and slack (a held braid's top moved 4 mm past
    // rings 1.3 mm apart: 2,000 iterations with contact off). The free vertices' unknowns are their
    // places, so the move is added to them: a zero move leaves q as it was, to the bit.
    Eigen::VectorXd StretchedTo(const Eigen::VectorXd& from, double u) const {
        // The ends: the highest vertex held at the bottom, the lowest riding on the top clamp (a
        // problem with an axial unknown has both).
        double bottom = -std::numeric_limits<double>::infinity(), top = std::numeric_limits<double>::infinity();
        for (int v = 0; v < problem.vertexCount(); ++v) {
            const int* d = &problem.dofOf[3 * v];
            if (d[2] == kAxial || d[0] == kRigid) top = std::min(top, problem.rest.z[v]);
            else if (d[2] == kFixed) bottom = std::max(bottom, problem.rest.z[v]);
        }
        Eigen::VectorXd q = from;
        const double move = u - from[problem.axial];
        for (int v = 0; v < problem.vertexCount(); ++v)
            if (const int d = problem.dofOf[3 * v + 2]; d >= 0) q[d] += move * std::clamp((problem.rest.z[v] - bottom) / (top - bottom), 0.0, 1.0);
        q[problem.axial] = u;
        return q;
    }
    // Where Newton stops as Runaway after a state of this volume (a force load has no such limit).
    double VolumeLimitAfter(double volume) const {
        return load.kind == ShellLoad::Force ? std::numeric_limits<double>::infinity() : kRunawayVolume * volume;
    }
    // One point of the curve: the state q at this pressure, under load fraction s (the force on the
    // top clamp is the held stroke's reaction under the blocked test, else the load on it).
    void Record(double pressureKpa, double s) {
        PositionsOf(problem, q, x);
        out.curvePressureKpa.push_back(pressureKpa);
        out.curveContractionPercent.push_back(Contraction(problem, q, length));
        out.curveVolumeMm3.push_back(EnclosedVolume(problem, x));
        out.curveForceN.push_back(load.kind == ShellLoad::Blocked ? AssembleEnergy(problem, q, LoadAt(s), solver.terms, true, nullptr, HessianKind::Exact).axialForce
                                                                  : LoadAt(s).force);
        out.curveTwistDeg.push_back(TwistDeg());
        out.steps.push_back(x);
    }
    // The top clamp's turn, degrees (positive: right-handed about +z).
    double TwistDeg() const { return (problem.twist >= 0 ? q[problem.twist] : problem.heldTwist) * 180 / std::numbers::pi; }
    // The load the end state is judged and measured under.
    LoadTerms FinalLoad() const {
        LoadTerms l = LoadAt(1.0);
        if (load.kind == ShellLoad::Volume) l.pressure = out.targetPressureKpa * 1e-3;
        return l;
    }
};

// How far a held state bows: the largest distance of a ring's centre (the mean of its vertices) from
// the axis, mm; 0 when straight.
double BowMm(const TubeEvaluation& t, const Positions& x) {
    const int perRing = t.def.geometry.ringVertices, rings = RingCount(t.def.geometry);
    double bow = 0;
    for (int j = 0; j < rings; ++j) {
        double cx = 0, cy = 0;
        for (int i = 0; i < perRing; ++i) {
            cx += x.x[j * perRing + i];
            cy += x.y[j * perRing + i];
        }
        bow = std::max(bow, std::hypot(cx, cy) / perRing);
    }
    return bow;
}

// A compressed held state pushed sideways (docs/models/shell.md section 12, held states). A coarse
// mesh can hold a compressed tube straight far past the load at which a finer one, and the bench,
// bow it sideways: the +/-70 deg braid held at its rest length at 3 kPa is straight (-0.172 N) and
// stable at 30 x 30, where 60 x 332 finds it bowed 25 mm (-0.041 N), and on every mesh the bowed state
// has the far lower energy. Its Hessian there is positive definite, so no inertia check sees it;
// a push does. The stable held state `held` (its exact factor in solver.exactFactor, its assembly
// in *exact) is moved SolverDef::heldPushDiameters tube diameters along its softest direction (at
// its largest; on the braid at 30 x 30, 3 mm comes back straight and 5 to 20 mm bow it) and
// minimised again: a stable state of lower energy found so replaces it, with its assembly in
// *exact. True when it did; otherwise `held` and *exact stand (exactFactor may then be another
// state's). A free top, or a tube in tension, does not bow so: those are left as they are.
bool PushCompressedHeldState(TubeEvaluation& t, Eigen::VectorXd& held, const LoadTerms& load, double volumeLimit, EnergyResult* exact) {
    if (!t.solver.holdAxial || !(exact->axialForce < 0) || !(t.def.solver.heldPushDiameters > 0)) return false;
    Eigen::VectorXd push = t.solver.SoftestDirection();
    if (push.size() == 0) return false;
    push *= t.def.solver.heldPushDiameters * 2 * t.def.geometry.radiusMm;
    Eigen::VectorXd pushed = held + t.solver.ImpactFree(held, push) * push;
    const NewtonEnd end = t.solver.Minimise(pushed, load, volumeLimit);
    // Back where it was (most pushes), or higher: no need to look at its stability.
    const auto lower = [&](double energy) { return energy < exact->energy - 1e-9 * std::fabs(exact->energy); };
    if (end != NewtonEnd::Converged || !lower(AssembleEnergy(t.problem, pushed, load, t.solver.terms, false, nullptr, HessianKind::Projected).energy))
        return false;
    EnergyResult reached;
    if (t.solver.StableState(pushed, load, volumeLimit, &reached) != 0 || !lower(reached.energy)) return false;
    PositionsOf(t.problem, pushed, t.x);
    if (t.def.solver.selfContact && SelfIntersects(t.problem, t.x)) return false;
    held = std::move(pushed);
    *exact = std::move(reached);
    return true;
}

// Solver::StableState, and then, for a held top, the push above: every held state a stage reports
// goes through here. Returns StableState's count of unstable directions; *moved (if given) says
// whether q changed.
int SettleState(TubeEvaluation& t, Eigen::VectorXd& q, const LoadTerms& load, double volumeLimit, EnergyResult* exact, bool* moved = nullptr) {
    bool escaped = false;
    const int negative = t.solver.StableState(q, load, volumeLimit, exact, &escaped);
    const bool pushed = negative == 0 && PushCompressedHeldState(t, q, load, volumeLimit, exact);
    if (moved) *moved = escaped || pushed;
    return negative;
}

// A held test's recorded point on its way to the target, pushed as its end state is
// (SettleOnStableState) when it pushes on its clamps, so that the force-pressure curve follows the
// bowed branch from where the tube bows. True when the state moved.
bool PushHeldPoint(TubeEvaluation& t, double s, double volumeLimit) {
    const LoadTerms load = t.LoadAt(s);
    if (!(AssembleEnergy(t.problem, t.q, load, t.solver.terms, true, nullptr, HessianKind::Exact).axialForce < 0)) return false;  // pulls: nothing to factorise
    EnergyResult exact;
    return t.solver.ExactInertia(t.q, load, &exact) == 0 && PushCompressedHeldState(t, t.q, load, volumeLimit, &exact);
}

// Stage: the load path in load.steps steps to the target, each point recorded on the curve. Volume
// control steps the enclosed volume; the others step the load, each step tried whole from the
// previous state and halved on failure down to 1/2^maxBisections.
Status FollowLoadPath(TubeEvaluation& t) {
    const LoadDef& load = t.load;
    ShellOutputs& out = t.out;
    Status status = Status::Ok;
    if (load.kind == ShellLoad::Volume) {
        double p = 0;
        for (int k = 1; k <= load.steps && status == Status::Ok; ++k) {
            const double target = t.problem.restVolume * (1 + (load.volumeRatio - 1) * k / load.steps);
            const NewtonEnd end = t.solver.AtVolume(t.q, p, target, t.LoadAt(double(k) / load.steps));
            if (end == NewtonEnd::Converged) t.Record(p * 1e3, double(k) / load.steps);
            else status = StatusOf(end);
        }
        out.targetPressureKpa = p * 1e3;
        return status;
    }
    double reached = 0;
    double lastVolume = t.problem.restVolume;
    // The tangent dq/dp = K^-1 dV/dq at the last converged state predicts the next one (pressure
    // loads): Newton then starts close and needs fewer iterations.
    Eigen::VectorXd tangent;
    double volumePerLoad = NAN;  // vacuum: the last step's volume change per load fraction, mm^3 (round, so far)
    const bool predict = load.kind == ShellLoad::Inflate || load.kind == ShellLoad::Blocked;
    const bool collapsing = load.kind == ShellLoad::Inflate && UnderVacuum(load);
    for (int k = 1; k <= load.steps && status == Status::Ok; ++k) {
        const double goal = double(k) / load.steps;
        double increment = goal - reached;
        const double smallest = increment / std::pow(2.0, t.def.solver.maxBisections);
        while (reached < goal - 1e-15 && status == Status::Ok) {
            const double next = std::min(goal, reached + increment);
            const bool predicted = predict && tangent.size() == t.q.size();
            auto start = [&](bool withTangent) {
                Eigen::VectorXd from = t.q;
                if (withTangent) {
                    const Eigen::VectorXd move = (next - reached) * load.pressureKpa * 1e-3 * tangent;
                    from += t.solver.ImpactFree(t.q, move) * move;
                }
                if (load.kind == ShellLoad::Blocked) {
                    // Without a tangent, the wall follows the top's move (StretchedTo).
                    const double u = t.HeldAxialAt(next);
                    if (withTangent) from[t.problem.axial] = u;
                    else from = t.StretchedTo(from, u);
                }
                return from;
            };
            Eigen::VectorXd trial = start(predicted);
            // Vacuum: a collapse is bracketed by halving the step, so a trial that is collapsing is
            // stopped as soon as it has lost that much (the smallest step may collapse in full).
            const bool beforeCollapse = collapsing && std::isnan(out.collapsePressureKpa);
            const double collapsedBelow = lastVolume - kCollapseDrop * t.problem.restVolume;
            const double floor = beforeCollapse && increment > smallest ? collapsedBelow : -std::numeric_limits<double>::infinity();
            // The smallest increment that collapses snaps through to a distant folded state, and
            // Newton can need more than a load step's iterations to get there (an SV5.2 design took
            // 300): the snap may spend the evaluation's budget, or ten load steps' without one.
            const int snapIterations = t.def.solver.newtonBudget > 0 ? t.def.solver.newtonBudget : 10 * t.def.solver.maxIterations;
            const int iterations = beforeCollapse && increment <= smallest ? snapIterations : 0;
            NewtonEnd end = t.solver.Minimise(trial, t.LoadAt(next), t.VolumeLimitAfter(lastVolume), floor, iterations);
            // A held tube bowed sideways can turn its bow about the axis at almost no cost, and the
            // tangent taken beside that direction predicts a move without bound: Newton runs away
            // from it at any increment, where from the last state it converges. The blocked test
            // tries the increment from the last state before halving it.
            if (predicted && load.kind == ShellLoad::Blocked && (end == NewtonEnd::Runaway || end == NewtonEnd::NonFinite || end == NewtonEnd::NotConverged)) {
                trial = start(false);
                end = t.solver.Minimise(trial, t.LoadAt(next), t.VolumeLimitAfter(lastVolume), floor);
            }
            if (end == NewtonEnd::OverBudget) {  // halving the step would only spend more
                status = Status::BudgetExceeded;
                break;
            }
            // Vacuum with contact off: a collapse Newton cannot follow has walls passing through
            // each other, not a pressure maximum (the self-intersection check runs as at the end).
            const auto passedThrough = [&] {
                if (!collapsing || t.problem.contact || !t.def.solver.selfContact) return false;
                PositionsOf(t.problem, trial, t.x);
                return std::isfinite(EnclosedVolume(t.problem, t.x)) && SelfIntersects(t.problem, t.x);
            };
            if (end == NewtonEnd::NonFinite && increment <= smallest) status = Status::NonFinite;
            if (end == NewtonEnd::Runaway && increment <= smallest) {
                if (passedThrough()) {
                    status = Status::SelfIntersection;
                    break;
                }
                out.limitPressureKpa = t.GaugeKpa(reached);
                status = Status::LimitPoint;
                break;
            }
            if (end == NewtonEnd::Converged) {
                PositionsOf(t.problem, trial, t.x);
                double volume = EnclosedVolume(t.problem, t.x);
                // Vacuum: a state that holds far less than the last has collapsed, and so has one
                // that is unstable (Newton follows a tube's round state past the pressure where it
                // turns unstable; StableState steps it down onto the folded one). The step is halved
                // until the collapse is bracketed within the smallest increment, and the path goes
                // on from the collapsed state.
                bool collapsed = false;
                if (beforeCollapse) {
                    EnergyResult exact;
                    bool escaped = false;
                    Eigen::VectorXd settled = trial;
                    const int negative = t.solver.StableState(settled, t.LoadAt(next), t.VolumeLimitAfter(lastVolume), &exact, &escaped);
                    const double predictedLoss = std::abs((next - reached) * volumePerLoad);
                    const bool leftRoundBranch = std::isfinite(predictedLoss) && lastVolume - volume > kCollapseCompliance * predictedLoss;
                    collapsed = negative != 0 || escaped || volume < collapsedBelow || leftRoundBranch;
                    if (collapsed && increment > smallest) {
                        increment *= 0.5;
                        continue;
                    }
                    if (escaped) {
                        trial = std::move(settled);
                        PositionsOf(t.problem, trial, t.x);
                        volume = EnclosedVolume(t.problem, t.x);
                    }
                    if (collapsed) out.collapsePressureKpa = 0.5 * (t.GaugeKpa(reached) + t.GaugeKpa(next));
                }
                // A converged state far beyond the last one has snapped through to a distant branch:
                // past the pressure maximum. (An unstable state is caught at the end, by inertia.)
                if (volume > t.VolumeLimitAfter(lastVolume)) {
                    out.limitPressureKpa = t.GaugeKpa(reached);
                    status = Status::LimitPoint;
                    break;
                }
                t.q = std::move(trial);
                if (beforeCollapse && !collapsed) volumePerLoad = (volume - lastVolume) / (next - reached);
                reached = next;
                if (load.kind == ShellLoad::Blocked && next == goal && goal < 1 && PushHeldPoint(t, next, t.VolumeLimitAfter(volume))) {
                    PositionsOf(t.problem, t.q, t.x);
                    volume = EnclosedVolume(t.problem, t.x);
                }
                lastVolume = volume;
                if (collapsed) increment = goal - reached;  // past the snap: the rest of the load step whole again
                if (predict) {
                    Eigen::VectorXd w = AssembleEnergy(t.problem, t.q, t.LoadAt(reached), t.solver.terms, true, nullptr, HessianKind::Projected).volumeGradient;
                    t.solver.HoldGradient(w);
                    // With the last Newton step's Hessian (a moment before convergence), solved as
                    // Newton's steps are; the preconditioner alone when that fails.
                    int used = 0;
                    if (!t.solver.preconditioner || t.solver.PreconditionedStep(t.solver.pattern.matrix, 0, w, -w, tangent, &used) != Solver::Linear::Solved)
                        tangent = t.solver.factor->Solve(w);
                    if (!tangent.allFinite()) tangent.resize(0);
                }
                continue;
            }
            if (increment <= smallest) {
                // Newton runs away when no equilibrium exists: past the pressure maximum.
                PositionsOf(t.problem, trial, t.x);
                const double volume = EnclosedVolume(t.problem, t.x);
                if (status == Status::Ok && passedThrough()) status = Status::SelfIntersection;
                else if (load.kind != ShellLoad::Force && (end == NewtonEnd::Runaway || !std::isfinite(volume) || volume > 2 * lastVolume)) {
                    out.limitPressureKpa = t.GaugeKpa(reached);
                    status = Status::LimitPoint;
                } else if (status == Status::Ok) {
                    status = Status::NotConverged;
                }
                break;
            }
            increment *= 0.5;
        }
        if (status == Status::Ok) t.Record(t.GaugeKpa(reached), reached);
    }
    out.targetPressureKpa = t.GaugeKpa(reached);
    return status;
}

// Stage: the exact Hessian's inertia at the end of the path tells a stable equilibrium from one past
// the pressure maximum; StableState steps off a saddle beside a stable state first, and the curve's
// last point becomes that state. Returns the exact Hessian's negative pivots (its factor stays in
// solver.exactFactor).
int SettleOnStableState(TubeEvaluation& t, const LoadTerms& finalLoad) {
    EnergyResult exact;
    if (t.load.kind == ShellLoad::Volume) return t.solver.ExactInertia(t.q, finalLoad, &exact);  // volume control holds a state past the maximum
    bool moved = false;
    const int negative = SettleState(t, t.q, finalLoad, t.VolumeLimitAfter(t.out.curveVolumeMm3.back()), &exact, &moved);
    if (moved) {
        ShellOutputs& out = t.out;
        PositionsOf(t.problem, t.q, t.x);
        out.targetPressureKpa = t.GaugeKpa(1.0);  // status ok: the path reached its target
        out.curvePressureKpa.back() = out.targetPressureKpa;
        out.curveContractionPercent.back() = Contraction(t.problem, t.q, t.length);
        out.curveVolumeMm3.back() = EnclosedVolume(t.problem, t.x);
        out.curveTwistDeg.back() = t.TwistDeg();
        if (t.load.kind == ShellLoad::Blocked)
            out.curveForceN.back() = AssembleEnergy(t.problem, t.q, finalLoad, t.solver.terms, true, nullptr, HessianKind::Exact).axialForce;
        out.steps.back() = t.x;
    }
    return negative;
}

// Stage: what the end state measures (also where the path stopped short: the pictures show it).
void Measure(TubeEvaluation& t, SimResult& result) {
    ShellOutputs& out = t.out;
    PositionsOf(t.problem, t.q, t.x);
    result.final = t.x;
    out.displacementMm = t.problem.axial >= 0 ? t.q[t.problem.axial] : 0;
    out.volumeMm3 = EnclosedVolume(t.problem, t.x);
    MaxStretchAndStress(t.problem, t.x, &out.maxStretch, &out.maxStressKpa);
    out.maxStressKpa *= 1e3;
    if (t.solver.holdAxial) out.heldBowMm = BowMm(t, t.x);  // a blocked test's end state, a held stroke's
    FibreOutputs(t.problem, t.x, t.length, out);
    if (t.problem.contact) {
        const ContactSummary contact = SummariseContact(*t.problem.contact, t.problem.barrier, t.x);
        out.contactPairs = contact.activePairs;
        out.minGapMm = contact.minGapMm;
        out.contactForceN = contact.forceN;
    }
    result.contractionPercent = Contraction(t.problem, t.q, t.length);
    // The top clamp's turn (sliding ends have none: the anchor holds their rotation), and the torque
    // on it: the one that holds it, or the one that turns it.
    if (t.problem.twistReference >= 0) {
        out.twistDeg = t.TwistDeg();
        out.twistPerLengthDegPerMm = out.twistDeg / t.length;
    }
    if (t.problem.twistReference < 0) return;
    // The loads on the clamp where a fixture holds it: the torque (twist held), the lateral resultant
    // and the bending moment about the two tilt axes (tip held); one assembly for all.
    const bool twistHeld = t.def.ends.twist == TwistEnd::Held;
    EnergyResult held;
    if (twistHeld || !t.problem.rigidTop) held = AssembleEnergy(t.problem, t.q, t.FinalLoad(), t.solver.terms, true, nullptr, HessianKind::Exact);
    if (twistHeld) out.torqueNMm = held.twistTorque;
    else if (t.def.ends.twist == TwistEnd::Loaded) out.torqueNMm = t.def.ends.torqueNMm;
    if (t.problem.rigidTop) {  // the tip: where it went
        const std::array<double, kTopParameters> top = TopParameters(t.problem, t.q);
        out.tipLateralMm = std::hypot(top[kTopX], top[kTopY]);
        out.tipTiltDeg = std::acos(std::clamp(std::cos(top[kTopTiltX]) * std::cos(top[kTopTiltY]), -1.0, 1.0)) * 180 / std::numbers::pi;
    } else {
        out.tipForceN = std::hypot(held.topLoads[kTopX], held.topLoads[kTopY]);
        out.tipMomentNMm = std::hypot(held.topLoads[kTopTiltX], held.topLoads[kTopTiltY]);
    }
}

// Stage: the stiffness at the free equilibrium, 1 / (K^-1)_uu of the exact Hessian (its Schur
// complement). Returns K^-1 e_u, dq per unit axial force (empty when the top is held).
Eigen::VectorXd AxialStiffness(TubeEvaluation& t, int negativePivots) {
    if (negativePivots < 0 || t.problem.axial < 0 || t.solver.holdAxial) return {};  // no exact factor, or the top is held
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(t.problem.unknowns);
    unit[t.problem.axial] = 1;
    Eigen::VectorXd response = t.solver.exactFactor->Solve(unit);
    t.out.axialStiffnessNPerMm = 1 / response[t.problem.axial];
    return response;
}

// Stage: the blocking force, the top clamp held at its rest place at the final load, from the free
// state. Only a stable held state's force is the actuator's: pulled back, a buckled wall can come to
// rest on a saddle (12 of 285 GA designs of reproduce's part 2), whose force no clamp would measure.
void BlockingForce(TubeEvaluation& t, const LoadTerms& finalLoad, const Eigen::VectorXd& axialResponse) {
    const ShellProblem& problem = t.problem;
    if (t.load.kind == ShellLoad::Blocked) {
        t.out.strokeForceN = t.out.curveForceN.back();  // the end state's reaction, recorded with the curve
        if (t.load.strokePercent == 0 && t.load.strokeMm == 0) t.out.blockingForceN = t.out.strokeForceN;  // held at its rest place
        return;
    }
    if (t.load.kind != ShellLoad::Inflate && t.load.kind != ShellLoad::Gas) return;
    // Starting from the free state's linear response to the clamp's return (not from the free state
    // with the clamp alone moved, which strains the rings beside it the most).
    Eigen::VectorXd held = t.q;
    if (axialResponse.allFinite() && axialResponse.size() == t.q.size() && axialResponse[problem.axial] > 0)
        held -= (t.q[problem.axial] / axialResponse[problem.axial]) * axialResponse;
    held[problem.axial] = 0;
    t.solver.PreconditionWithExact();
    t.solver.holdAxial = true;
    if (t.solver.Minimise(held, finalLoad) == NewtonEnd::Converged) {
        Positions heldPositions;
        PositionsOf(problem, held, heldPositions);
        EnergyResult heldExact;
        const int negative = SettleState(t, held, finalLoad, t.VolumeLimitAfter(EnclosedVolume(problem, heldPositions)), &heldExact);
        PositionsOf(problem, held, heldPositions);
        // A held state through itself (big bulbs pushed into one another) has no force to report,
        // as a blocked test's end state or a held stroke there has none.
        if (negative == 0 && !(t.def.solver.selfContact && SelfIntersects(problem, heldPositions))) {
            t.out.blockingForceN = heldExact.axialForce;
            t.out.heldBowMm = BowMm(t, heldPositions);
        }
    }
    t.solver.holdAxial = false;
}

// Stage: the verdict on an equilibrium that was reached: a wall through itself, a state past the
// pressure maximum (negative curvature of the exact Hessian under a prescribed load), else ok.
Status JudgeEquilibrium(TubeEvaluation& t, int negativePivots) {
    if (t.def.solver.selfContact && SelfIntersects(t.problem, t.x)) return Status::SelfIntersection;
    if (negativePivots > 0 && t.load.kind != ShellLoad::Volume) {
        t.out.limitPressureKpa = t.out.targetPressureKpa;
        return Status::LimitPoint;
    }
    return Status::Ok;
}

// The held state t.q measured into a result of its own, as a blocked test's end state is (the free
// state's outputs in t.out are kept).
SimResult MeasureHeldState(TubeEvaluation& t, double forceN) {
    SimResult held;
    held.initial = t.problem.rest;
    ShellOutputs kept = std::move(t.out);
    t.out = ShellOutputs{};
    t.out.stretchLimit = kept.stretchLimit;
    t.out.tensileStrengthKpa = kept.tensileStrengthKpa;
    t.out.restVolumeMm3 = kept.restVolumeMm3;
    t.out.targetPressureKpa = kept.targetPressureKpa;
    Measure(t, held);
    t.out.strokeForceN = forceN;
    held.shell = std::move(t.out);
    t.out = std::move(kept);
    held.status = StretchStatus(t.def.material, held.shell.maxStretch, held.shell.stretchLimit);
    held.fitness = held.status == Status::Ok ? held.contractionPercent : std::nan("");
    return held;
}

// Stage (the isobaric test): from the free equilibrium, the top held at each fraction of the free
// stroke, the largest first, each held state from the last.
std::vector<IsobaricPoint> HeldStrokes(TubeEvaluation& t, const LoadTerms& finalLoad, const std::vector<double>& fractions, double freeContractionPercent) {
    const ShellProblem& problem = t.problem;
    std::vector<IsobaricPoint> points;
    const double freeU = t.q[problem.axial];
    t.solver.holdAxial = true;
    std::vector<double> order(fractions);
    std::sort(order.begin(), order.end(), std::greater<>());
    for (double fraction : order) {
        IsobaricPoint point;
        point.strokePercent = fraction * freeContractionPercent;
        Eigen::VectorXd held = t.StretchedTo(t.q, fraction * freeU);
        const Counters before = t.solver.counters;
        if (const NewtonEnd end = t.solver.Minimise(held, finalLoad); end != NewtonEnd::Converged) {
            point.status = StatusOf(end);
        } else {
            Positions x;
            PositionsOf(problem, held, x);
            EnergyResult exact;
            const int negative = SettleState(t, held, finalLoad, t.VolumeLimitAfter(EnclosedVolume(problem, x)), &exact);
            PositionsOf(problem, held, x);
            if (negative != 0) point.status = Status::LimitPoint;
            else if (t.def.solver.selfContact && SelfIntersects(problem, x)) point.status = Status::SelfIntersection;
            else {
                point.forceN = exact.axialForce;
                point.twistDeg = (problem.twist >= 0 ? held[problem.twist] : problem.heldTwist) * 180 / std::numbers::pi;
                t.q = held;  // the next stroke starts here
                point.state = MeasureHeldState(t, point.forceN);
                point.status = point.state.status;  // a held state may stretch the wall past its limit
                if (fraction == 0) point.state.shell.blockingForceN = point.forceN;  // held at its rest place
                point.state.shell.newtonIterations = t.solver.counters.iterations - before.iterations;  // this point's own work
                point.state.shell.factorizations = t.solver.counters.factorizations - before.factorizations;
                point.state.iterationsRun = point.state.shell.newtonIterations;
            }
        }
        if (point.state.initial.Size() == 0) {  // failed: the record of a failed evaluation
            point.state.initial = point.state.final = problem.rest;
            point.state.status = point.status;
            point.state.contractionPercent = point.state.fitness = std::nan("");
        }
        points.push_back(point);
    }
    t.solver.holdAxial = false;
    std::reverse(points.begin(), points.end());  // in the order of increasing stroke, as `fractions` sorted
    return points;
}

// The evaluation as its pipeline: build the tube, follow the load path, settle on a stable state,
// measure, judge, stiffness and blocking force, then the stretch verdict; for the isobaric test
// (inflation with isobaric points), the held strokes after, each also into `points` when given.
// Each output is written by one stage (the solver's counters at the end of the stages that count).
// Stage (inflation with isobaric points): the held strokes from the free state, none to the free
// stroke's fractions, and the curve they make, closed by the free state; the work of one stroke.
std::vector<IsobaricPoint> IsobaricCurveOf(TubeEvaluation& t, const LoadTerms& finalLoad, double freeContractionPercent) {
    const int n = t.load.isobaricPoints;
    std::vector<double> fractions;
    for (int i = 0; i + 1 < n; ++i) fractions.push_back(double(i) / (n - 1));
    std::vector<IsobaricPoint> points = HeldStrokes(t, finalLoad, fractions, freeContractionPercent);
    ShellOutputs& out = t.out;
    for (const IsobaricPoint& point : points) {
        out.isobaricContractionPercent.push_back(point.strokePercent);
        out.isobaricForceN.push_back(point.status == Status::Ok ? point.forceN : NAN);
    }
    out.isobaricContractionPercent.push_back(freeContractionPercent);
    out.isobaricForceN.push_back(0.0);
    out.workPerStrokeMj = StrokeWorkMj(out.isobaricContractionPercent, out.isobaricForceN, t.length);
    if (out.siliconeG > 0) out.workPerGramMjPerG = out.workPerStrokeMj / out.siliconeG;
    return points;
}

// Stage: what the rest design weighs and how far it reaches from the axis (the envelope's measures).
// The wall's silicone at rest: its mid-surface's area times the thickness, mm^3.
double RestWallVolumeMm3(const ShellProblem& problem, const ShellDef& def) {
    double area = 0;
    for (const MembraneRest& rest : problem.membrane) area += rest.area;
    return area * def.geometry.thicknessMm;
}

void MeasureRest(const ShellProblem& problem, const ShellDef& def, ShellOutputs& out) {
    if (def.material.densityKgPerM3 > 0) out.siliconeG = RestWallVolumeMm3(problem, def) * def.material.densityKgPerM3 * 1e-6;  // kg/m^3 = 1e-6 g/mm^3
    double reach = 0;
    const int wall = def.geometry.ringVertices * RingCount(def.geometry);  // the caps' centres are not the wall's
    for (int v = 0; v < wall; ++v) reach = std::max(reach, std::hypot(problem.rest.x[v], problem.rest.y[v]));
    out.restMaxRadiusMm = reach;
}

// Stage: the bench's bounds on the design (EnvelopeDef), each 0 when not given.
bool WithinEnvelope(const ShellDef& def, const ShellOutputs& out) {
    const EnvelopeDef& e = def.envelope;
    if (e.maxRadiusRatio > 0 && out.restMaxRadiusMm > e.maxRadiusRatio * def.geometry.radiusMm) return false;
    if (e.maxRadiusMm > 0 && out.restMaxRadiusMm > e.maxRadiusMm) return false;
    if (e.maxSiliconeG > 0 && !(out.siliconeG <= e.maxSiliconeG)) return false;
    return true;
}

SimResult EvaluateTube(const Shape& shape, const ShellDef& def, bool bending, std::vector<IsobaricPoint>* points) {
    const auto started = std::chrono::steady_clock::now();
    SimResult result;
    ShellOutputs& out = result.shell;
    out.stretchLimit = StretchLimit(def.material);
    out.tensileStrengthKpa = def.material.tensileStrengthKpa;
    auto finish = [&](Status status) {
        result.status = status;
        result.fitness = status == Status::Ok ? result.contractionPercent : std::nan("");
        if (status != Status::Ok) result.contractionPercent = std::nan("");
        result.elapsedMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
        return result;
    };
    std::string error;
    const ShellProblem problem = BuildTubeProblem(def, shape, bending, &error);
    if (!error.empty()) return finish(Status::InvalidGeometry);
    result.initial = problem.rest;
    result.final = problem.rest;
    out.restVolumeMm3 = problem.restVolume;
    MeasureRest(problem, def, out);
    if (!WithinEnvelope(def, out)) return finish(Status::OutsideEnvelope);

    TubeEvaluation t(def, problem, out);
    Status status = FollowLoadPath(t);
    const LoadTerms finalLoad = t.FinalLoad();
    const int negativePivots = status == Status::Ok ? SettleOnStableState(t, finalLoad) : -1;
    Measure(t, result);
    if (status == Status::Ok) status = JudgeEquilibrium(t, negativePivots);
    if (status == Status::Ok) BlockingForce(t, finalLoad, AxialStiffness(t, negativePivots));
    out.newtonIterations = t.solver.counters.iterations;
    out.factorizations = t.solver.counters.factorizations;
    result.iterationsRun = out.newtonIterations;  // the common "iterations" column: Newton iterations here
    if (status == Status::Ok) status = StretchStatus(def.material, out.maxStretch, out.stretchLimit);
    if (status == Status::Ok && def.load.kind == ShellLoad::Inflate && def.load.isobaricPoints >= 2) {
        std::vector<IsobaricPoint> held = IsobaricCurveOf(t, finalLoad, result.contractionPercent);
        out.newtonIterations = t.solver.counters.iterations;  // the held strokes' work counts
        out.factorizations = t.solver.counters.factorizations;
        result.iterationsRun = out.newtonIterations;
        if (points) *points = std::move(held);
    }
    // A stage that ran out of the budget (a stability check, the blocking force, a held stroke)
    // leaves its verdict unfinished: the whole evaluation is a failed design, not a partial one.
    if (t.solver.overBudget) status = Status::BudgetExceeded;
    return finish(status);
}

}  // namespace

SimResult EvaluateShell(const Shape& shape, const ShellDef& def, bool bending) { return EvaluateTube(shape, def, bending, nullptr); }

double StrokeWorkMj(const std::vector<double>& contractionPercent, const std::vector<double>& forceN, double lengthMm) {
    double work = contractionPercent.size() > 1 && forceN.size() == contractionPercent.size() ? 0 : NAN;
    for (size_t i = 1; i < contractionPercent.size() && i < forceN.size(); ++i)
        work += 0.5 * (forceN[i] + forceN[i - 1]) * (contractionPercent[i] - contractionPercent[i - 1]) / 100 * lengthMm;
    return work;
}

double WallVolumeMm3(const Shape& shape, const ShellDef& def) {
    std::string error;
    const ShellProblem problem = BuildTubeProblem(def, shape, false, &error);
    if (!error.empty()) return NAN;
    return RestWallVolumeMm3(problem, def);
}

IsobaricCurve IsobaricForces(const Shape& shape, const ShellDef& inflate, bool bending) {
    IsobaricCurve curve;
    curve.free = EvaluateTube(shape, inflate, bending, &curve.points);
    return curve;
}

}  // namespace sim
