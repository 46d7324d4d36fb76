#include "sim/mesh.h"

#include <cmath>
#include <numbers>

namespace sim {

MeshDef DefaultMeshDef() { return MeshDef{}; }

std::array<int, 4> SpringOffsets(const MeshDef& def) {
    const int r = def.resolution;
    return {1, r, r - 1, r + 1};
}

int SpringCount(const MeshDef& def) {
    const int n = VertexCount(def);
    int count = 0;
    for (int offset : SpringOffsets(def)) count += n - offset;
    return count;
}

double HelixAngle(const MeshDef& def, int vertex) {
    return 2.0 * std::numbers::pi * vertex / def.resolution;
}

double HelixHeight(const MeshDef& def, int vertex) {
    return static_cast<double>(vertex + 1) / def.resolution;
}

Positions BaseHelix(const MeshDef& def) {
    Positions p;
    const int n = VertexCount(def);
    p.Resize(n);
    for (int i = 0; i < n; ++i) {
        const double theta = HelixAngle(def, i);
        p.x[i] = std::sin(theta);
        p.y[i] = std::cos(theta);
        p.z[i] = HelixHeight(def, i);
    }
    return p;
}

std::vector<std::array<int, 3>> Triangles(const MeshDef& def) {
    const int r = def.resolution;
    const int n = VertexCount(def);
    std::vector<std::array<int, 3>> triangles;
    triangles.reserve(2 * static_cast<size_t>(n));
    for (int i = 0; i + r + 1 < n; ++i) {
        triangles.push_back({i, i + 1, i + r + 1});
        triangles.push_back({i, i + r + 1, i + r});
    }
    return triangles;
}

}  // namespace sim
