// The pour of an exported mold: the sprue in the bottom end wall and the vents in the top one, the
// fill's time against thin-gap flow's closed forms, and the choice of gravity or syringe against
// each silicone's pot life; `export` writes it in manifest.json and casting.md.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include <fmt/format.h>

#include "cli_fixture.h"
#include "sim/casting.h"
#include "sim/solid.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

// The area of a solid's faces lying in the plane z = height, mm^2.
double AreaAt(const sim::TriangleMesh& mesh, double height) {
    double area = 0;
    for (const auto& t : mesh.triangles) {
        const auto& a = mesh.vertices[t[0]];
        const auto& b = mesh.vertices[t[1]];
        const auto& c = mesh.vertices[t[2]];
        if (a[2] != height || b[2] != height || c[2] != height) continue;
        area += 0.5 * std::fabs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
    }
    return area;
}

sim::PartSolids Cylinder(const sim::MoldDef& mold = {}) {
    sim::PartSolids solids;
    EXPECT_EQ(sim::BuildPartSolids(sim::CylinderShape{}, sim::PartDef{}, mold, &solids), "");
    return solids;
}

}  // namespace

TEST(Casting, TheSprueOpensTheBottomEndWallAndTheVentsTheTop) {
    const sim::MoldDef mold;
    const sim::PartSolids solids = Cylinder(mold);
    const double bottom = -mold.endWallMm, top = sim::PartDef{}.lengthMm + mold.endWallMm;
    const double sprueArea = solids.sprueMm3 / mold.endWallMm;
    ASSERT_GT(sprueArea, 0);
    // Shell A's bottom face lacks the sprue's section; B's is whole. At the top each lacks two vents.
    EXPECT_NEAR(sim::MeshBounds(solids.shellA)[2], bottom, 1e-12);
    EXPECT_NEAR(AreaAt(solids.shellA, bottom) + sprueArea, AreaAt(solids.shellB, bottom), 1e-9 * AreaAt(solids.shellB, bottom));
    EXPECT_NEAR(AreaAt(solids.shellA, top), AreaAt(solids.shellB, top), 1e-9 * AreaAt(solids.shellB, top)) << "two vents in each half";
    const double vents = (solids.openingsMm3 - solids.sprueMm3) / mold.endWallMm;
    EXPECT_NEAR(AreaAt(solids.shellB, bottom) - AreaAt(solids.shellB, top), vents / 2, 1e-9 * AreaAt(solids.shellB, top));
    // At least 3 mm both ways: across the 1 mm wall it reaches 2 mm past it.
    EXPECT_DOUBLE_EQ(solids.sprueGapMm, 3);
    EXPECT_GE(solids.sprueDegreesBuilt * std::numbers::pi / 180 * (4.5 + 1.5), 3);
    EXPECT_LE(solids.sprueResistanceShare, 0.25);
    EXPECT_NEAR(sprueArea, solids.sprueDegreesBuilt * std::numbers::pi / 180 * 0.5 * (7.5 * 7.5 - 4.5 * 4.5), 0.02 * sprueArea)
        << "an annular sector from the core (4.5 mm) to 2 mm past the wall (7.5 mm)";
    // A sprue given as an arc is that arc, in whole cells.
    sim::MoldDef wide;
    wide.sprueDegrees = 90;
    EXPECT_NEAR(Cylinder(wide).sprueDegreesBuilt, 90, 360.0 / sim::PartDef{}.angularSamples);
}

TEST(Casting, AStraightTubeFillsInTheClosedFormTimeOfThinGapFlow) {
    const sim::PartDef part;
    const sim::MoldDef mold;
    const sim::PartSolids solids = Cylinder(mold);
    sim::MaterialDef material;
    material.densityKgPerM3 = 1e-3;  // no column to lift: the syringe's pressure drives it all
    const sim::CastingDef casting{3.0, 45, 4, 1, "test"};
    const sim::PourPlan syringe = sim::PlanPour(solids, part, mold, material, casting);
    // t = integral of P h (R_sprue + 12 mu s / (P h^3)) / p over the length = (6 + 12 share) mu L^2 / (h^2 p).
    const double mu = 3, L = 0.15, h = 1e-3, p = sim::PourDef{}.syringeKpa * 1e3;
    EXPECT_NEAR(syringe.syringeMin * 60, (6 + 12 * solids.sprueResistanceShare) * mu * L * L / (h * h * p), 1e-6 * syringe.syringeMin * 60);
    // By gravity the drive is rho g (H - s), H the funnel's level: t = 12 mu / (h^2 rho g) (-L + (H + a) ln(H / (H - L))), a = share L.
    material.densityKgPerM3 = 1070;
    const sim::PourPlan gravity = sim::PlanPour(solids, part, mold, material, casting);
    const double H = (part.lengthMm + mold.endWallMm + sim::PourDef{}.funnelAboveTopMm) * 1e-3, a = solids.sprueResistanceShare * L;
    const double exact = 12 * mu / (h * h * 1070 * 9.81) * (-L + (H + a) * std::log(H / (H - L)));
    EXPECT_NEAR(gravity.gravityMin * 60 / exact, 1, 1e-3);
    EXPECT_NEAR(gravity.gravityMin, 4.5, 0.1) << "Ecoflex 00-30 in a 1 mm wall, 150 mm long, from a funnel 100 mm above the block";
    // What to mix: the cavity and slots, and the margin of 30 %, at least 5 ml.
    EXPECT_NEAR(gravity.cavityMl, sim::MeshVolume(solids.actuator) / 1000, 1e-12);
    EXPECT_NEAR(gravity.mixMl, gravity.cavityMl + gravity.slotsMl + std::max(5.0, 0.3 * (gravity.cavityMl + gravity.slotsMl)), 1e-12);
    EXPECT_NEAR(gravity.partAG + gravity.partBG, gravity.mixMl * 1.07, 1e-9);
}

