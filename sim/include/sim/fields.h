// Every user-settable field of the models' def structs, listed once: its key in experiment files
// and JSON outputs (the command-line option is the key with '-' for '_'), what it means with its
// unit, and its valid range. The default is whatever the def struct holds. Visitors read the fields
// from JSON (experiment.cpp), bind them to options (cli.cpp) and write them out (json_out.cpp).
//
// A visitor provides:
//   Integer(key, int& value, help, min, max)
//   Number(key, double& value, help, min, max)
//   Enum(key, E& value, help)            (the names come from sim::EnumNames<E>)
// Visiting a const def hands out const references (for writing).
#pragma once

#include <charconv>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sim/batch.h"
#include "sim/mesh.h"
#include "sim/shell.h"
#include "sim/solid.h"
#include "sim/solver.h"

namespace sim {

constexpr double kUnbounded = std::numeric_limits<double>::max();

// The helix of the `thesis` model.
template <class Def, class Visitor>
void VisitFields(Def& mesh, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::MeshDef> {
    v.Integer("resolution", mesh.resolution, "vertices per turn of the helix", sim::kMinResolution, 4096);
    v.Integer("turns", mesh.turns, "turns of the helix (two clamped at each end)", sim::kMinTurns, 4096);
}

// The `thesis` model's constants (docs/models/thesis.md, "One iteration").
template <class Def, class Visitor>
void VisitFields(Def& p, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::SimParams> {
    v.Integer("iterations", p.iterations, "relaxation steps; the fitness is read after the last", 0, sim::kMaxIterations);
    v.Enum("load", p.load, "inflation pressure, the stretch test's pull on the end turns, or no load");
    v.Number("spring_constant", p.springConstant, "spring stiffness k (force per unit of stretch)", 0, kUnbounded);
    v.Number("pressure_scale", p.pressureScale, "inflation scale c_p on the cross-product force", 0, kUnbounded);
    v.Number("pull_force", p.pullForce, "stretch load c_pull on each end-turn vertex", 0, kUnbounded);
    v.Number("step_scale", p.stepScale, "displacement per unit force per iteration (c_step)", 0, kUnbounded);
    v.Number("divergence_limit", p.divergenceLimit, "a coordinate beyond this (mesh units) ends the run as 'diverged'", 1e-300, kUnbounded);
    v.Enum("precision", p.precision, "solver arithmetic; float is about twice as fast and within 0.005 of double in fitness");
}

// The membrane and shell models (docs/models/shell.md). Option names: --radius-mm, --length-mm, ...
template <class Def, class Visitor>
void VisitFields(Def& g, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::GeometryDef> {
    v.Number("radius_mm", g.radiusMm, "base radius, mm: one thesis radius unit", 1e-3, 1e4);
    v.Number("length_mm", g.lengthMm, "length between the ends, clamped rings included, mm", 1e-3, 1e5);
    v.Number("thickness_mm", g.thicknessMm, "wall thickness, mm", 1e-4, 1e3);
    v.Integer("ring_vertices", g.ringVertices, "vertices per ring", 6, 4096);
    v.Integer("rings", g.rings, "rings along the length (0: near-equilateral triangles)", 0, 100000);
    v.Number("clamp_mm", g.clampMm, "length each end clamp holds, mm (the mesh puts a ring at its edge; default one ring spacing of the 30-ring thesis tube)", 1e-3, 1e5);
    v.Number("edge_spacing_mm", g.edgeSpacingMm, "ring spacing at each clamp's edge, mm, growing by a quarter a ring up to the middle's: rings added where the wall bends hardest (0: evenly spaced rings)", 0, 1e5);
    v.Enum("ends", g.ends, "rigid clamps, or end plates the end rings slide on (closed-form checks)");
}

// The material's constants; a preset (--material) sets them all first, these override.
template <class Def, class Visitor>
void VisitFields(Def& m, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::MaterialDef> {
    v.Enum("law", m.law, "hyperelastic law");
    v.Number("mu_kpa", m.muKpa, "neo-Hookean shear modulus, kPa (overrides the preset)", 0, kUnbounded);
    v.Number("c10_kpa", m.c10Kpa, "Mooney-Rivlin and Yeoh C10, kPa", 0, kUnbounded);
    // The higher constants may be negative: a state past the law's stable range is material-unstable.
    v.Number("c01_kpa", m.c01Kpa, "Mooney-Rivlin C01, kPa (may be negative)", -kUnbounded, kUnbounded);
    v.Number("c20_kpa", m.c20Kpa, "Yeoh C20, kPa (may be negative)", -kUnbounded, kUnbounded);
    v.Number("c30_kpa", m.c30Kpa, "Yeoh C30, kPa (may be negative)", -kUnbounded, kUnbounded);
    v.Number("tensile_strength_kpa", m.tensileStrengthKpa, "tensile strength to compare stresses with, kPa", 0, kUnbounded);
    v.Number("elongation_at_break", m.elongationAtBreak, "elongation at break as a fraction (9 = 900 %)", 0, kUnbounded);
    v.Number("stretch_limit", m.stretchLimit, "largest allowed principal stretch (0: 1 + elongation / 2)", 0, kUnbounded);
    v.Number("density_kg_per_m3", m.densityKgPerM3, "density, kg/m^3: the silicone's mass (silicone_g, per-gram objectives, max_silicone_g, exports)", 0, kUnbounded);
}

template <class Def, class Visitor>
void VisitFields(Def& l, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::LoadDef> {
    v.Number("pressure_kpa", l.pressureKpa, "target gauge pressure, kPa (inflate, gas, blocked); negative is vacuum", -1e6, 1e6);
    v.Number("force_n", l.forceN, "axial force on the top clamp, N, + pulls it up: alone (load force) or with the pressure (inflate, gas, volume)",
             -1e6, 1e6);
    v.Number("volume_ratio", l.volumeRatio, "target enclosed volume over the rest volume (load volume)", 1e-3, 1e3);
    v.Number("stroke_percent", l.strokePercent,
             "load blocked: the top held this far below its rest place, % of the length (0: the blocking force)", -100, 100);
    v.Number("stroke_mm", l.strokeMm, "load blocked: the same in mm (give stroke_percent or stroke_mm)", -1e6, 1e6);
    v.Integer("steps", l.steps, "load steps: points of the contraction-pressure curve", 1, 1000);
    v.Integer("isobaric_points", l.isobaricPoints,
              "load inflate: after the free inflation, the top held at this many strokes from none to the free stroke: the isobaric curve "
              "and the work of one stroke (0: none)",
              0, 100);
}

template <class Def, class Visitor>
void VisitFields(Def& e, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::EndsDef> {
    v.Enum("twist", e.twist, "the top clamp's turn about the axis: free, held (its torque reported) or loaded (torque_n_mm)");
    v.Number("torque_n_mm", e.torqueNMm, "twist loaded: torque on the top clamp, N mm, + right-handed about +z", -1e9, 1e9);
    v.Enum("tip", e.tip, "the top clamp's lateral translation and tilt, together: held (the force and moment that hold it reported) or free "
                         "(a bending actuator's free end)");
}

template <class Def, class Visitor>
void VisitFields(Def& e, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::EnvelopeDef> {
    v.Number("max_radius_ratio", e.maxRadiusRatio, "envelope: the rest wall's largest radius over the base radius (0: no bound); beyond it the design is outside-envelope", 0, 1e4);
    v.Number("max_radius_mm", e.maxRadiusMm, "envelope: the same in mm (0: no bound)", 0, 1e6);
    v.Number("max_silicone_g", e.maxSiliconeG, "envelope: the wall's silicone at rest, g, at the material's density (0: no bound)", 0, 1e6);
}

template <class Def, class Visitor>
void VisitFields(Def& c, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::ContactDef> {
    v.Enum("contact", c.mode, "self-contact: on, walls touch and rest a wall thickness apart (a barrier; vacuum actuators need it); off, a state "
                              "that passes through itself is the status self-intersection");
    v.Number("contact_gap_fraction", c.gapFraction, "contact on: the barrier's reach beyond a wall thickness, as a fraction of it (touching walls rest "
                                                    "between h and h (1 + this) apart)", 1e-4, 1);
    v.Number("contact_stiffness", c.stiffness, "contact on: the barrier's strength kappa over the wall's mu h", 1e-6, 1e6);
}

template <class Def, class Visitor>
void VisitFields(Def& s, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::SolverDef> {
    v.Number("tolerance", s.tolerance, "converged when the largest free-node force is below this x mu h l", 1e-16, 1e-2);
    v.Integer("max_iterations", s.maxIterations, "Newton iterations per load step", 1, 10000);
    v.Integer("max_bisections", s.maxBisections, "times a failed load step may be halved", 0, 30);
    v.Integer("newton_budget", s.newtonBudget, "Newton iterations for the whole evaluation, past which it is budget-exceeded (0: none)", 0, 10000000);
    v.Number("held_push_diameters", s.heldPushDiameters, "a held state pushing on its clamps is pushed this many tube diameters sideways and "
                                                         "minimised again; a lower (bowed) state found so is reported (0: not pushed)", 0, 10);
}

namespace detail {
// The given material's values by key (enums by their index), then set over a preset's.
struct MaterialCollector {
    std::map<std::string, double>& values;
    void Integer(const char* key, const int& v, const char*, long long, long long) { values[key] = v; }
    void Number(const char* key, const double& v, const char*, double, double) { values[key] = v; }
    template <class E>
    void Enum(const char* key, const E& v, const char*) {
        values[key] = static_cast<double>(static_cast<int>(v));
    }
};
struct MaterialSetter {
    const std::map<std::string, double>& values;
    const std::function<bool(const char*)>& isGiven;
    void Integer(const char* key, int& v, const char*, long long, long long) {
        if (isGiven(key)) v = static_cast<int>(values.at(key));
    }
    void Number(const char* key, double& v, const char*, double, double) {
        if (isGiven(key)) v = values.at(key);
    }
    template <class E>
    void Enum(const char* key, E& v, const char*) {
        if (isGiven(key)) v = static_cast<E>(static_cast<int>(values.at(key)));
    }
};
}  // namespace detail

// Fibres on the wall (docs/models/shell.md section 7). Bands and sectors of angles are experiment-file lists
// (fibre_bands, fibre_sectors_deg), not fields.
template <class Def, class Visitor>
void VisitFields(Def& f, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::FibreDef> {
    v.Enum("fibres", f.layout, "fibres on the wall: none, meridian (alpha 0), hoop (90 deg), braid (+/- alpha) or single (+alpha)");
    v.Number("fibre_angle_deg", f.angleDeg, "fibre angle to the meridian, degrees (braid and single)", -90, 90);
    v.Number("fibre_stiffness_n_per_mm", f.stiffnessNPerMm, "stiffness of each fibre family per unit width, N/mm (1e4 mu h: nearly inextensible)", 0,
             kUnbounded);
}

// A preset's material with the fields `isGiven` names taken from `given` (an option or experiment
// key given by the user overrides the preset's value). A neo-Hookean modulus given over a preset of
// another law switches to neo-Hookean, unless the law is given too.
inline sim::MaterialDef MaterialWithOverrides(sim::MaterialDef material, const sim::MaterialDef& given,
                                              const std::function<bool(const char* key)>& isGiven) {
    std::map<std::string, double> values;
    VisitFields(given, detail::MaterialCollector{values});
    VisitFields(material, detail::MaterialSetter{values, isGiven});
    if (isGiven("mu_kpa") && !isGiven("law")) material.law = sim::MaterialLaw::NeoHookean;
    return material;  // named after the preset it started from (custom for a file); the fields say what changed
}
inline sim::MaterialDef MaterialWithOverrides(sim::MaterialPreset preset, const sim::MaterialDef& given,
                                              const std::function<bool(const char* key)>& isGiven) {
    sim::MaterialDef base = preset == sim::MaterialPreset::Custom ? sim::MaterialDef{} : sim::MaterialPresetDef(preset);
    base.preset = preset;
    return MaterialWithOverrides(base, given, isGiven);
}

// The mold around an exported part (sim/solid.h). Option names: --margin-mm, --end-wall-mm, ...
template <class Def, class Visitor>
void VisitFields(Def& m, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::MoldDef> {
    v.Number("margin_mm", m.marginMm, "block beyond the actuator's widest point, mm", 0.1, 1e4);
    v.Number("end_wall_mm", m.endWallMm, "block beyond each end of the actuator, mm", 0.1, 1e4);
    v.Number("handle_mm", m.handleMm, "core beyond the block at each end, to hold and pull it, mm", 0.1, 1e4);
    v.Number("sprue_deg", m.sprueDegrees, "arc of the sprue through shell A's bottom wall, centred at 90 degrees (0: sized for --sprue-mm and the flow)", 0, 120);
    v.Number("sprue_mm", m.sprueMm, "the sprue's least width, both ways, mm (reaches outward past the wall when the wall is thinner)", 0.1, 50);
    v.Number("vent_deg", m.ventDegrees, "arc of each of the four vents through the top wall (45 and 135 degrees in A, 225 and 315 in B)", 0, 60);
    v.Number("pin_clearance_mm", m.pinClearanceMm, "the registration pins' taper: their tops this much inside their holes, mm", 0, 10);
    v.Enum("core", m.core, "rigid: one piece, pulled out through an end (refused where the wall cannot stretch over it); lost: printed to dissolve or melt out, with a drain");
    v.Number("drain_mm", m.drainMm, "core lost: diameter of the drain bored along the core's axis, mm (0: up to 4, leaving 1 mm of core)", 0, 1e3);
}

// Where a field has an effect, for refusing one that is given where it has none. `decider` is empty
// when the field applies under the definition; otherwise it is the key of the field that decides
// ("kind" of the load, "law", "ends", "fibres"), with the values under which the field applies and
// the value the decider has.
struct FieldUse {
    std::string decider, values, now;
    bool Applies() const { return decider.empty(); }
};

inline FieldUse ShellFieldUse(const sim::ShellDef& def, std::string_view key) {
    auto unless = [](bool applies, const char* decider, std::string values, const char* now) {
        return applies ? FieldUse{} : FieldUse{decider, std::move(values), now};
    };
    const sim::ShellLoad load = def.load.kind;
    const sim::MaterialLaw law = def.material.law;
    const sim::FibreLayout fibres = def.fibres.layout;
    using L = sim::ShellLoad;
    using M = sim::MaterialLaw;
    if (key == "pressure_kpa") return unless(load == L::Inflate || load == L::Gas || load == L::Blocked, "kind", "inflate, gas or blocked", sim::Name(load));
    if (key == "force_n") return unless(load != L::Blocked, "kind", "inflate, gas, volume or force", sim::Name(load));
    if (key == "stroke_percent" || key == "stroke_mm") return unless(load == L::Blocked, "kind", "blocked", sim::Name(load));
    if (key == "isobaric_points") return unless(load == L::Inflate, "kind", "inflate", sim::Name(load));
    // The held states it pushes: the blocking force (inflate, gas), the held strokes, a blocked test.
    if (key == "held_push_diameters") return unless(load == L::Inflate || load == L::Gas || load == L::Blocked, "kind", "inflate, gas or blocked", sim::Name(load));
    if (key == "torque_n_mm") return unless(def.ends.twist == sim::TwistEnd::Loaded, "twist", "loaded", sim::Name(def.ends.twist));
    // Sliding ends hold the tube's rotation by an anchor; only clamps turn.
    if (key == "twist" || key == "tip") return unless(def.geometry.ends == sim::EndCondition::Clamped, "ends", "clamped", sim::Name(def.geometry.ends));
    if (key == "volume_ratio") return unless(load == L::Volume, "kind", "volume", sim::Name(load));
    // Volume control follows its steps as they are; the others halve a step that fails.
    if (key == "max_bisections") return unless(load != L::Volume, "kind", "inflate, gas, force or blocked", sim::Name(load));
    if (key == "mu_kpa") return unless(law == M::NeoHookean, "law", "neo-hookean", sim::Name(law));
    if (key == "c10_kpa") return unless(law != M::NeoHookean, "law", "mooney-rivlin or yeoh", sim::Name(law));
    if (key == "c01_kpa") return unless(law == M::MooneyRivlin, "law", "mooney-rivlin", sim::Name(law));
    if (key == "c20_kpa" || key == "c30_kpa") return unless(law == M::Yeoh, "law", "yeoh", sim::Name(law));
    // Sliding ends hold the end rings alone; the clamp's rings are a clamp's.
    if (key == "clamp_mm" || key == "edge_spacing_mm") return unless(def.geometry.ends == sim::EndCondition::Clamped, "ends", "clamped", sim::Name(def.geometry.ends));
    if (key == "contact_gap_fraction" || key == "contact_stiffness")
        return unless(def.contact.mode == sim::ContactMode::On, "contact", "on", sim::Name(def.contact.mode));
    if (key == "fibre_stiffness_n_per_mm") return unless(fibres != sim::FibreLayout::None, "fibres", "meridian, hoop, braid or single", sim::Name(fibres));
    // Angles by band or sector replace a braid's or a single family's one angle.
    if (key == "fibre_bands" || key == "fibre_sectors_deg")
        return unless(fibres == sim::FibreLayout::Braid || fibres == sim::FibreLayout::Single, "fibres", "braid or single", sim::Name(fibres));
    if (key == "fibre_angle_deg") {
        // Meridian and hoop fibres have their angle (0 and 90 degrees); bands and sectors give their own.
        if (!def.fibres.bands.empty() || !def.fibres.sectorAnglesDeg.empty())
            return FieldUse{def.fibres.bands.empty() ? "fibre_sectors_deg" : "fibre_bands", "none given", "given"};
        return unless(fibres == sim::FibreLayout::Braid || fibres == sim::FibreLayout::Single, "fibres", "braid or single", sim::Name(fibres));
    }
    return {};
}

inline FieldUse ThesisFieldUse(const sim::SimParams& p, std::string_view key) {
    // With no load the rest shape is at rest: nothing moves, whatever its springs or step.
    if ((key == "spring_constant" || key == "step_scale") && p.load == sim::Load::None) return FieldUse{"load", "inflate or stretch", "none"};
    if (key == "pressure_scale" && p.load != sim::Load::Inflate) return FieldUse{"load", "inflate", sim::Name(p.load)};
    if (key == "pull_force" && p.load != sim::Load::Stretch) return FieldUse{"load", "stretch", sim::Name(p.load)};
    return {};
}

namespace detail {
// The keys of the fields whose value in `def` differs from that in `reference`.
template <class Def>
struct ChangeFinder {
    const Def& def;
    const Def& reference;
    std::vector<std::string>& keys;
    template <class T>
    const T& Same(const T& field) const {
        const auto offset = reinterpret_cast<const char*>(&field) - reinterpret_cast<const char*>(&def);
        return *reinterpret_cast<const T*>(reinterpret_cast<const char*>(&reference) + offset);
    }
    void Integer(const char* key, const int& v, const char*, long long, long long) {
        if (v != Same(v)) keys.push_back(key);
    }
    void Number(const char* key, const double& v, const char*, double, double) {
        if (!(v == Same(v))) keys.push_back(key);
    }
    template <class E>
    void Enum(const char* key, const E& v, const char*) {
        if (v != Same(v)) keys.push_back(key);
    }
};
}  // namespace detail

template <class Def>
std::vector<std::string> ChangedKeys(const Def& def, const Def& reference) {
    std::vector<std::string> keys;
    VisitFields(def, detail::ChangeFinder<Def>{def, reference, keys});
    return keys;
}

// For definitions made without a command line (Python): the first field set away from its default
// (the material's: its preset's) that has no effect, as "force_n: has no effect: it applies when kind
// is force, not inflate"; empty when there is none.
inline std::string ShellFieldsWithoutEffect(const sim::ShellDef& def) {
    const sim::ShellDef defaults = sim::DefaultShellDef();
    const sim::MaterialDef preset = def.material.preset == sim::MaterialPreset::Custom ? sim::MaterialDef{} : sim::MaterialPresetDef(def.material.preset);
    std::vector<std::string> keys;
    for (const auto& part : {ChangedKeys(def.geometry, defaults.geometry), ChangedKeys(def.material, preset), ChangedKeys(def.load, defaults.load), ChangedKeys(def.ends, defaults.ends),
                             ChangedKeys(def.solver, defaults.solver), ChangedKeys(def.fibres, defaults.fibres), ChangedKeys(def.envelope, defaults.envelope),
                             ChangedKeys(def.contact, defaults.contact)})
        keys.insert(keys.end(), part.begin(), part.end());
    for (const auto& key : keys)
        if (const FieldUse use = ShellFieldUse(def, key); !use.Applies())
            return key + ": has no effect: it applies when " + use.decider + " is " + use.values + ", not " + use.now;
    return "";
}

namespace detail {
// The first field outside its range, as "key: value is out of range (min to max)".
struct RangeChecker {
    std::string& error;
    // The shortest text that reads back as the same number ("1000000", "0.15").
    static std::string Shortest(double v) {
        char text[32];
        const auto end = std::to_chars(text, text + sizeof text, v).ptr;
        return std::string(text, end);
    }
    static std::string Bound(double b) { return b == -kUnbounded || b == kUnbounded ? std::string("any") : Shortest(b); }
    void Integer(const char* key, const int& v, const char*, long long min, long long max) {
        if (error.empty() && (v < min || v > max))
            error = std::string(key) + ": " + std::to_string(v) + " is out of range (" + std::to_string(min) + " to " + std::to_string(max) + ")";
    }
    void Number(const char* key, const double& v, const char*, double min, double max) {
        if (error.empty() && !(v >= min && v <= max))
            error = std::string(key) + ": " + Shortest(v) + " is out of range (" + Bound(min) + " to " + Bound(max) + ")";
    }
    template <class E>
    void Enum(const char* key, const E& v, const char*) {
        if (error.empty() && sim::Name(v) == std::string("?")) error = std::string(key) + ": not one of " + sim::Choices<E>();
    }
};
}  // namespace detail

// Each def's fields, part by part (a new def adds its overload).
template <class V>
void VisitDefFields(const ThesisDef& def, V& v) {
    VisitFields(def.mesh, v);
    VisitFields(def.params, v);
}
template <class V>
void VisitDefFields(const ShellDef& def, V& v) {
    VisitFields(def.geometry, v);
    VisitFields(def.material, v);
    VisitFields(def.load, v);
    VisitFields(def.ends, v);
    VisitFields(def.solver, v);
    VisitFields(def.fibres, v);
    VisitFields(def.envelope, v);
    VisitFields(def.contact, v);
}

// Empty when every field of the job's model lies in the range the command line and experiment files
// accept; otherwise the first that does not (for jobs that come from elsewhere: the evaluation
// server's requests, Python).
inline std::string JobFieldsError(const sim::EvalJob& job) {
    std::string error;
    detail::RangeChecker check{error};
    std::visit([&](const auto& def) { VisitDefFields(def, check); }, job.def);
    return error;
}

}  // namespace sim
