// One entry point for every model: a job's checks, its evaluation and the surface its meshes are
// drawn on.
#include <Eigen/Geometry>
#include <set>

#include "sim/batch.h"
#include "shell/shell_problem.h"

namespace sim {

SimResult Evaluate(const EvalJob& job) {
    switch (job.model) {
        case ModelKind::Thesis: return Evaluate(job.shape, job.mesh, job.params);
        case ModelKind::Membrane: return EvaluateShell(job.shape, job.shell, false);
        case ModelKind::Shell: return EvaluateShell(job.shape, job.shell, true);
    }
    return {};
}

std::string JobError(const EvalJob& job) {
    if (job.model == ModelKind::Thesis) {
        if (std::string error = SimParamsError(job.params); !error.empty()) return error;
        return ShapeError(job.shape, job.mesh);
    }
    if (std::string error = ShellDefError(job.shell); !error.empty()) return error;
    // Shapes are checked as the thesis defines them; sizes that depend on the ring mesh (free-xy,
    // mesh) are checked when the tube is built, and a design that cannot be built is the status
    // invalid-geometry, not an input error.
    const GeometryDef& g = job.shell.geometry;
    const MeshDef ringMesh{g.ringVertices, RingCount(g)};
    if (std::holds_alternative<FreeXYShape>(job.shape) || std::holds_alternative<MeshShape>(job.shape)) {
        const size_t n = static_cast<size_t>(ringMesh.resolution) * ringMesh.turns;
        const size_t got = std::holds_alternative<FreeXYShape>(job.shape) ? std::get<FreeXYShape>(job.shape).dx.size()
                                                                         : static_cast<size_t>(std::get<MeshShape>(job.shape).positions.Size());
        if (got != n)
            return std::string(ShapeName(job.shape)) + " needs one entry per vertex of the " + std::to_string(g.ringVertices) + " x " +
                   std::to_string(ringMesh.turns) + " ring mesh: " + std::to_string(n) + ", got " + std::to_string(got);
        return "";
    }
    return ShapeError(job.shape, DefaultMeshDef());
}

double SweepValue(const EvalJob& job, SweepParameter parameter) {
    if (parameter == SweepParameter::PressureKpa) return job.model == ModelKind::Thesis ? NAN : job.shell.load.pressureKpa;
    if (parameter == SweepParameter::FibreAngleDeg) return job.model == ModelKind::Thesis ? NAN : job.shell.fibres.angleDeg;
    return SweepParameterValue(job.shape, parameter);
}

EvalJob WithSweepValue(EvalJob job, SweepParameter parameter, double value) {
    if (parameter == SweepParameter::PressureKpa) job.shell.load.pressureKpa = value;
    else if (parameter == SweepParameter::FibreAngleDeg) job.shell.fibres.angleDeg = value;
    else job.shape = WithSweepParameter(job.shape, parameter, value);
    return job;
}

std::vector<EvalJob> SweepJobs(const SweepDef& def, const EvalJob& base) {
    std::vector<EvalJob> jobs{base};
    jobs.front().shape = def.base;
    for (const SweepAxis& axis : def.axes) {
        std::vector<EvalJob> next;
        for (const EvalJob& job : jobs)
            for (double value : axis.values) next.push_back(WithSweepValue(job, axis.parameter, value));
        jobs = std::move(next);
    }
    return jobs;
}

Surface ShellSurface(const GeometryDef& geometry) {
    Surface s;
    const int R = geometry.ringVertices, H = RingCount(geometry);
    s.vertexCount = R * H + 2;
    std::vector<std::array<int, 3>> wall, caps;
    TubeTriangles(R, H, wall, caps);
    s.triangles = wall;
    s.triangles.insert(s.triangles.end(), caps.begin(), caps.end());
    std::set<std::pair<int, int>> edges;
    for (const auto& t : wall)
        for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    for (const auto& [a, b] : edges) s.edges.push_back({a, b});
    return s;
}

Surface SurfaceOf(const EvalJob& job) {
    return job.model == ModelKind::Thesis ? HelixSurface(job.mesh) : ShellSurface(job.shell.geometry);
}

ShellFields ShellFieldValues(const ShellDef& def, const Shape& shape, bool bending, const Positions& deformed) {
    ShellFields fields;
    std::string error;
    const ShellProblem problem = BuildTubeProblem(def, shape, bending, &error);
    const int n = problem.vertexCount();
    if (!error.empty() || deformed.Size() != n) return fields;
    fields.stretch.assign(n, 0.0);
    fields.stressKpa.assign(n, 0.0);
    std::vector<int> count(n, 0);
    for (size_t t = 0; t < problem.wall.size(); ++t) {
        const PrincipalValues v = Principal(problem.material, DeformationGradient(problem, static_cast<int>(t), deformed));
        for (int a : problem.wall[t]) {
            fields.stretch[a] += v.stretch[0];
            fields.stressKpa[a] += v.stress[0] * 1e3;
            ++count[a];
        }
    }
    // Fibres: a dash per triangle and family along the deformed fibre, on the wall's outer face.
    for (size_t t = 0; t < problem.wall.size() && !problem.fibreFamilies.empty(); ++t) {
        const auto& tri = problem.wall[t];
        Eigen::Vector3d x[3];
        for (int a = 0; a < 3; ++a) x[a] = {deformed.x[tri[a]], deformed.y[tri[a]], deformed.z[tri[a]]};
        const Eigen::Vector3d centroid = (x[0] + x[1] + x[2]) / 3, normal = (x[1] - x[0]).cross(x[2] - x[0]).normalized();
        const double edge = ((x[1] - x[0]).norm() + (x[2] - x[1]).norm() + (x[0] - x[2]).norm()) / 3;
        const Matrix32 F = DeformationGradient(problem, static_cast<int>(t), deformed);
        for (int k = 0; k < problem.fibreFamilies[t]; ++k) {
            const Eigen::Vector3d d = F.col(0) * problem.fibreDirections[t][2 * k] + F.col(1) * problem.fibreDirections[t][2 * k + 1];
            FibreDash dash;
            const Eigen::Vector3d centre = centroid + 0.5 * problem.material.thicknessMm * normal, along = d.normalized();
            for (int c = 0; c < 3; ++c) {
                dash.centre[c] = centre[c];
                dash.along[c] = along[c];
            }
            dash.halfLengthMm = 0.45 * edge;
            dash.stretch = d.norm();
            fields.fibres.push_back(dash);
        }
    }
    for (int v = 0; v < n; ++v) {
        if (count[v]) {
            fields.stretch[v] /= count[v];
            fields.stressKpa[v] /= count[v];
        } else {
            fields.stretch[v] = 1;  // cap centres: rigid
        }
    }
    return fields;
}

}  // namespace sim
