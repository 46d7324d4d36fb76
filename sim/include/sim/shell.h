// The models of record (docs/models/shell.md): `membrane`, an incompressible hyperelastic thin sheet, and
// `shell`, the membrane plus discrete-shell bending; a tube of silicone in millimetres, newtons and
// megapascals (N/mm^2), closed by end caps, held by rigid clamps, loaded by pressure (or a sealed gas,
// a prescribed volume, an axial force), solved to static equilibrium by Newton's method on Eigen's
// sparse LDLT. Contraction, blocking force, stiffness, stretch and stress come out in physical units.
//
// Evaluation is a pure function of (shape, ShellDef): safe to call from many threads.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "sim/mesh.h"
#include "sim/result.h"
#include "sim/names.h"
#include "sim/shape.h"
#include "sim/status.h"
#include "sim/surface.h"

namespace sim {

enum class ModelKind {
    Thesis,    // the 2019 thesis's mass-spring model (docs/models/thesis.md), kept exact for reproduction
    Membrane,  // hyperelastic membrane, no bending: verification and speed
    Shell,     // membrane plus discrete-shell bending: the default for new studies
};

enum class MaterialLaw { NeoHookean, MooneyRivlin, Yeoh };

// Silicones (docs/guide/materials.md): the first five fitted to measured tensile curves, the
// `...Datasheet` ones from their suppliers' 100 % moduli (the constants studies used before the
// fits). `Custom` keeps the constants given.
enum class MaterialPreset {
    Ecoflex0030, Ecoflex0050, DragonSkin10, DragonSkin20, DragonSkin30, Elastosil4601,
    Ecoflex0030Datasheet, Ecoflex0050Datasheet, DragonSkin10Datasheet, DragonSkin20Datasheet, DragonSkin30Datasheet,
    Custom };

// How the actuator is loaded.
enum class ShellLoad {
    Inflate,  // prescribed gauge pressure, raised in steps to the target
    Gas,      // a sealed charge of gas at the target pressure, isothermal (p V = const) as it deforms
    Volume,   // prescribed enclosed volume (follows the curve past the pressure maximum)
    Force,    // an axial force on the top clamp, no pressure
    Blocked,  // the target pressure with the top clamp held: the blocking force
};

// How the tube's ends are held.
enum class EndCondition {
    Clamped,  // rigid clamps: the end rings keep their shape; the top clamp slides along the axis
    Sliding,  // end plates the end rings slide on: free radially, held axially (closed-form checks)
};

// The clamp of the thesis-sized tube (L = 150 mm) as two clamp rings held it on the 30-ring mesh:
// one ring spacing, 150 / 29 mm. Fixed in millimetres, so that refining the mesh refines the same
// problem (at 59 rings the clamp holds three rings).
inline constexpr double kThesisTubeClampMm = 150.0 / 29.0;
// How much each ring spacing of a graded mesh grows over the one before it, from a clamp's edge
// toward the middle: slow enough that neighbouring triangles stay alike.
inline constexpr double kRingGrowth = 1.25;

struct GeometryDef {
    double radiusMm = 5;      // base radius R: one thesis radius unit
    double lengthMm = 150;    // between the ends, including the clamped rings
    double thicknessMm = 1;   // wall thickness h
    int ringVertices = 30;    // vertices per ring
    int rings = 30;           // rings along the length; 0: chosen so that triangles are near equilateral.
                              // 30, the thesis's mesh size: near-equilateral at R = 5, L = 150 is 30 x 166
                              // and 30 times slower, for a contraction within 1 % (the mesh study of
                              // the reproduce chapter)
    double clampMm = kThesisTubeClampMm;  // length each end clamp holds, mm: a property of the fixture,
                              // not of the mesh. The mesh puts a ring at the clamp's edge and the
                              // clamp holds every ring within it (ClampRingCount)
    double edgeSpacingMm = 1;  // ring spacing at each clamp's edge, mm, growing by kRingGrowth a ring
                              // up to the middle's (RingHeightsMm): rings added where the wall bends
                              // hardest, within about sqrt(R h) = 2.2 mm of each clamp of the thesis
                              // tube; 0: evenly spaced rings. At 1 (a wall thickness), 30 rings
                              // become 40 and the plain tube, the A = 1.3 sine and the +/-30 and
                              // +/-70 deg braids at 1 kPa are 3.6, 2.8, 0.0 and 1.1 % off the
                              // converged contraction (evenly spaced: 7.3, 4.8, 0.3, 7.9 %). Finer
                              // edges converge for those four but not for designs strained hardest
                              // at the clamp's edge (docs/models/shell.md section 2)
    EndCondition ends = EndCondition::Clamped;
};

// A silicone. The values come from a preset (MaterialPresetDef, where each is written once, with its
// source); any may be overridden.
struct MaterialDef {
    MaterialPreset preset = MaterialPreset::Custom;
    MaterialLaw law = MaterialLaw::NeoHookean;
    double muKpa = 0;                  // neo-Hookean small-strain shear modulus, kPa
    double c10Kpa = 0, c01Kpa = 0;     // Mooney-Rivlin constants, kPa (shear modulus 2 (C10 + C01))
    double c20Kpa = 0, c30Kpa = 0;     // Yeoh's higher constants, kPa (C10 is shared with Mooney-Rivlin)
    double tensileStrengthKpa = 0;     // supplier's tensile strength, kPa
    double elongationAtBreak = 0;      // supplier's elongation at break as a fraction (900 % = 9)
    double stretchLimit = 0;           // largest allowed principal stretch; 0: 1 + elongationAtBreak / 2
                                       // (a material with neither is refused: no run may be over-stretched
                                       // for want of a limit)
    double densityKgPerM3 = 0;         // for silicone volume and mass
};
// The preset's constants and limits, with their sources (materials.cpp).
MaterialDef MaterialPresetDef(MaterialPreset preset);
// The small-strain shear modulus of a material, kPa.
double ShearModulusKpa(const MaterialDef& material);
double StretchLimit(const MaterialDef& material);

// How the top clamp may turn about the tube's axis (docs/models/shell.md section 12); the bottom
// clamp is fixed.
enum class TwistEnd {
    Free,    // turns as the wall makes it (a bench's top on a bearing): the default
    Held,    // kept from turning; the torque that holds it is an output
    Loaded,  // a prescribed torque turns it
};

// The top clamp's lateral translation and tilt, together (docs/models/shell.md section 12).
enum class TipEnd {
    Held,  // kept on the axis and square to it (a bench's guided top): the default; the lateral force
           // and bending moment that hold it are outputs
    Free,  // moves and tilts as the wall makes it (a bending actuator's free end)
};

struct LoadDef {
    ShellLoad kind = ShellLoad::Inflate;
    double pressureKpa = 3;    // target gauge pressure (Inflate, Gas, Blocked); negative is vacuum
    double forceN = 0;         // axial force on the top clamp, + pulls it up: alone (Force), or with
                               // the pressure or volume (Inflate, Gas, Volume: a hanging load)
    double volumeRatio = 1.5;  // target enclosed volume over the rest volume (Volume)
    double strokePercent = 0;  // Blocked: the top held this far below its rest place, % of the
                               // length (the isobaric test; 0: the blocking force)
    double strokeMm = 0;       // Blocked: the same in mm, for a bench set by its travel (one of the two, not both)
    int steps = 4;             // load steps: the contraction-pressure curve's points
    int isobaricPoints = 0;    // Inflate: after the free inflation, the top held at this many strokes from none
                               // to the free stroke (the isobaric curve and the work of one stroke); 0: none
};
// A negative pressure: the walls collapse onto each other.
inline bool UnderVacuum(const LoadDef& load) { return load.pressureKpa < 0; }

// Stiff threads on the wall (docs/models/shell.md section 7): fibre families as directions in the rest tangent
// plane at an angle to the meridian, tension only, energy (k/4)(I4 - 1)^2 per rest area.
enum class FibreLayout {
    None,
    Meridian,  // one family along the meridian (alpha = 0): the pleated-muscle mechanism
    Hoop,      // one family around the tube (alpha = 90 deg)
    Single,    // one family at +alpha
    Braid,     // +alpha and -alpha: a McKibben braid
};

// A band of the tube's length whose fibres run at their own angle.
struct FibreBand {
    double from = 0, to = 1;  // fractions of the length, 0 at the bottom end
    double angleDeg = 0;      // to the meridian
};

struct FibreDef {
    FibreLayout layout = FibreLayout::None;
    double angleDeg = 30;                 // to the meridian: braid +/- this, single + this
    double stiffnessNPerMm = 50;          // per family and unit width: about 1,300 mu h of Ecoflex 00-30 at
                                          // 1 mm, near the inextensible limit
    std::vector<FibreBand> bands;         // angles by band along the length (covering 0 to 1); empty: angleDeg
    std::vector<double> sectorAnglesDeg;  // or angles by angular sector, as the thesis's B-spline sectors
    bool plus = true, minus = true;       // which families are on (+alpha, and a braid's -alpha): GA genes
};

// Fibre families the wall carries: a braid's switched-on families (0-2), a single family when on,
// meridian and hoop fibres always one, none without fibres. The one rule the model and its reports use.
int FamiliesOn(const FibreDef& fibres);

// The angle to the meridian (degrees) of the +alpha family at a rest point: by band of its height
// (a fraction of the length), by sector of its angle (radians from +x), or the def's one angle.
double FibreAngleDegAt(const FibreDef& fibres, double heightFraction, double angle);

struct SolverDef {
    double tolerance = 1e-8;   // converged when the largest free-node force is below this x mu h l
    int maxIterations = 200;   // Newton iterations per load step (wrinkled walls need 100+)
    int maxBisections = 6;     // a failed step is halved at most this often (down to 1/64)
    int newtonBudget = 2000;   // Newton iterations for the whole evaluation (every load step, stability
                               // check, blocking force and held stroke); past it the status is
                               // budget-exceeded. Counted, not timed, so the same on every machine.
                               // 0: no budget. Chosen from the shipped searches' distribution
                               // (docs/performance.md, per-evaluation budget).
    bool selfContact = true;   // check every converged state for self-intersection
    double heldPushDiameters = 1;  // a stable held state that pushes on its clamps is pushed this many tube
                                   // diameters (2 R) along its softest direction and minimised again, and
                                   // a lower state found so (a bowed tube) is reported; 0: not pushed
                                   // (docs/models/shell.md section 12, held states that bow)
};

// The top clamp as a bench fixture holds it (docs/models/shell.md section 12): the axial motion is
// the load's (free, loaded by force_n, or held at a stroke); these are its other degrees of freedom.
struct EndsDef {
    TwistEnd twist = TwistEnd::Free;  // a free top turns as the fibres wind it
    double torqueNMm = 0;             // twist Loaded: torque on the top clamp, N mm, + turns it right-handed about +z
    TipEnd tip = TipEnd::Held;        // lateral translation and tilt
};

// The bounds a bench puts on a design (docs/models/shell.md section 12, envelope): a rest design beyond any
// of them is the status outside-envelope, judged before anything is simulated, so a search learns
// of it as of any failed design and nothing is clamped. 0: no bound.
struct EnvelopeDef {
    double maxRadiusRatio = 0;  // the rest wall's largest distance from the axis over the base radius
    double maxRadiusMm = 0;     // the same in mm
    double maxSiliconeG = 0;    // the wall's silicone (rest area x thickness x the material's density), g
    bool Any() const { return maxRadiusRatio > 0 || maxRadiusMm > 0 || maxSiliconeG > 0; }
};

// Self-contact (docs/models/shell.md section 8).
enum class ContactMode {
    Off,  // a converged state that passes through itself ends self-intersection (the design is discarded)
    On,   // walls touch: a barrier keeps the mid-surfaces at least a wall thickness apart
};
struct ContactDef {
    ContactMode mode = ContactMode::On;  // no design passes through itself; off is cheaper where walls never meet
    double gapFraction = 0.1;   // s_hat / h: walls closer than h (1 + this) push each other apart; in
                                // contact they rest between h and that apart
    double stiffness = 1;       // kappa / (mu h): the barrier's strength against the wall's (IPC's kappa)
};

struct ShellDef {
    GeometryDef geometry;
    MaterialDef material = MaterialPresetDef(MaterialPreset::Ecoflex0030);
    LoadDef load;
    EndsDef ends;
    SolverDef solver;
    FibreDef fibres;
    EnvelopeDef envelope;
    ContactDef contact;
};
ShellDef DefaultShellDef();

// Empty when the definition is usable; otherwise what is wrong, for a user to read.
std::string ShellDefError(const ShellDef& def);

// The mesh size a definition gives: rings chosen for near-equilateral triangles when rings is 0, and
// the rings a graded mesh adds toward the clamps (RingHeightsMm).
int RingCount(const GeometryDef& geometry);
// Whether the rings are graded toward the clamps (RingHeightsMm): more rings than `rings`.
bool RingsGraded(const GeometryDef& geometry);
// Ring spacings each clamp spans, so that a ring falls on its edge. Evenly spaced rings: the clamp's
// length in whole spacings (at least one). Graded: two, the one at the clamp's edge as long as the
// first free one (a hinge there sees alike triangles on both sides), or one when the clamp is shorter
// than two edge spacings.
int ClampIntervals(const GeometryDef& geometry);
// Rings each clamp holds, its edge ring included: ClampIntervals + 1.
int ClampRingCount(const GeometryDef& geometry);
// Every ring's height, mm, from 0 to lengthMm. Evenly spaced: clamp intervals of
// clampMm / ClampIntervals at each end and equal intervals between (the uniform L j / (H - 1) when
// the clamp falls on a ring of it). Graded (clamped ends, 0 < edgeSpacingMm < L / (rings - 1)): the
// middle keeps the spacing `rings` evenly spaced would give, and from each clamp's edge the spacings
// grow from edgeSpacingMm by kRingGrowth a ring up to it, so that RingCount is more than `rings`.
std::vector<double> RingHeightsMm(const GeometryDef& geometry);

// The memory one evaluation needs, estimated from its mesh before anything is built: 1,750 bytes x
// V log2 V (the sparse factor's fill under nested dissection and the solver's workspaces; fitted to
// the peak resident memory of shell evaluations from 30 x 30 to 240 x 240 vertices, within 5 %) and
// the positions kept at every load step.
double EvaluationBytesEstimate(const ShellDef& def);
// The largest evaluation accepted: 8 GiB, about 270,000 vertices (520 x 520). A larger one is refused
// up front, before any allocation (ShellDefError).
constexpr double kMaxEvaluationBytes = 8.0 * 1024 * 1024 * 1024;

// A design evaluated under a shell model (bending on: `shell`; off: `membrane`). Pure and thread-safe.
SimResult EvaluateShell(const Shape& shape, const ShellDef& def, bool bending);

// The isobaric test as a bench does it: the design evaluated as EvaluateShell does under
// `inflate` (its free stroke), then, from that free state, the top held at fractions of the free
// stroke in turn, from the largest down (each held state from the last), the force and twist read
// at each. Points in increasing order of stroke; none when the free inflation failed. A point that
// fails has its status and NaN numbers.
struct IsobaricPoint {
    double strokePercent = 0;  // contraction held, % of the length
    double forceN = NAN;       // the force the muscle pulls with there (+ pulls on its supports)
    double twistDeg = NAN;
    Status status = Status::Ok;
    // The held state measured as an evaluation of the blocked test at this stroke would measure it
    // (its meshes and every output, for archives and pictures); for a point that failed, its status
    // on the rest shape. A held state that stretches the wall past its limit is over-stretched.
    SimResult state;
};
struct IsobaricCurve {
    SimResult free;  // EvaluateShell's result under `inflate` with the isobaric outputs
    std::vector<IsobaricPoint> points;
};
// `inflate`'s load is inflation with its isobaricPoints (2 or more) set.
IsobaricCurve IsobaricForces(const Shape& shape, const ShellDef& inflate, bool bending);

// The work of one stroke, mJ (N mm): the isobaric force integrated over the contraction by
// trapezoids, from no contraction to the free stroke; NaN when a point failed or there is none.
double StrokeWorkMj(const std::vector<double>& contractionPercent, const std::vector<double>& forceN, double lengthMm);

// The silicone of the design's wall at rest, mm^3: its mid-surface's area times the wall thickness
// (the clamps' rings included; the caps are the fixture's). NaN when the tube cannot be built.
double WallVolumeMm3(const Shape& shape, const ShellDef& def);

// The wall's triangles (and caps) and edges for drawing, in the model's vertex order.
Surface ShellSurface(const GeometryDef& geometry);

// Per-vertex largest principal stretch and true stress (kPa) of a deformed shell, averaged from the
// triangles around each vertex: for colour maps.
// A fibre drawn as a dash across its triangle: centre (on the outer face), unit direction, half
// length, and the fibre's stretch.
struct FibreDash {
    double centre[3], along[3];
    double halfLengthMm = 0;
    double stretch = 1;
};
struct ShellFields {
    std::vector<double> stretch, stressKpa;
    std::vector<FibreDash> fibres;  // one per wall triangle and fibre family
};
ShellFields ShellFieldValues(const ShellDef& def, const Shape& shape, bool bending, const Positions& deformed);
// Self-contact on: per vertex, the gap between its wall and the nearest other wall beyond a wall
// thickness (mm; 0 where they touch), over the pairs it belongs to within a wall thickness of
// touching; NaN where no other wall is that near. Empty when contact is off or the tube cannot be built.
std::vector<double> ContactGapValues(const ShellDef& def, const Shape& shape, const Positions& deformed);

// The wall's state cell by cell, for field files (VTU): one value per triangle of ShellSurface (the
// wall's triangles, then the caps'). NaN where a field has no value: the caps (the fixture's, not
// silicone) for the wall's fields, a triangle without that fibre family for the fibre's. Empty
// (no cells) when the tube cannot be built or `deformed` is not its mesh.
enum class WallRegion { Wall = 0, Clamped = 1, Cap = 2 };  // a wall triangle within a clamp's rings is Clamped
struct WallCells {
    std::vector<int> region;                            // WallRegion per cell
    std::vector<double> stretchMax, stretchMin;         // principal stretches in the wall's plane
    std::vector<double> stressMaxKpa, stressMinKpa;     // principal true (Cauchy) stresses, kPa
    std::vector<double> thicknessMm;                    // the deformed wall: rest thickness / (stretchMax stretchMin)
    int families = 0;                                   // fibre families the design has (0-2)
    std::array<std::vector<std::array<double, 3>>, 2> fibreDirection;  // unit, deformed
    std::array<std::vector<double>, 2> fibreStrain;     // stretch - 1 (negative: slack)
    std::array<std::vector<double>, 2> fibreTensionNPerMm;  // per mm of rest width across the threads; 0 when slack
};
WallCells WallCellValues(const ShellDef& def, const Shape& shape, bool bending, const Positions& deformed);

}  // namespace sim

