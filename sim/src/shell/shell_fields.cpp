// What the membrane and shell models' meshes are drawn with: the tube's triangles and edges, and per
// vertex the wall's stretch and stress and the fibres' dashes, for colour maps.
#include <Eigen/Geometry>
#include <set>

#include "shell/shell_problem.h"
#include "sim/shell.h"

namespace sim {

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
