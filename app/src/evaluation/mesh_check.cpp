#include "evaluation/mesh_check.h"

#include <algorithm>
#include <cmath>

namespace app {

sim::EvalJob RefinedJob(sim::EvalJob job) {
    sim::GeometryDef& g = job.Shell().geometry;
    g.ringVertices *= 2;
    if (g.rings > 0) g.rings = 2 * g.rings - 1;  // every edge halved
    return job;
}

MeshChange ChangeOf(double coarse, double fine) {
    MeshChange c;
    if (!std::isfinite(coarse) || !std::isfinite(fine)) return c;
    c.points = std::fabs(fine - coarse);
    c.relativePercent = 100 * c.points / std::max(std::fabs(fine), 1e-12);
    c.within = std::fabs(fine) < 1 ? c.points <= 0.05 : c.relativePercent <= 5;
    return c;
}

}  // namespace app