template <>
struct sim::EnumNames<sim::ModelKind> {
    static constexpr std::array<std::pair<sim::ModelKind, const char*>, 3> table{
        {{sim::ModelKind::Thesis, "thesis"}, {sim::ModelKind::Membrane, "membrane"}, {sim::ModelKind::Shell, "shell"}}};
};
template <>
struct sim::EnumNames<sim::MaterialLaw> {
    static constexpr std::array<std::pair<sim::MaterialLaw, const char*>, 3> table{
        {{sim::MaterialLaw::NeoHookean, "neo-hookean"}, {sim::MaterialLaw::MooneyRivlin, "mooney-rivlin"}, {sim::MaterialLaw::Yeoh, "yeoh"}}};
};
template <>
struct sim::EnumNames<sim::MaterialPreset> {
    static constexpr std::array<std::pair<sim::MaterialPreset, const char*>, 12> table{{
        {sim::MaterialPreset::Ecoflex0030, "ecoflex-00-30"},
        {sim::MaterialPreset::Ecoflex0050, "ecoflex-00-50"},
        {sim::MaterialPreset::DragonSkin10, "dragon-skin-10"},
        {sim::MaterialPreset::DragonSkin20, "dragon-skin-20"},
        {sim::MaterialPreset::DragonSkin30, "dragon-skin-30"},
        {sim::MaterialPreset::Elastosil4601, "elastosil-m4601"},
        {sim::MaterialPreset::Ecoflex0030Datasheet, "ecoflex-00-30-datasheet"},
        {sim::MaterialPreset::Ecoflex0050Datasheet, "ecoflex-00-50-datasheet"},
        {sim::MaterialPreset::DragonSkin10Datasheet, "dragon-skin-10-datasheet"},
        {sim::MaterialPreset::DragonSkin20Datasheet, "dragon-skin-20-datasheet"},
        {sim::MaterialPreset::DragonSkin30Datasheet, "dragon-skin-30-datasheet"},
        {sim::MaterialPreset::Custom, "custom"},
    }};
};
template <>
struct sim::EnumNames<sim::ShellLoad> {
    static constexpr std::array<std::pair<sim::ShellLoad, const char*>, 5> table{{{sim::ShellLoad::Inflate, "inflate"},
                                                                                   {sim::ShellLoad::Gas, "gas"},
                                                                                   {sim::ShellLoad::Volume, "volume"},
                                                                                   {sim::ShellLoad::Force, "force"},
                                                                                   {sim::ShellLoad::Blocked, "blocked"}}};
};
template <>
struct sim::EnumNames<sim::FibreLayout> {
    static constexpr std::array<std::pair<sim::FibreLayout, const char*>, 5> table{{{sim::FibreLayout::None, "none"},
                                                                                     {sim::FibreLayout::Meridian, "meridian"},
                                                                                     {sim::FibreLayout::Hoop, "hoop"},
                                                                                     {sim::FibreLayout::Braid, "braid"},
                                                                                     {sim::FibreLayout::Single, "single"}}};
};
template <>
struct sim::EnumNames<sim::TwistEnd> {
    static constexpr std::array<std::pair<sim::TwistEnd, const char*>, 3> table{
        {{sim::TwistEnd::Free, "free"}, {sim::TwistEnd::Held, "held"}, {sim::TwistEnd::Loaded, "loaded"}}};
};
template <>
struct sim::EnumNames<sim::ContactMode> {
    static constexpr std::array<std::pair<sim::ContactMode, const char*>, 2> table{{{sim::ContactMode::Off, "off"}, {sim::ContactMode::On, "on"}}};
};
template <>
struct sim::EnumNames<sim::TipEnd> {
    static constexpr std::array<std::pair<sim::TipEnd, const char*>, 2> table{{{sim::TipEnd::Held, "held"}, {sim::TipEnd::Free, "free"}}};
};
template <>
struct sim::EnumNames<sim::EndCondition> {
    static constexpr std::array<std::pair<sim::EndCondition, const char*>, 2> table{
        {{sim::EndCondition::Clamped, "clamped"}, {sim::EndCondition::Sliding, "sliding"}}};
};
