// From a design to parts that can be printed and cast: the actuator's wall as a closed solid of a
// given thickness around the design's rest surface, and a two-piece mold with a core. Every solid
// is closed, 2-manifold and oriented outward by construction (the tests check it with CGAL). Pure
// geometry in millimetres; app/ writes the files.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "sim/batch.h"
#include "sim/names.h"
#include "sim/shape.h"

namespace sim {

struct TriangleMesh {
    std::vector<std::array<double, 3>> vertices;  // mm
    std::vector<std::array<int, 3>> triangles;     // counter-clockwise seen from outside the solid
};

double MeshVolume(const TriangleMesh& mesh);                  // mm^3, by the divergence theorem
std::array<double, 6> MeshBounds(const TriangleMesh& mesh);   // x, y, z minimum then maximum, mm

enum class WallSide {
    Centred,  // half the wall inside the rest surface, half outside (the models' mid-surface)
    Outward,  // the rest surface is the inside of the wall
};

// Guide grooves for the fibres in the outer face of a first-stage layer (PartDef::layerMm): one per
// family, following its thread ring by ring.
struct GuideDef {
    double depthMm = 0.3;  // the thread lies in a groove this deep (a polyester or aramid thread of 0.2-0.3 mm)
    double widthMm = 1;    // and this wide across the thread (a cosine profile)
    std::vector<std::vector<double>> anglePerRing;   // per family: the thread's angle about the axis at each ring (radians from +x)
    std::vector<std::vector<double>> cosinePerRing;  // per family: cos of its angle to the meridian there
};

// How a design becomes a part. Defaults are the shell models' geometry defaults.
struct PartDef {
    double radiusMm = 5;        // one design unit of radius
    double lengthMm = 150;      // the tube between its end faces
    double thicknessMm = 1;     // the wall, measured along the surface normal
    WallSide wall = WallSide::Centred;
    double clampFraction = 0;   // middle-region B-splines: the share of the length at each end kept at radius 1
    int angularSamples = 120;   // around the tube; a multiple of 8 (the mold splits at 0 and 180 degrees, its block corners lie at 45)
    int axialSamples = 121;     // along the tube, end rings included
    bool helixAngles = false;   // thesis-model designs: sector angles run as the helix's (x = sin, y = cos), not from +x counter-clockwise
    // A fibre design's first stage: the wall's inner layer this thick, its outer face grooved along
    // the threads (guides). 0: the whole wall.
    double layerMm = 0;
    GuideDef guides;
    // A piece of the design cast on its own (CastKind::Halves): the heights it spans, as fractions of
    // the length; its solids start at z = 0. At a cut end (not the design's own end) the wall ends
    // in a bonding flange this far beyond its outer face, one sample band thick.
    double fromFraction = 0, toFraction = 1;
    double flangeMm = 0;
};

// How the actuator is cast (docs/guide/export.md, casting in halves).
enum class CastKind {
    Whole,   // in one mold
    Halves,  // cut across the axis at its widest section into two pieces, each in its own mold with a
             // core that leaves through the cut, bonded at their flanges
};

// A design's radius, in units of the base radius, at height fraction t (0..1) and at an angle
// (radians, from +x counter-clockwise).
using RadiusField = std::function<double(double t, double angle)>;

// The radius of a design defined per vertex (free-xy offsets, an OBJ mesh), read from its rest mesh
// under the job's model: each vertex's distance from the axis, interpolated around the rings (or the
// helix's turns) and between them. Empty with `error` set when the rest mesh cannot be built.
RadiusField MeasuredRadiusField(const EvalJob& job, std::string* error);

// Rigid end fittings: a plug at each end, its insert filling the tube's end where the clamps grip and
// its collar outside, the bottom one bored through for the air line.
struct FittingDef {
    bool enabled = false;
    double portMm = 4;         // the bottom plug's through hole, diameter
    double collarMm = 10;      // collar length beyond the end
    double collarMarginMm = 2; // collar beyond the actuator's outer end ring
    double insertMm = 0;       // insert length into the tube; 0: the clamped length (clampFraction x length), at least two walls
};

// How the core leaves the cured part (docs/guide/export.md, demoulding).
enum class CoreKind {
    Rigid,  // one piece, pulled out through an end opening: only where the wall can stretch over it
    Lost,   // printed to be dissolved or melted out (PVA, wax, a low-melt alloy), with a drain along its axis
};

// The mold: a block around the actuator split in two halves through the axis (the plane y = 0), and
// a core that forms the inside, its ends reaching through the block as handles.
struct MoldDef {
    double marginMm = 5;    // block beyond the actuator's widest point, in x and y
    double endWallMm = 5;   // block beyond each end face of the actuator
    double handleMm = 15;   // core beyond the block at each end
    // The pour (docs/guide/export.md, pouring): the mold stands upright and fills from its lowest
    // point, through a sprue in shell A's bottom end wall centred at 90 degrees; the air leaves
    // through vents in the top end wall, the cavity's only high point, at 45 and 135 degrees (shell
    // A) and 225 and 315 (shell B). Each slot spans at least one sample cell.
    double sprueDegrees = 0;  // the sprue's arc; 0: as wide as sprueMm at its mean radius, and wide enough that it adds at
                              // most a quarter to the cavity's resistance to the flow
    double sprueMm = 3;       // the sprue's section is at least this wide both ways (a 14 G blunt needle or a 3 mm tube
                              // fits): across the wall it reaches outward past the wall's outer face
    double ventDegrees = 6;
    // Registration: four square pins on shell A's split face (in the margin, near each end), tapered
    // by this clearance at their tops, into holes of their feet's size in shell B.
    double pinClearanceMm = 0.15;
    // The pour mark: an arrow pointing up, engraved this deep in shell A's back (the block's side at
    // y = +w, over the sprue), so that the mold stands the right way up with its sprue found; never
    // deeper than a quarter of the margin. 0: none.
    double markDepthMm = 0.6;
    CoreKind core = CoreKind::Rigid;
    double drainMm = 0;  // a lost core's drain, a bore along its axis handle to handle: its diameter; 0: up to 4 mm,
                         // leaving 1 mm of core around it
};

// A one-piece core leaves through one end: every section of the wall between the core's widest
// section and that end must stretch around it. The hoop stretch needed is the core's largest
// perimeter that must pass over the part's perimeter there; the exit is the end that needs less.
struct CoreExit {
    bool top = true;         // leaves through the top end (else the bottom)
    double stretch = 1;      // the largest hoop stretch of the wall on the way out
    double zMm = 0;          // the wall's section that needs it, mm from the bottom end
    double coreAcrossMm = 0; // the widest core section that must pass it: perimeter / pi, mm
    double openingMm = 0;    // that section's inner perimeter / pi, mm
};

// The hoop stretch a cured wall may take once, while a one-piece core is pulled out through it: the
// material's stretch limit, and never more than 3, the largest stretch the presets' tensile fits
// cover (docs/guide/export.md).
double DemouldingStretchLimit(const MaterialDef& material);

struct PartSolids {
    TriangleMesh actuator;  // the silicone wall
    TriangleMesh actuatorCut;  // its half at y >= 0, closed by the cut faces (pictures of the wall's thickness)
    TriangleMesh core;      // the inner cavity with a handle at each end
    TriangleMesh shellA;    // the block's half at y >= 0, less the actuator and the core's channels
    TriangleMesh shellB;    // the half at y <= 0
    double coreOutsideBlockMm3 = 0;  // the handles' parts beyond the block (the rest of the core fills the cavity)
    TriangleMesh fittingBottom, fittingTop;  // when asked for (FittingDef::enabled)
    double openingsMm3 = 0;          // the sprue and vents: block volume in neither shell nor part
    double sprueMm3 = 0;             // the sprue's share of it
    double sprueDegreesBuilt = 0;    // the sprue's arc as built (whole sample cells)
    double sprueGapMm = 0;           // its width across the wall (the wall, or sprueMm when that is wider)
    double sprueResistanceShare = 0; // the sprue's viscous resistance over the full cavity's (thin-gap flow)
    std::array<double, 3> sprueMouthMm{};  // the middle of the sprue's opening in the block's bottom face
    // The cavity the silicone fills, ring by ring from the bottom: the wall's mid-surface perimeter and
    // the distance along the wall from the bottom end (mm), for the fill-time estimate (casting.h).
    std::vector<double> cavityPerimeterMm, cavityPathMm, cavityHeightMm;
    // That mid-surface's samples, ring j (from the bottom) sample i (from +x counter-clockwise) at
    // j * midAround + i: where the fibres lie (the models put them in the wall's mid-surface).
    std::vector<std::array<double, 3>> midSurfaceMm;
    int midAround = 0;
    std::vector<double> corePerimeterMm;  // the core's section at each ring (the wall's inner perimeter), mm
    double pinsLessHolesMm3 = 0;     // shell A's pins less shell B's holes (the clearance's share)
    double markMm3 = 0;              // the pour mark's pocket in shell A's back (in no part)
    double markDepthMm = 0;          // its depth as built (0: unmarked)
    double drainInBlockMm3 = 0;      // a lost core's drain within the block (in no part)
    double drainMm = 0;              // its diameter as built
    CoreExit coreExit;               // how a one-piece core would leave (for a lost core too: the reason to lose it)
};

// B-spline sectors meet in a step of radius that no wall of finite thickness can follow; the part
// blends one sector's radius into the next over this angle either side of each boundary (radians).
double SectorBlendRadians(const PartDef& part);

// Builds every solid. Empty when the design can be made; otherwise one line naming where and why
// (a radius that is not positive, a wall that would fold over itself at this thickness, a design
// defined only per vertex), and `out` is left untouched.
// `measured` is the radius of per-vertex designs (MeasuredRadiusField); other designs use their
// profile (DesignRadius).
std::string BuildPartSolids(const Shape& shape, const PartDef& part, const MoldDef& mold, PartSolids* out, const FittingDef& fittings = {},
                            const RadiusField& measured = {});

}  // namespace sim

template <>
struct sim::EnumNames<sim::CoreKind> {
    static constexpr std::array<std::pair<sim::CoreKind, const char*>, 2> table{{{sim::CoreKind::Rigid, "rigid"}, {sim::CoreKind::Lost, "lost"}}};
};
template <>
struct sim::EnumNames<sim::CastKind> {
    static constexpr std::array<std::pair<sim::CastKind, const char*>, 2> table{{{sim::CastKind::Whole, "whole"}, {sim::CastKind::Halves, "halves"}}};
};
template <>
struct sim::EnumNames<sim::WallSide> {
    static constexpr std::array<std::pair<sim::WallSide, const char*>, 2> table{{{sim::WallSide::Centred, "centred"}, {sim::WallSide::Outward, "outward"}}};
};
