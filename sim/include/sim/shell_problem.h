// A shell model's discretisation, ready to solve: a triangle mesh with its rest shape, per-element
// rest data, and which coordinates are unknowns. Energies, gradients and Hessians of SHELL.md
// sections 3-5 are assembled here, exactly and (for Newton's steps) projected to positive
// semi-definite per element. Exposed for the solver and for the verification tests, which check
// every gradient and Hessian against central differences.
//
// Units: millimetres, newtons, megapascals (N/mm^2); energies in N mm.
//
// [SECTION] Elements: membrane triangles, bending hinges, enclosed volume
// [SECTION] Problems: mesh, rest shape, unknowns
// [SECTION] Energy and its derivatives
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <vector>

#include "sim/mesh.h"
#include "sim/shell.h"

namespace sim {

// ---------------------------------------------------------------------------------------------
// [SECTION] Elements
// ---------------------------------------------------------------------------------------------

// The material's constants per rest area: energy density Psi(I1, I2) in N/mm.
struct MembraneMaterial {
    MaterialLaw law = MaterialLaw::NeoHookean;
    double thicknessMm = 1;
    double mu = 0;               // neo-Hookean shear modulus, MPa
    double c10 = 0, c01 = 0;     // Mooney-Rivlin, MPa (Yeoh uses c10, c20, c30)
    double c20 = 0, c30 = 0;
};
MembraneMaterial MembraneMaterialOf(const ShellDef& def);
double MembraneMaterialShearModulus(const MembraneMaterial& material);  // small-strain, MPa

// A wall triangle's rest data: the gradients of its linear shape functions in a rest tangent frame
// (g[a] for corner a; F = sum_a x_a g[a]^T) and its rest area.
struct MembraneRest {
    double g[3][2] = {};
    double area = 0;  // mm^2
};
MembraneRest MakeMembraneRest(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2);

using Matrix32 = Eigen::Matrix<double, 3, 2>;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// Energy per rest area of the incompressible sheet at deformation gradient F (3 x 2), and its
// derivatives with respect to F's entries (column by column). Either pointer may be null.
double MembraneDensity(const MembraneMaterial& material, const Matrix32& F, Vector6* gradient, Matrix6* hessian);

// Principal stretches (largest first) and principal true stresses (MPa) of a deformed triangle.
struct PrincipalValues {
    double stretch[2] = {1, 1};
    double stress[2] = {0, 0};
};
PrincipalValues Principal(const MembraneMaterial& material, const Matrix32& F);

// A fibre family's energy per rest area, (k/4)(I4 - 1)^2 with I4 = |F a|^2 when I4 > 1 (threads carry
// no compression), for unit rest direction a in the triangle's rest frame and stiffness k (N/mm);
// with its derivatives with respect to F's entries. Either pointer may be null (then not touched).
// With tautAtKink (Newton's matrix), a fibre at its rest length within round-off adds the taut
// side's stiffness 2k (F a)(F a)^T to the Hessian, where the exact one is 0.
double FibreDensity(const Matrix32& F, const double a[2], double stiffness, Vector6* gradient, Matrix6* hessian, bool tautAtKink = false);

// The bending angle of hinge (p0, p1, q, r) and its derivatives (see scripts/generate_hinge_angle.py):
// 12-vector gradient and 12 x 12 Hessian over (p0, p1, q, r). Either pointer may be null.
double HingeAngle(const Eigen::Matrix<double, 12, 1>& x, Eigen::Matrix<double, 12, 1>* gradient, Eigen::Matrix<double, 12, 12>* hessian);

// ---------------------------------------------------------------------------------------------
// [SECTION] Problems
// ---------------------------------------------------------------------------------------------

// Where a coordinate's value comes from.
constexpr int kFixed = -1;  // held at its value in ShellProblem::held
constexpr int kAxial = -2;  // the top clamp's axial translation u, added to its rest value

// A soft anchor against rigid motions that no support prevents (sliding ends, a free sphere):
// (k/2)(|T|^2 + |R|^2) with T = sum (x - X), R = sum X x (x - X) over the anchored vertices, for
// the chosen components. A symmetric deformation about the anchored vertices' centroid makes both
// zero, so the anchor changes such solutions not at all while it removes the zero-energy modes.
struct Anchor {
    std::vector<int> vertices;
    bool translation[3] = {false, false, false};
    bool rotation[3] = {false, false, false};
    double stiffness = 0;  // N/mm
};

struct ShellProblem {
    Positions rest;                                // the as-moulded shape
    Positions held;                                // values of fixed coordinates (rest, or prescribed)
    std::vector<std::array<int, 3>> wall;          // elastic triangles, outward
    std::vector<std::array<int, 3>> caps;          // pressure-only triangles closing the ends, outward
    std::vector<std::array<int, 4>> hinges;        // p0, p1 shared; q in (p0, p1, q); r in (p1, p0, r)
    std::vector<MembraneRest> membrane;            // per wall triangle
    std::vector<double> hingeRestAngle;            // theta0 of the as-moulded shape, radians
    std::vector<double> hingeStiffness;            // k_e, N mm
    MembraneMaterial material;
    bool bending = true;
    std::vector<int> dofOf;                        // per coordinate (3 v + c): unknown index, kFixed or kAxial
    int unknowns = 0;                              // free coordinates, plus u when axial >= 0
    int axial = -1;                                // index of u among the unknowns; -1: u held at heldAxial
    double heldAxial = 0;                          // u when it is not an unknown (blocked), mm
    Anchor anchor;
    double restVolume = 0;                         // mm^3, caps included
    double meanEdgeMm = 1;                         // for the convergence tolerance
    // Fibres: per wall triangle, up to two families' unit rest directions in its rest frame (the
    // frame of MembraneRest::g).
    std::vector<std::array<double, 4>> fibreDirections;
    std::vector<int> fibreFamilies;                // per wall triangle: 0, 1 or 2
    double fibreStiffness = 0;                     // N/mm per family
    int vertexCount() const { return rest.Size(); }
};

// The tube of the `membrane` and `shell` models for a design: staggered rings (SHELL.md section 2),
// caps, clamps; the shape's radius profile in millimetres. Empty error string when it can be built;
// otherwise why not (the status is invalid-geometry).
ShellProblem BuildTubeProblem(const ShellDef& def, const Shape& shape, bool bending, std::string* error);

// Verification problems: a closed sphere (icosahedron subdivided `subdivisions` times, radius R),
// held against rigid motion by six coordinates of three vertices; and a flat square patch of side
// `size` on an n x n grid whose boundary is held at F X (interior free).
ShellProblem BuildSphereProblem(const MembraneMaterial& material, double radiusMm, int subdivisions, bool bending);
ShellProblem BuildPatchProblem(const MembraneMaterial& material, double size, int n, const Eigen::Matrix<double, 3, 2>& boundaryF);

// The staggered ring mesh's wall triangles and end-cap fans (R vertices per ring, H rings; the caps'
// centre vertices are R*H and R*H + 1).
void TubeTriangles(int R, int H, std::vector<std::array<int, 3>>& wall, std::vector<std::array<int, 3>>& caps);

// Hinges from triangles: every edge shared by two of them.
std::vector<std::array<int, 4>> HingesOf(const std::vector<std::array<int, 3>>& triangles);
// Rest angles and stiffnesses k_e = (D/2) |e|^2 / (A1 + A2), D = mu h^3 / 3: SHELL.md section 4's
// hinge energy, with the factor that passes its own cylinder calibration (see shell_problem.cpp).
void SetHingeRest(ShellProblem& problem);

// Each unknown's place in a factorisation's 3 x 3 blocks (BlockLdlt), 3 * block + coordinate: a
// vertex's free coordinates share a block; the clamp's axial unknown has one of its own.
std::vector<int> VertexBlockPlaces(const ShellProblem& problem);

// The unknowns' values for positions (u read from the first axial coordinate) and back.
Eigen::VectorXd UnknownsOf(const ShellProblem& problem, const Positions& x);
void PositionsOf(const ShellProblem& problem, const Eigen::VectorXd& q, Positions& x);

// ---------------------------------------------------------------------------------------------
// [SECTION] Energy and its derivatives
// ---------------------------------------------------------------------------------------------

// The load terms of the total energy E = elastic + bending - p (V - V0) - F u (+ the gas term).
struct LoadTerms {
    double pressure = 0;     // gauge pressure, MPa
    double force = 0;        // axial force on u, N
    double gasConstant = 0;  // > 0: sealed gas, p_abs V = gasConstant (N mm); `pressure` is then ignored
    double atmosphere = 0.101325;  // MPa, for the gas's gauge pressure
};

enum class HessianKind {
    Exact,       // the true second derivatives (stability, stiffness, verification)
    Projected,   // elastic parts projected to positive semi-definite per element; pressure exact (Newton)
    Definite,    // Projected without the pressure's Hessian: positive semi-definite whatever the state
};

// Which terms to include (verification checks them one by one).
struct EnergyTerms {
    bool membrane = true, bending = true, pressure = true, force = true, anchor = true, fibres = true;
};

// The sparse pattern of a problem's Hessian over its unknowns, and where each element's entries go.
class HessianPattern {
public:
    explicit HessianPattern(const ShellProblem& problem);
    Eigen::SparseMatrix<double> matrix;  // full symmetric pattern, values overwritten by Assemble
    std::vector<int> wallSlots, hingeSlots, capSlots;  // per element: 81, 144 or 81 value indices (-1: none)
    std::vector<int> anchorSlots;                      // the anchor's dense block
};

struct EnergyResult {
    double energy = 0;
    double volume = 0;           // mm^3
    double axialForce = 0;       // dE/du: the force the actuator exerts on the top clamp (+ pulls it down), N
    Eigen::VectorXd gradient;    // over the unknowns
    Eigen::VectorXd volumeGradient;
};

// The total energy at unknowns q. With `gradient`, its gradient (and the volume's); with `hessian`,
// the Hessian's values written into hessian->matrix.
EnergyResult AssembleEnergy(const ShellProblem& problem, const Eigen::VectorXd& q, const LoadTerms& load, const EnergyTerms& terms,
                            bool gradient, HessianPattern* hessian, HessianKind kind);

// Minimises the total energy at `load` from q (in place) by Newton's method (SHELL.md section 6).
// With holdAxial, u stays where q has it. Returns Ok, NotConverged or NonFinite; counts its work.
Status SolveStatic(const ShellProblem& problem, const LoadTerms& load, const SolverDef& solver, Eigen::VectorXd& q, bool holdAxial = false,
                   int* iterations = nullptr);

// Equilibrium at a prescribed enclosed volume (mm^3) by bordered Newton on (q, p), from q and the
// pressure guess p (MPa), both updated in place: follows the curve past the pressure maximum.
Status SolveVolume(const ShellProblem& problem, const SolverDef& solver, double volume, Eigen::VectorXd& q, double& pressure,
                   int* iterations = nullptr);

// Enclosed volume of positions x (caps included), summed compensated.
double EnclosedVolume(const ShellProblem& problem, const Positions& x);

// Sets a problem's fibre families from a fibre def (SHELL.md section 7): each wall triangle's
// directions at its angle (by band or sector of its rest centroid) to the rest meridian, the tangent
// of the surface along the axis. Empty error when the def is usable.
void SetFibres(ShellProblem& problem, const FibreDef& fibres, double lengthMm, std::string* error);

// Per wall triangle and family: the fibre's stretch (|F a|) and its angle to the axis (degrees) at
// positions x.
struct FibreState {
    std::vector<double> stretch, angleDeg, restHeightMm;
};
FibreState FibreStates(const ShellProblem& problem, const Positions& x);

// Whether two non-adjacent wall or cap triangles intersect (SHELL.md section 8).
bool SelfIntersects(const ShellProblem& problem, const Positions& x);

// The wall's per-triangle deformation gradient at positions x.
Matrix32 DeformationGradient(const ShellProblem& problem, int triangle, const Positions& x);

}  // namespace sim
