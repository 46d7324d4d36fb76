#include "sim/casting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sim {

CastingDef CastingPresetDef(MaterialPreset preset) {
    // Smooth-On's technical bulletins (Ecoflex series, Dragon Skin series: mixed viscosity, pot life,
    // cure time, mix ratio) and Wacker's data sheet for Elastosil M 4601, as published; a batch's own
    // bulletin wins.
    const char* smoothOn = "Smooth-On technical bulletin";
    switch (preset) {
        case MaterialPreset::Ecoflex0030:
        case MaterialPreset::Ecoflex0030Datasheet: return {3.0, 45, 4, 1, std::string(smoothOn) + ", Ecoflex 00-30"};
        case MaterialPreset::Ecoflex0050:
        case MaterialPreset::Ecoflex0050Datasheet: return {8.0, 18, 3, 1, std::string(smoothOn) + ", Ecoflex 00-50"};
        case MaterialPreset::DragonSkin10:
        case MaterialPreset::DragonSkin10Datasheet: return {23.0, 20, 5, 1, std::string(smoothOn) + ", Dragon Skin 10 Medium"};
        case MaterialPreset::DragonSkin20:
        case MaterialPreset::DragonSkin20Datasheet: return {20.0, 25, 4, 1, std::string(smoothOn) + ", Dragon Skin 20"};
        case MaterialPreset::DragonSkin30:
        case MaterialPreset::DragonSkin30Datasheet: return {20.0, 45, 16, 1, std::string(smoothOn) + ", Dragon Skin 30"};
        case MaterialPreset::Elastosil4601: return {15.0, 90, 12, 9, "Wacker data sheet, Elastosil M 4601 A/B"};
        case MaterialPreset::Custom: break;
    }
    return {};
}

PourPlan PlanPour(const PartSolids& solids, const PartDef& part, const MoldDef& mold, const MaterialDef& material, const CastingDef& casting,
                  const PourDef& pour) {
    PourPlan plan;
    plan.cavityMl = MeshVolume(solids.actuator) / 1000;
    plan.slotsMl = solids.openingsMm3 / 1000;
    const double needed = plan.cavityMl + plan.slotsMl;
    plan.mixMl = needed + std::max(pour.marginFraction * needed, pour.marginMinMl);
    plan.mixG = plan.mixMl * material.densityKgPerM3 / 1000;  // kg/m^3 = 1e-3 g/ml
    plan.partBG = plan.mixG / (casting.partsAPerB + 1);
    plan.partAG = plan.mixG - plan.partBG;

    const double mu = casting.mixedViscosityPaS;
    if (!(mu > 0) || !(material.densityKgPerM3 > 0)) {
        plan.gravityMin = plan.syringeMin = NAN;
        return plan;
    }
    // In SI: a gap h wide, of perimeter P, resists the flow Q = dp / R over a length ds with
    // R = 12 mu ds / (P h^3); the sprue's resistance is its share of the full cavity's.
    const double h = part.thicknessMm * 1e-3;
    const auto& perimeter = solids.cavityPerimeterMm;
    const auto& path = solids.cavityPathMm;
    const auto& height = solids.cavityHeightMm;
    auto bandResistance = [&](size_t j) {
        return 12 * mu * (path[j] - path[j - 1]) * 1e-3 / (0.5 * (perimeter[j] + perimeter[j - 1]) * 1e-3 * h * h * h);
    };
    double cavity = 0;
    for (size_t j = 1; j < perimeter.size(); ++j) cavity += bandResistance(j);
    const double sprue = solids.sprueResistanceShare * cavity;
    const double rhoG = material.densityKgPerM3 * 9.81;
    const double funnel = (part.lengthMm + mold.endWallMm + pour.funnelAboveTopMm) * 1e-3;  // above the cavity's bottom, m
    auto fillMinutes = [&](auto drive) -> double {
        double seconds = 0, behind = sprue;
        for (size_t j = 1; j < perimeter.size(); ++j) {
            const double ds = (path[j] - path[j - 1]) * 1e-3, p = 0.5 * (perimeter[j] + perimeter[j - 1]) * 1e-3;
            const double dp = drive(0.5 * (height[j] + height[j - 1]) * 1e-3);
            if (!(dp > 0)) return std::numeric_limits<double>::infinity();  // the column outweighs the drive: it never fills
            // The band's volume over the flow that reaches its middle (exact for a straight tube).
            seconds += p * h * ds * (behind + 0.5 * bandResistance(j)) / dp;
            behind += bandResistance(j);
        }
        return seconds / 60;
    };
    plan.gravityMin = fillMinutes([&](double z) { return rhoG * (funnel - z); });
    plan.syringeMin = fillMinutes([&](double z) { return pour.syringeKpa * 1e3 - rhoG * z; });
    plan.gravity = plan.gravityMin <= 0.5 * casting.potLifeMin;
    plan.tooSlow = !plan.gravity && !(plan.syringeMin <= 0.5 * casting.potLifeMin);
    return plan;
}

}  // namespace sim
