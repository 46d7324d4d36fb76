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
        for (int k = 0; k < problem.fibreFamilies[t]; ++k) {
            const Eigen::Vector3d d = FibreVector(problem, static_cast<int>(t), k, deformed);
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

WallCells WallCellValues(const ShellDef& def, const Shape& shape, bool bending, const Positions& deformed) {
    WallCells cells;
    std::string error;
    const ShellProblem problem = BuildTubeProblem(def, shape, bending, &error);
    if (!error.empty() || deformed.Size() != problem.vertexCount()) return cells;
    const size_t wall = problem.wall.size(), n = wall + problem.caps.size();
    const int R = def.geometry.ringVertices, H = RingCount(def.geometry);
    const int clamp = def.geometry.ends == EndCondition::Clamped ? ClampRingCount(def.geometry) : 0;
    auto clamped = [&](int v) { return v / R < clamp || v / R >= H - clamp; };
    for (int f = 0; f < 2; ++f) {
        cells.fibreDirection[f].assign(n, {NAN, NAN, NAN});
        cells.fibreStrain[f].assign(n, NAN);
        cells.fibreTensionNPerMm[f].assign(n, NAN);
    }
    cells.region.assign(n, static_cast<int>(WallRegion::Cap));
    for (auto* field : {&cells.stretchMax, &cells.stretchMin, &cells.stressMaxKpa, &cells.stressMinKpa, &cells.thicknessMm}) field->assign(n, NAN);
    for (size_t t = 0; t < wall; ++t) {
        const auto& tri = problem.wall[t];
        cells.region[t] = static_cast<int>(clamped(tri[0]) && clamped(tri[1]) && clamped(tri[2]) ? WallRegion::Clamped : WallRegion::Wall);
        const Matrix32 F = DeformationGradient(problem, static_cast<int>(t), deformed);
        const PrincipalValues v = Principal(problem.material, F);
        cells.stretchMax[t] = v.stretch[0];
        cells.stretchMin[t] = v.stretch[1];
        cells.stressMaxKpa[t] = v.stress[0] * 1e3;
        cells.stressMinKpa[t] = v.stress[1] * 1e3;
        cells.thicknessMm[t] = problem.material.thicknessMm / (v.stretch[0] * v.stretch[1]);
        for (int k = 0; !problem.fibreFamilies.empty() && k < problem.fibreFamilies[t]; ++k) {
            // The same stretch as the model's fibre outputs (FibreStates); the tension is the
            // energy (k/4)(lambda^2 - 1)^2's derivative in lambda.
            const Eigen::Vector3d d = FibreVector(problem, static_cast<int>(t), k, deformed);
            const double stretch = d.norm();
            const Eigen::Vector3d unit = d / stretch;
            cells.fibreDirection[k][t] = {unit.x(), unit.y(), unit.z()};
            cells.fibreStrain[k][t] = stretch - 1;
            cells.fibreTensionNPerMm[k][t] = stretch > 1 ? problem.fibreStiffness * stretch * (stretch * stretch - 1) : 0.0;
            cells.families = std::max(cells.families, k + 1);
        }
    }
    return cells;
}

std::vector<double> ContactGapValues(const ShellDef& def, const Shape& shape, const Positions& deformed) {
    if (def.contact.mode != ContactMode::On) return {};
    std::string error;
    const ShellProblem problem = BuildTubeProblem(def, shape, false, &error);
    if (!error.empty() || !problem.contact || deformed.Size() != problem.vertexCount()) return {};
    const double h = problem.barrier.thicknessMm;
    std::vector<double> gap(problem.vertexCount(), NAN);
    for (const ContactPair& pair : ContactCandidates(*problem.contact, deformed, nullptr, 2 * h)) {
        const double g = std::sqrt(SquaredDistance(pair.kind, PairCoordinates(pair, deformed), nullptr, nullptr)) - h;
        for (int v : pair.vertices)
            if (!(gap[v] <= g)) gap[v] = std::max(0.0, g);
    }
    return gap;
}

}  // namespace sim
