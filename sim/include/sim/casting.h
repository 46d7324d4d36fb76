// Casting an exported part: the silicone's handling as its supplier states it (viscosity once mixed,
// pot life, cure), what to mix, and how long the cavity takes to fill from its lowest point
// (docs/guide/export.md, pouring). Pure arithmetic on the built solids; app/ reports it.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "sim/shell.h"
#include "sim/solid.h"

namespace sim {

// A silicone's handling at room temperature (23 C), from its technical bulletin.
struct CastingDef {
    double mixedViscosityPaS = 0;  // the parts once mixed (1 Pa s = 1000 cps); 0: not known
    double potLifeMin = 0;         // working time from mixing, minutes
    double cureHours = 0;          // until it can be demoulded
    double partsAPerB = 1;         // mix ratio by weight, parts of A to one of B
    std::string source;            // where the numbers come from
};
// The preset's handling (the datasheet and fitted presets of one silicone share it); a custom
// material has none (viscosity 0).
CastingDef CastingPresetDef(MaterialPreset preset);

// How the silicone goes in: from below, by gravity from a funnel above the mold, or pushed by a syringe.
struct PourDef {
    double funnelAboveTopMm = 100;  // a gravity pour: the funnel's level above the block's top face, mm
    double syringeKpa = 50;         // a syringe's gauge pressure at the sprue (about 16 N on a 20 ml syringe's plunger), kPa
    double marginFraction = 0.3;    // silicone mixed beyond the cavity and the slots: what stays in the cup, the funnel, the tube
    double marginMinMl = 5;         // ... and at least this much
};

struct PourPlan {
    double cavityMl = 0;       // the part's silicone
    double slotsMl = 0;        // the sprue and the vents, filled too
    double mixMl = 0;          // to mix: cavity and slots plus the margin
    double mixG = 0, partAG = 0, partBG = 0;
    double gravityMin = 0;     // the fill's time from the funnel; NaN when the viscosity is not known
    double syringeMin = 0;     // ... and by the syringe
    bool gravity = false;      // gravity fills within half the pot life (the other half: mixing and degassing)
    bool tooSlow = false;      // even the syringe needs more than half the pot life
};

// The plan for a part cast in `material` with the handling `casting`. The fill is thin-gap
// (Poiseuille) flow from the sprue up the cavity, the front rising ring by ring: each band fills at
// the flow that the pressure left over the column already standing drives through the resistance
// behind it (the sprue's and the filled cavity's). Newtonian, at the bulletin's viscosity; the tube
// from funnel or syringe to the sprue is not counted.
// A first-stage layer's solids (part.layerMm > 0) fill a gap of the layer. The second stage, with the
// full wall's solids and the layer given (its thickness and volume), fills the wall less the layer.
PourPlan PlanPour(const PartSolids& solids, const PartDef& part, const MoldDef& mold, const MaterialDef& material, const CastingDef& casting,
                  const PourDef& pour = {}, double overLayerMm = 0, double overLayerMm3 = 0);

// Whether the core stays centred while the silicone flows in. It is held at both ends (its handles
// in the end walls), a beam clamped at both ends; the worst lateral load is the fill's whole head
// on one side of it (a front rising faster on the sprue's side), rho g H over its widest section.
// Its deflection at mid-span, with its thinnest section's bending stiffness along all of it (on the
// safe side), must stay within a tenth of the wall; otherwise the span is split by stations of
// spacers until each part's deflection does.
struct CoreSupport {
    double deflectionMm = 0;       // unsupported, at mid-span
    double allowedMm = 0;          // a tenth of the wall
    double slenderness = 0;        // the core's length over its thinnest section's diameter
    double thinnestMm = 0;         // that diameter (perimeter / pi)
    std::vector<double> stationsMm;  // spacer stations, heights from the bottom end (empty: none needed)
    double modulusGpa = 0;         // the core's material, as assumed
};
CoreSupport CheckCoreSupport(const PartSolids& solids, const PartDef& part, const MoldDef& mold, const MaterialDef& material,
                             const PourDef& pour = {});

// How a design's fibres are wound onto its wall (the models' fibres as threads): each family as
// threads from the bottom end to the top at the design's angle to the meridian,
// integrated over the wall's mid-surface ring by ring (on a bulb the thread turns faster where the
// radius is smaller: dtheta = tan(alpha) ds / r).
struct WindingBand {
    double fromMm = 0, toMm = 0;  // heights, from the bottom end
    double angleDeg = 0;          // to the meridian; NaN for sector angles (they change around the tube)
    double turns = 0;             // around the axis over the band
    double pitchMm = 0;           // height per turn; NaN where the thread runs straight up (no turns)
};
// One thread of a family, ring by ring.
struct ThreadPath {
    double startDeg = 0;                // its start at the bottom end, degrees from +x
    std::vector<double> anglePerRing;   // its angle about the axis at each ring of the part (radians from +x)
    std::vector<double> cosinePerRing;  // cos of its angle to the meridian there (for GuideDef)
    std::vector<std::array<double, 3>> pointsMm;  // where it crosses each ring, on the mid-surface
};
struct FibreWinding {
    std::string family;  // "+alpha" or "-alpha" (the models' names)
    std::string hand;    // "left-handed" (+alpha: clockwise seen from the top, going up), "right-handed", "straight" (meridian)
    double pathMm = 0;   // the thread's length on the wall, mm
    double turns = 0;    // around the axis, bottom to top
    std::vector<WindingBand> bands;
    // The family as threads: equally spaced at the bottom end, as many as keep them the spacing
    // apart where the tube is widest. The models' fibres are a continuous family of a stiffness per
    // unit width; threads of EA newtons each, this far apart, are that family where the spacing is
    // its mean (stiffer where the tube is narrower, softer where it is wider).
    std::vector<ThreadPath> threads;
    double spacingMinMm = 0, spacingMaxMm = 0;  // across the threads, over the length
    double eaPerThreadN = 0;                    // the stiffness per unit width times the mean spacing
};
// Empty for a design without fibres. Hoop fibres (90 degrees) are rings, not a thread wound up the
// tube: `error` says so, and so it does for angles of 89 degrees or more.
std::vector<FibreWinding> PlanWinding(const PartSolids& solids, const PartDef& part, const FibreDef& fibres, double threadSpacingMm,
                                      std::string* error);

// A fibre design's first stage (docs/guide/export.md, fibres): the wall's inner half, its outer face
// (the mid-surface, where the models' fibres lie) grooved along every family's thread.
PartDef FirstStagePart(const PartDef& part, const std::vector<FibreWinding>& winding);

}  // namespace sim
