// The helical mesh of the `thesis` model (docs/models/thesis.md, "Mesh"): R vertices per turn, H turns,
// vertex i at angle 2*pi*i/R and height (i+1)/R, springs at four fixed index offsets.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace sim {

// Size of the helix. The thesis used 30 x 30 throughout.
struct MeshDef {
    int resolution = 30;  // R: vertices per turn of the helix
    int turns = 30;       // H: number of turns; the mesh has R*H vertices
};
MeshDef DefaultMeshDef();

inline int VertexCount(const MeshDef& def) { return def.resolution * def.turns; }

// Smallest mesh the model is defined on: two clamped turns at each end plus at least one free turn,
// and at least three vertices per turn so that the tube has an inside.
constexpr int kMinResolution = 3;
constexpr int kMinTurns = 5;
constexpr int kMaxVertices = 1 << 20;  // keeps a typo like --turns 300000 from eating the machine
constexpr int kClampedTurns = 2;       // turns held by the clamps at each end

// Positions as structure-of-arrays, in helix order. Always double outside the solver.
struct Positions {
    std::vector<double> x, y, z;

    int Size() const { return static_cast<int>(x.size()); }
    void Resize(int n) { x.assign(n, 0.0); y.assign(n, 0.0); z.assign(n, 0.0); }
    bool operator==(const Positions&) const = default;
};

// The four spring families, as index offsets from the lower vertex: (i, i+offset) for every
// i with i+offset < N. Neighbour along the helix, the vertex one turn up, and the two diagonals.
std::array<int, 4> SpringOffsets(const MeshDef& def);
int SpringCount(const MeshDef& def);

// The bare helix of radius 1 (the `cylinder` shape).
Positions BaseHelix(const MeshDef& def);
double HelixAngle(const MeshDef& def, int vertex);   // radians
double HelixHeight(const MeshDef& def, int vertex);  // (i+1)/R

// Whether a vertex is held by the clamps (the two bottom and two top turns).
inline bool IsClamped(const MeshDef& def, int vertex) {
    const int band = kClampedTurns * def.resolution;
    return vertex < band || vertex >= VertexCount(def) - band;
}

// Triangles for drawing and OBJ export: quad (i, i+1, i+R+1, i+R) split in two.
std::vector<std::array<int, 3>> Triangles(const MeshDef& def);

}  // namespace sim
