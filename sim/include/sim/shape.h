// Shapes: radius profiles and offsets that turn the bare helix into an actuator (docs/models/thesis.md, "Shapes").
// Each is a small value type; `Shape` is their variant. BuildInitialPositions() makes the mesh.
#pragma once

#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "sim/mesh.h"
#include "sim/names.h"

namespace sim {

// The plain tube, rho = 1.
struct CylinderShape {
    bool operator==(const CylinderShape&) const = default;
};

// rho_i = amplitude * sin(phaseStart + t_i*(phaseEnd - phaseStart)), t_i = i/(N-1).
// rho may go negative: the mesh then passes through the axis, as in the thesis.
struct SineShape {
    double amplitude = 4.1;                 // radius scale, mesh units (the base radius is 1)
    double phaseStart = 0.5;                // radians at the bottom vertex
    double phaseEnd = std::numbers::pi - 0.5;  // radians at the top vertex (thesis 4.1: pi - 0.5)
    bool operator==(const SineShape&) const = default;
};

// rho_i = amplitude * |sin(...)| (thesis 4.3): the tube never passes through its axis.
struct AbsSineShape {
    double amplitude = 4.0;                  // radius scale, mesh units (Table 4.4's realistic mesh)
    double phaseStart = 0.0;                 // radians at the bottom vertex
    double phaseEnd = 4.0 * std::numbers::pi;  // radians at the top vertex: two full bulges
    bool operator==(const AbsSineShape&) const = default;
};

enum class SplineRegion {
    Entire,  // the spline spans every vertex
    Middle,  // the two clamped turns at each end keep rho = 1; the spline spans the rest
};

// Uniform cubic B-spline radius profiles (thesis eq. 2.2), one per angular sector.
// With S splines, vertex i belongs to sector ((i mod R) * S) / R.
struct BSplineShape {
    SplineRegion region = SplineRegion::Middle;
    std::vector<std::vector<double>> splines;  // control points of each sector's spline, >= 4 each
    bool operator==(const BSplineShape&) const = default;
};

// The bare helix plus a free (dx, dy) offset per vertex (thesis 5.5). Both arrays have N entries.
struct FreeXYShape {
    std::vector<double> dx, dy;
    bool operator==(const FreeXYShape&) const = default;
};

// Arbitrary initial positions in helix order (for example an OBJ file written by --save-mesh).
struct MeshShape {
    Positions positions;
    bool operator==(const MeshShape&) const = default;
};

using Shape = std::variant<CylinderShape, SineShape, AbsSineShape, BSplineShape, FreeXYShape, MeshShape>;

// The shape families, in the variant's order.
enum class ShapeKind { Cylinder, Sine, AbsSine, BSpline, FreeXY, Mesh };
inline ShapeKind KindOf(const Shape& shape) { return static_cast<ShapeKind>(shape.index()); }

// The name used on the command line and in results: cylinder, sine, abs-sine, bspline, free-xy, mesh.
const char* ShapeName(const Shape& shape);

// Empty when the shape can be built on this mesh; otherwise what is wrong, for a user to read.
// Checks finiteness, control-point counts, sector counts and array sizes.
std::string ShapeError(const Shape& shape, const MeshDef& def);

// Uniform cubic B-spline through control points at parameter t in [0, 1] (docs/models/thesis.md formula).
double EvaluateBSpline(const std::vector<double>& controlPoints, double t);

// A design's radius (in units of the base radius) at height fraction t (0..1) along the tube and at
// `angle` (radians): the thesis's profiles read as functions, independent of any mesh. Middle-region
// B-splines keep radius 1 over `clampFraction` of the length at each end and span the rest. NaN for
// free-xy and mesh designs, which are defined per vertex only.
double DesignRadius(const Shape& shape, double t, double angle, double clampFraction);

// The initial (rest) mesh of a shape. Precondition: ShapeError(shape, def) is empty.
Positions BuildInitialPositions(const Shape& shape, const MeshDef& def);

template <>
struct EnumNames<ShapeKind> {
    static constexpr std::array<std::pair<ShapeKind, const char*>, 6> table{{
        {ShapeKind::Cylinder, "cylinder"},
        {ShapeKind::Sine, "sine"},
        {ShapeKind::AbsSine, "abs-sine"},
        {ShapeKind::BSpline, "bspline"},
        {ShapeKind::FreeXY, "free-xy"},
        {ShapeKind::Mesh, "mesh"},
    }};
};
template <>
struct EnumNames<SplineRegion> {
    static constexpr std::array<std::pair<SplineRegion, const char*>, 2> table{{{SplineRegion::Entire, "entire"}, {SplineRegion::Middle, "middle"}}};
};

}  // namespace sim
