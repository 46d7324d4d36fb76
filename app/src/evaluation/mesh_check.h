// A physical-model result's mesh error estimate (docs/models/shell.md section 2): the same design,
// the same clamps in millimetres, meshed twice as finely in both directions, and how far its
// contraction moves. `simulate --mesh-check` reports it; reproduce's mesh-convergence study is made of it.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/batch.h"

namespace app {

// The design meshed with every edge halved: twice the ring vertices, 2 H - 1 rings (0, near-
// equilateral, stays 0 and halves with the ring). The clamps keep their length.
sim::EvalJob RefinedJob(sim::EvalJob job);

// How far a contraction moves under refinement, against the 5 % rule: relative, except that
// contractions under 1 % are compared in absolute terms (0.05 percentage points), where a relative
// figure of two near-zero numbers says nothing.
struct MeshChange {
    double points = NAN, relativePercent = NAN;
    bool within = false;
};
MeshChange ChangeOf(double coarse, double fine);
// The same rule for a held state's force: within 5 %, except that forces under 20 mN are compared in
// absolute terms (1 mN, what a bench's load cell for soft muscles resolves).
bool ForceWithinMeshRule(double coarseN, double fineN);
inline constexpr const char* kMeshRule =
    "within 5 % of the same design meshed twice as finely in both directions; under 1 % contraction, within 0.05 percentage points";
inline constexpr const char* kForceMeshRule = "the held force within 5 % of the same at twice the mesh; under 20 mN, within 1 mN";

// The check as simulate and the searches report it ("mesh_check"): the refined mesh, its status and
// contraction, the difference from `coarseContraction` in points and percent, the verdict and the rule;
// with a held state's force on both meshes (`coarseBlockingForceN` finite), that force refined, how
// far it moved in percent and its own verdict: a held state's stability can depend on the mesh, and a
// bowed held state converges only at first order (docs/models/shell.md section 12), so a contraction
// that has converged says nothing of its held force.
nlohmann::json MeshCheckJson(double coarseContraction, const sim::EvalJob& refined, const sim::SimResult& fine, double coarseBlockingForceN = NAN);
// The same for a design's own result in hand (simulate, Python): its contraction and held force
// count only when it ended ok.
nlohmann::json MeshCheckJson(const sim::SimResult& coarse, const sim::EvalJob& refined, const sim::SimResult& fine);

}  // namespace app
