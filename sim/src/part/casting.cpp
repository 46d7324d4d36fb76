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
                  const PourDef& pour, double overLayerMm, double overLayerMm3) {
    PourPlan plan;
    // The gap the silicone fills: the wall, a first stage's layer, or the wall over a layer.
    const double gapMm = overLayerMm > 0 ? part.thicknessMm - overLayerMm : part.layerMm > 0 ? part.layerMm : part.thicknessMm;
    plan.cavityMl = (MeshVolume(solids.actuator) - (overLayerMm > 0 ? overLayerMm3 : 0)) / 1000;
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
    const double h = gapMm * 1e-3;
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

CoreSupport CheckCoreSupport(const PartSolids& solids, const PartDef& part, const MoldDef& mold, const MaterialDef& material, const PourDef& pour) {
    CoreSupport c;
    // Printed PLA (a rigid core) about 3.5 GPa; PVA about 2 GPa (a wax core is far softer: not counted).
    c.modulusGpa = mold.core == CoreKind::Rigid ? 3.5 : 2.0;
    c.allowedMm = 0.1 * part.thicknessMm;
    double thinnest = INFINITY, widest = 0;
    for (const double p : solids.corePerimeterMm) thinnest = std::min(thinnest, p / std::numbers::pi), widest = std::max(widest, p / std::numbers::pi);
    if (!std::isfinite(thinnest) || !(thinnest > 0)) return c;
    c.thinnestMm = thinnest;
    const double span = part.lengthMm + 2 * mold.endWallMm;  // between the end walls' outer faces, where it is held
    c.slenderness = span / thinnest;
    const double head = (part.lengthMm + mold.endWallMm + pour.funnelAboveTopMm) * 1e-3;
    const double load = material.densityKgPerM3 * 9.81 * head * widest * 1e-3;                     // N/m
    const double stiffness = c.modulusGpa * 1e9 * std::numbers::pi * std::pow(thinnest * 1e-3, 4) / 64;  // E I, N m^2
    auto deflection = [&](double lengthMm) { return load * std::pow(lengthMm * 1e-3, 4) / (384 * stiffness) * 1e3; };  // clamped-clamped, mm
    c.deflectionMm = deflection(span);
    if (c.deflectionMm <= c.allowedMm) return c;
    // n parts, each clamped at its stations as a first approximation: deflection / n^4.
    const int parts = static_cast<int>(std::ceil(std::pow(c.deflectionMm / c.allowedMm, 0.25)));
    for (int k = 1; k < parts; ++k) c.stationsMm.push_back(-mold.endWallMm + span * k / parts);
    return c;
}

std::vector<FibreWinding> PlanWinding(const PartSolids& solids, const PartDef& part, const FibreDef& fibres, double threadSpacingMm,
                                      std::string* error) {
    std::vector<FibreWinding> out;
    if (fibres.layout == FibreLayout::None || (!fibres.plus && !fibres.minus)) return out;
    const int nt = solids.midAround, nz = nt > 0 ? static_cast<int>(solids.midSurfaceMm.size()) / nt : 0;
    if (nz < 2) {
        *error = "no wall to wind on";
        return {};
    }
    const double pi = std::numbers::pi, degree = pi / 180;
    // The mid-surface at ring j and angle theta, interpolated around the ring.
    auto at = [&](int j, double theta) {
        double u = theta / (2 * pi) * nt;
        u -= nt * std::floor(u / nt);
        const int i = static_cast<int>(u) % nt;
        const double f = u - std::floor(u);
        const auto& a = solids.midSurfaceMm[static_cast<size_t>(j) * nt + i];
        const auto& b = solids.midSurfaceMm[static_cast<size_t>(j) * nt + (i + 1) % nt];
        return std::array<double, 3>{a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
    };
    // The bands as the design has them (the model's angles by band, or one for the whole length).
    std::vector<std::pair<double, double>> ranges;
    if (!fibres.bands.empty())
        for (const FibreBand& band : fibres.bands) ranges.push_back({band.from, band.to});
    else ranges.push_back({0, 1});
    const bool sectors = fibres.bands.empty() && !fibres.sectorAnglesDeg.empty();
    std::vector<std::pair<const char*, double>> families;  // +alpha winds theta down going up (the hoop direction is normal x meridian)
    const bool braid = fibres.layout == FibreLayout::Braid;
    if (fibres.layout == FibreLayout::Meridian) families.push_back({"+alpha", 0});
    else {
        if (fibres.plus) families.push_back({"+alpha", -1});
        if (braid && fibres.minus) families.push_back({"-alpha", 1});
    }
    // One thread of a family from its start angle at the bottom end, ring by ring.
    auto march = [&](double start, double sign, FibreWinding& w, ThreadPath& path) {
        double theta = start;
        size_t band = 0;
        WindingBand current{0, 0, NAN, 0, NAN};
        w.pathMm = w.turns = 0;
        w.bands.clear();
        for (int j = 0; j + 1 < nz; ++j) {
            path.anglePerRing.push_back(theta);
            const auto p0 = at(j, theta);
            path.pointsMm.push_back(p0);
            const double t = 0.5 * (p0[2] + at(j + 1, theta)[2]) / part.lengthMm;
            const double alpha = fibres.layout == FibreLayout::Meridian ? 0
                                 : fibres.layout == FibreLayout::Hoop   ? 90
                                                                        : FibreAngleDegAt(fibres, t, theta);
            if (std::fabs(alpha) >= 89) return false;
            // The meridian step here, and the turn it brings.
            const auto p1 = at(j + 1, theta);
            const double ds = std::sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) + (p1[1] - p0[1]) * (p1[1] - p0[1]) + (p1[2] - p0[2]) * (p1[2] - p0[2]));
            const double r = 0.5 * (std::hypot(p0[0], p0[1]) + std::hypot(p1[0], p1[1]));
            const double dtheta = sign * std::tan(alpha * degree) * ds / r;
            path.cosinePerRing.push_back(std::cos(alpha * degree));
            w.pathMm += ds / std::cos(alpha * degree);
            w.turns += std::fabs(dtheta) / (2 * pi);
            theta += dtheta;
            // Band by band.
            while (band + 1 < ranges.size() && t > ranges[band].second) {
                current.toMm = p0[2];
                current.pitchMm = current.turns > 1e-9 ? (current.toMm - current.fromMm) / current.turns : NAN;
                w.bands.push_back(current);
                ++band;
                current = {p0[2], 0, NAN, 0, NAN};
            }
            current.angleDeg = sectors ? NAN : alpha;
            current.turns += std::fabs(dtheta) / (2 * pi);
        }
        path.anglePerRing.push_back(theta);
        path.cosinePerRing.push_back(path.cosinePerRing.back());
        path.pointsMm.push_back(at(nz - 1, theta));
        current.toMm = part.lengthMm;
        current.pitchMm = current.turns > 1e-9 ? (current.toMm - current.fromMm) / current.turns : NAN;
        w.bands.push_back(current);
        return true;
    };
    for (const auto& [name, sign] : families) {
        FibreWinding w;
        w.family = name;
        ThreadPath first;
        if (!march(0, sign, w, first)) {
            *error = "fibres at 89 degrees or more to the meridian are rings around the tube, not a thread wound along it: wind them as a "
                     "close helix by hand";
            return {};
        }
        // As many threads as keep them at most threadSpacingMm apart across (perimeter x cos(alpha) / n)
        // where the tube is widest, equally spaced around at the bottom end.
        double widest = 0, narrowest = INFINITY, mean = 0;
        for (int j = 0; j < nz; ++j) {
            const double across = solids.cavityPerimeterMm[j] * first.cosinePerRing[j];
            widest = std::max(widest, across), narrowest = std::min(narrowest, across), mean += across / nz;
        }
        const int n = std::max(1, static_cast<int>(std::ceil(widest / threadSpacingMm - 1e-9)));
        w.spacingMaxMm = widest / n;
        w.spacingMinMm = narrowest / n;
        w.eaPerThreadN = fibres.stiffnessNPerMm * mean / n;
        first.startDeg = 0;
        w.threads.push_back(std::move(first));
        FibreWinding scratch;  // the others' turns and bands: the first's on a round tube, each followed anyway
        for (int k = 1; k < n; ++k) {
            ThreadPath path;
            path.startDeg = 360.0 * k / n;
            march(2 * pi * k / n, sign, scratch, path);
            w.threads.push_back(std::move(path));
        }
        w.hand = w.turns < 1e-9 ? "straight" : sign < 0 ? "left-handed" : "right-handed";
        out.push_back(w);
    }
    return out;
}

PartDef FirstStagePart(const PartDef& part, const std::vector<FibreWinding>& winding) {
    PartDef first = part;
    first.layerMm = 0.5 * part.thicknessMm;
    // A groove the thread's depth, at most 40 % of the layer (the layer keeps most of itself under it).
    first.guides.depthMm = std::min(first.guides.depthMm, 0.4 * first.layerMm);
    for (const FibreWinding& w : winding)
        for (const ThreadPath& thread : w.threads) {
            first.guides.anglePerRing.push_back(thread.anglePerRing);
            first.guides.cosinePerRing.push_back(thread.cosinePerRing);
        }
    return first;
}

}  // namespace sim
