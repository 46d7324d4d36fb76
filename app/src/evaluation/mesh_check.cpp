#include "evaluation/mesh_check.h"

#include <algorithm>
#include <cmath>

namespace app {

sim::EvalJob RefinedJob(sim::EvalJob job) {
    sim::GeometryDef& g = job.Shell().geometry;
    g.ringVertices *= 2;
    if (g.rings > 0) g.rings = 2 * g.rings - 1;  // every edge halved
    g.edgeSpacingMm /= 2;                        // a graded mesh's at the clamps too
    return job;
}

nlohmann::json MeshCheckJson(double coarseContraction, const sim::EvalJob& refined, const sim::SimResult& fine, double coarseBlockingForceN) {
    const bool ok = fine.status == sim::Status::Ok && std::isfinite(coarseContraction);
    const MeshChange change = ok ? ChangeOf(coarseContraction, fine.contractionPercent) : MeshChange{};
    auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    nlohmann::json check = {{"mesh", sim::ModelOf(refined).meshText(refined)},
                            {"status", sim::Name(fine.status)},
                            {"contraction_percent", number(fine.status == sim::Status::Ok ? fine.contractionPercent : NAN)},
                            {"difference_points", number(change.points)},
                            {"relative_difference_percent", number(change.relativePercent)},
                            {"converged", ok && change.within},
                            {"rule", kMeshRule}};
    if (std::isfinite(coarseBlockingForceN)) {
        const double refinedForce = fine.status == sim::Status::Ok ? fine.shell.blockingForceN : NAN;
        check["blocking_force_n"] = number(refinedForce);
        check["blocking_force_difference_percent"] = number(100 * std::fabs(refinedForce - coarseBlockingForceN) / std::fabs(refinedForce));
        check["blocking_force_converged"] = ForceWithinMeshRule(coarseBlockingForceN, refinedForce);
        check["blocking_force_rule"] = kForceMeshRule;
    }
    return check;
}

nlohmann::json MeshCheckJson(const sim::SimResult& coarse, const sim::EvalJob& refined, const sim::SimResult& fine) {
    const bool ok = coarse.status == sim::Status::Ok;
    return MeshCheckJson(ok ? coarse.contractionPercent : NAN, refined, fine, ok ? coarse.shell.blockingForceN : NAN);
}

MeshChange ChangeOf(double coarse, double fine) {
    MeshChange c;
    if (!std::isfinite(coarse) || !std::isfinite(fine)) return c;
    c.points = std::fabs(fine - coarse);
    c.relativePercent = 100 * c.points / std::max(std::fabs(fine), 1e-12);
    c.within = std::fabs(fine) < 1 ? c.points <= 0.05 : c.relativePercent <= 5;
    return c;
}

bool ForceWithinMeshRule(double coarseN, double fineN) {
    const double apart = std::fabs(fineN - coarseN);  // NaN (a failed state) is within nothing
    return std::fabs(fineN) < 0.02 ? apart <= 0.001 : apart <= 0.05 * std::fabs(fineN);
}

}  // namespace app