TEST(Casting, ThickSiliconesAreInjectedAndTooShortAPotLifeIsSaid) {
    const sim::PartDef part;
    const sim::MoldDef mold;
    const sim::PartSolids solids = Cylinder(mold);
    auto plan = [&](sim::MaterialPreset preset) {
        return sim::PlanPour(solids, part, mold, sim::MaterialPresetDef(preset), sim::CastingPresetDef(preset));
    };
    const sim::PourPlan ecoflex = plan(sim::MaterialPreset::Ecoflex0030), dragon = plan(sim::MaterialPreset::DragonSkin10);
    EXPECT_TRUE(ecoflex.gravity) << ecoflex.gravityMin << " min";
    EXPECT_FALSE(dragon.gravity) << "23,000 cps: " << dragon.gravityMin << " min against a 20 min pot life";
    EXPECT_FALSE(dragon.tooSlow) << dragon.syringeMin << " min by syringe";
    EXPECT_NEAR(dragon.gravityMin / ecoflex.gravityMin, 23.0 / 3.0, 1e-9) << "Newtonian: the time scales with the viscosity";
    EXPECT_EQ(sim::CastingPresetDef(sim::MaterialPreset::Elastosil4601).partsAPerB, 9);
    const sim::PourPlan elastosil = plan(sim::MaterialPreset::Elastosil4601);
    EXPECT_NEAR(elastosil.partAG, 9 * elastosil.partBG, 1e-9);
    // A paste with a short pot life cannot be filled in time; a material of one's own has no viscosity.
    const sim::PourPlan paste = sim::PlanPour(solids, part, mold, sim::MaterialPresetDef(sim::MaterialPreset::Ecoflex0030), {2000, 5, 1, 1, "paste"});
    EXPECT_TRUE(paste.tooSlow);
    const sim::PourPlan unknown = sim::PlanPour(solids, part, mold, sim::MaterialPresetDef(sim::MaterialPreset::Ecoflex0030), {});
    EXPECT_TRUE(std::isnan(unknown.gravityMin));
    EXPECT_GT(unknown.mixG, 0) << "the amounts need only the density";
}

class CastingCli : public CliTest {};

TEST_F(CastingCli, ExportWritesThePourAndTheStepsInOrder) {
    Result r = Run("export --model shell --shape cylinder --out " + Path("tube"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto manifest = nlohmann::json::parse(Slurp(dir_ / "tube" / "manifest.json"));
    EXPECT_EQ(manifest["pour"]["fill"]["method"], "gravity");
    EXPECT_EQ(manifest["pour"]["handling"]["mixed_viscosity_cps"], 3000.0);
    EXPECT_THAT(manifest["pour"]["orientation"].get<std::string>(), HasSubstr("bottom end (z = 0) down"));
    const std::string sheet = Slurp(dir_ / "tube" / "casting.md");
    const auto at = [&](const char* heading) { return sheet.find(heading); };
    ASSERT_NE(at("## 1. Print"), std::string::npos) << sheet;
    EXPECT_LT(at("## 1. Print"), at("## 2. Prepare and assemble"));
    EXPECT_LT(at("## 2. Prepare and assemble"), at("## 3. Mix"));
    EXPECT_LT(at("## 3. Mix"), at("## 4. Pour from below"));
    EXPECT_LT(at("## 4. Pour from below"), at("## 5. Cure and demould"));
    EXPECT_THAT(sheet, HasSubstr("pour by gravity"));
    EXPECT_THAT(sheet, HasSubstr(fmt::format("{:.1f} g of part A", manifest["pour"]["to_mix_g"]["part_a"].get<double>())));
    // A batch's own bulletin: a paste that cannot be filled in its pot life is said, and still written.
    r = Run("export --model shell --shape cylinder --viscosity-cps 2000000 --pot-life-min 5 --out " + Path("paste"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("more than half the 5 min pot life"));
    EXPECT_THAT(Slurp(dir_ / "paste" / "casting.md"), HasSubstr("even the syringe needs more than half of it"));
    r = Run("export --model shell --shape cylinder --viscosity-cps 0 --out " + Path("bad"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
}
