// The pour of an exported mold: the sprue in the bottom end wall and the vents in the top one, the
// fill's time against thin-gap flow's closed forms, and the choice of gravity or syringe against
// each silicone's pot life; `export` writes it in manifest.json and casting.md.
#include <Eigen/Dense>
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

// The mold's way up is engraved: an arrow pointing up in shell A's back (y = +w), over the sprue at
// 90 degrees, its pocket the only difference from an unmarked shell A; shell B is unmarked.
TEST(Casting, ShellABackCarriesAnUpwardArrowOverTheSprue) {
    const sim::MoldDef marked;
    sim::MoldDef plain;
    plain.markDepthMm = 0;
    const sim::PartSolids a = Cylinder(marked), b = Cylinder(plain);
    const double w = sim::MeshBounds(a.shellA)[4], h = std::min(0.6 * w, (150 + 2 * marked.endWallMm) / 7.5);
    EXPECT_NEAR(a.markMm3, marked.markDepthMm * 3.9 * h * h, 1e-9) << "shaft 0.8h x 3h and head h wide x 1.5h tall";
    EXPECT_NEAR(sim::MeshVolume(b.shellA) - sim::MeshVolume(a.shellA), a.markMm3, 1e-6 * a.markMm3);
    EXPECT_NEAR(sim::MeshVolume(a.shellB), sim::MeshVolume(b.shellB), 1e-9 * sim::MeshVolume(b.shellB));
    EXPECT_EQ(b.markMm3, 0);
    // The pocket's floor: its highest point (the tip) on the sprue's meridian above its widest (the head's base).
    std::array<double, 3> tip{0, 0, -1e9}, wing{0, 0, 0};
    int floor = 0;
    for (const auto& v : a.shellA.vertices) {
        if (std::fabs(v[1] - (w - marked.markDepthMm)) > 1e-12) continue;
        ++floor;
        if (v[2] > tip[2]) tip = v;
        if (v[0] > wing[0]) wing = v;
    }
    EXPECT_GE(floor, 9);
    EXPECT_NEAR(tip[0], 0, 1e-12) << "over the sprue, centred at 90 degrees (x = 0)";
    EXPECT_NEAR(wing[0], h, 1e-12);
    EXPECT_GT(tip[2], wing[2] + h) << "pointing up";
    EXPECT_GT(a.sprueMouthMm[1], 0) << "the sprue is in the same half (y > 0)";
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
    EXPECT_LT(at("## 1. Print"), at("## 2. Prepare"));
    EXPECT_LT(at("## 2. Prepare"), at("## 3. Assemble, mix and pour"));
    EXPECT_LT(at("## 3. Assemble, mix and pour"), at("**Mix**"));
    EXPECT_LT(at("**Mix**"), at("**Pour from below.**"));
    EXPECT_LT(at("**Pour from below.**"), at("## 4. Demould"));
    EXPECT_EQ(at("stage1"), std::string::npos) << "one stage without fibres";
    EXPECT_THAT(sheet, HasSubstr("pour by gravity"));
    EXPECT_THAT(sheet, HasSubstr(fmt::format("{:.1f} g of part A", manifest["pour"]["to_mix_g"]["part_a"].get<double>())));
    // A batch's own bulletin: a paste that cannot be filled in its pot life is said, and still written.
    r = Run("export --model shell --shape cylinder --viscosity-cps 2000000 --pot-life-min 5 --out " + Path("paste"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("more than half the 5 min pot life"));
    EXPECT_THAT(Slurp(dir_ / "paste" / "casting.md"), HasSubstr("even the syringe needs more than half of it"));
    EXPECT_TRUE(manifest["core"]["support"]["spacers"].empty()) << "a plain tube's core needs none";
    EXPECT_EQ(sheet.find("**Spacers.**"), std::string::npos);
    // A thin neck's core gets spacers, and the sheet says where to put them.
    r = Run("export --model shell --shape bspline --region middle --control-points 1,0.5,0.5,0.5,1 --out " + Path("neck"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto neck = nlohmann::json::parse(Slurp(dir_ / "neck" / "manifest.json"));
    ASSERT_EQ(neck["core"]["support"]["spacers"].size(), 1u);
    EXPECT_NEAR(neck["core"]["support"]["spacers"][0]["z_mm"].get<double>(), 75, 1e-9);
    EXPECT_THAT(Slurp(dir_ / "neck" / "casting.md"), HasSubstr("at heights 75 mm, at 30, 150 and 270 deg"));
    r = Run("export --model shell --shape cylinder --viscosity-cps 0 --out " + Path("bad"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

TEST(Casting, FibresAreWoundAsHelicesWithTheClosedFormTurnsAndLength) {
    const sim::PartDef part;  // R 5 mm, L 150 mm: the mid-surface is the 5 mm cylinder
    const sim::PartSolids solids = Cylinder();
    sim::FibreDef braid;
    braid.layout = sim::FibreLayout::Braid;
    braid.angleDeg = 40;
    std::string error;
    const auto winding = sim::PlanWinding(solids, part, braid, 3, &error);
    ASSERT_EQ(error, "");
    ASSERT_EQ(winding.size(), 2u);
    const double alpha = 40 * std::numbers::pi / 180;
    // Between samples the thread runs on the 120-gon's chords, up to 0.03 % inside the circle.
    const double chords = 5e-4;
    for (const auto& w : winding) {
        EXPECT_NEAR(w.turns, std::tan(alpha) * 150 / (2 * std::numbers::pi * 5), chords * w.turns) << w.family;
        EXPECT_NEAR(w.pathMm, 150 / std::cos(alpha), 1e-9) << "the meridian steps are exact";
        ASSERT_EQ(w.bands.size(), 1u);
        EXPECT_NEAR(w.bands[0].pitchMm, 2 * std::numbers::pi * 5 / std::tan(alpha), chords * w.bands[0].pitchMm);
    }
    EXPECT_EQ(winding[0].hand, "left-handed");
    EXPECT_EQ(winding[1].hand, "right-handed");
    // As threads at most 3 mm apart across: n = ceil(P cos(alpha) / 3), equally spaced, each the
    // family's stiffness per width times its spacing.
    const double across = solids.cavityPerimeterMm[0] * std::cos(alpha);
    const size_t n = static_cast<size_t>(std::ceil(across / 3));
    EXPECT_EQ(n, 9u);
    for (const auto& w : winding) {
        ASSERT_EQ(w.threads.size(), n);
        EXPECT_NEAR(w.spacingMaxMm, across / n, 1e-9);
        EXPECT_NEAR(w.spacingMinMm, across / n, 1e-9);
        EXPECT_NEAR(w.eaPerThreadN, braid.stiffnessNPerMm * across / n, 1e-9);
        for (size_t k = 0; k < n; ++k) {
            EXPECT_NEAR(w.threads[k].startDeg, 360.0 * k / n, 1e-12);
            // On a round tube each thread is the first turned by its start.
            EXPECT_NEAR(w.threads[k].anglePerRing.back() - w.threads[0].anglePerRing.back(), 2 * std::numbers::pi * k / n, 1e-3);
        }
    }
    // Bands wind at their own angles; a single family is one thread; meridian threads run straight.
    sim::FibreDef banded;
    banded.layout = sim::FibreLayout::Single;
    banded.bands = {{0, 0.5, 20}, {0.5, 1, 60}};
    const auto single = sim::PlanWinding(solids, part, banded, 3, &error);
    ASSERT_EQ(single.size(), 1u);
    ASSERT_EQ(single[0].bands.size(), 2u);
    EXPECT_NEAR(single[0].bands[0].toMm, 75, 150.0 / 120 + 1e-9) << "the band's end at the ring nearest it";
    EXPECT_NEAR(single[0].bands[1].pitchMm, 2 * std::numbers::pi * 5 / std::tan(60 * std::numbers::pi / 180), chords * 18.14);
    EXPECT_NEAR(single[0].bands[0].pitchMm, 2 * std::numbers::pi * 5 / std::tan(20 * std::numbers::pi / 180), chords * 86.31);
    sim::FibreDef meridian;
    meridian.layout = sim::FibreLayout::Meridian;
    const auto straight = sim::PlanWinding(solids, part, meridian, 3, &error);
    ASSERT_EQ(straight.size(), 1u);
    EXPECT_EQ(straight[0].hand, "straight");
    EXPECT_NEAR(straight[0].pathMm, 150, 1e-9);
    EXPECT_EQ(straight[0].threads.size(), 11u) << "a 31.4 mm perimeter at most 3 mm apart";
    // Hoop fibres are rings: they are not wound along the tube, and the export says so.
    sim::FibreDef hoop;
    hoop.layout = sim::FibreLayout::Hoop;
    EXPECT_TRUE(sim::PlanWinding(solids, part, hoop, 3, &error).empty());
    EXPECT_THAT(error, HasSubstr("rings around the tube"));
    // Families switched off (a GA gene) leave nothing to wind.
    braid.plus = braid.minus = false;
    error.clear();
    EXPECT_TRUE(sim::PlanWinding(solids, part, braid, 3, &error).empty());
    EXPECT_EQ(error, "");
}

TEST_F(CastingCli, AFibreDesignGetsItsWindingPlanAndHoopFibresAreRefused) {
    Result r = Run("export --model shell --shape cylinder --fibres braid --fibre-angle-deg 50 --out " + Path("braid"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto manifest = nlohmann::json::parse(Slurp(dir_ / "braid" / "manifest.json"));
    ASSERT_EQ(manifest["fibres"]["families"].size(), 2u);
    EXPECT_NEAR(manifest["fibres"]["families"][0]["turns"].get<double>(), std::tan(50 * std::numbers::pi / 180) * 150 / (2 * std::numbers::pi * 5), 3e-3);
    const std::string sheet = Slurp(dir_ / "braid" / "casting.md");
    EXPECT_THAT(sheet, HasSubstr("Winding order: the +alpha family's threads first"));
    EXPECT_EQ(manifest["fibres"]["families"][0]["threads"], 7) << "ceil(31.4 cos 50 deg / 3)";
    // Two stages: the inner layer in its own mold, wound, then overmoulded in the wall's mold.
    EXPECT_LT(sheet.find("## 3. First stage: the inner layer"), sheet.find("## 4. Wind the fibres"));
    EXPECT_LT(sheet.find("## 4. Wind the fibres"), sheet.find("## 5. Second stage: the overmould"));
    for (const char* file : {"stage1_shell_a.stl", "stage1_shell_b.stl", "stage1_layer.stl", "winding_guides.png"})
        EXPECT_TRUE(fs::exists(dir_ / "braid" / file)) << file;
    const auto& first = manifest["first_stage"];
    EXPECT_EQ(first["layer_mm"], 0.5);
    const double layerMl = first["pour"]["silicone_ml"]["cavity"].get<double>(), overMl = manifest["pour"]["silicone_ml"]["cavity"].get<double>();
    EXPECT_NEAR(layerMl + overMl, manifest["silicone"]["volume_mm3"].get<double>() / 1000, 1e-9) << "the two pours make the wall";
    EXPECT_NEAR(first["pour"]["fill"]["gravity_min"].get<double>(), 4 * 4.5, 1) << "a half-wall gap fills 4x slower than the whole wall (4.5 min)";
    r = Run("export --model shell --shape cylinder --thread-spacing-mm 2 --out " + Path("bare"));
    EXPECT_EQ(r.exitCode, 2) << "a spacing for threads a design without fibres does not have is refused, not ignored";
    EXPECT_FALSE(fs::exists(dir_ / "bare"));
    r = Run("export --model shell --shape cylinder --fibres hoop --out " + Path("hoop"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_THAT(r.err, HasSubstr("cannot wind this design's fibres"));
    EXPECT_FALSE(fs::exists(dir_ / "hoop"));
}

// The first stage's guide grooves lie on the threads: at every ring, the layer's surface point
// nearest each thread's crossing is the groove's bottom, straight under it (across the thread within
// a tenth of the wall) and the groove's depth down.
TEST(Casting, TheFirstStagesGuideGroovesLieOnTheFibrePaths) {
    sim::PartDef part;
    part.angularSamples = 240;  // 0.13 mm around at R 5: the nearest sample is within 0.07 mm of any point
    const std::pair<const char*, sim::Shape> designs[] = {{"cylinder", sim::CylinderShape{}},
                                                          {"bspline", sim::BSplineShape{sim::SplineRegion::Middle, {{1, 1.3, 1.6, 1.3, 1}}}}};
    for (const auto& [name, shape] : designs) {
        SCOPED_TRACE(name);
        sim::PartSolids full;
        ASSERT_EQ(sim::BuildPartSolids(shape, part, {}, &full), "");
        sim::FibreDef braid;
        braid.layout = sim::FibreLayout::Braid;
        braid.angleDeg = 40;
        std::string error;
        const auto winding = sim::PlanWinding(full, part, braid, 3, &error);
        ASSERT_EQ(winding.size(), 2u) << error;
        const sim::PartDef first = sim::FirstStagePart(part, winding);
        EXPECT_DOUBLE_EQ(first.layerMm, 0.5);
        EXPECT_DOUBLE_EQ(first.guides.depthMm, 0.2);
        sim::PartSolids layer;
        ASSERT_EQ(sim::BuildPartSolids(shape, first, {}, &layer), "");
        const auto& v = layer.actuator.vertices;
        double worstAcross = 0, worstDepth = 0;
        int checked = 0;
        for (const auto& w : winding)
            for (const auto& thread : w.threads)
            for (size_t k = 4; k + 4 < thread.pointsMm.size(); ++k) {
                const auto& p = thread.pointsMm[k];
                size_t best = 0;
                double nearest = INFINITY;
                for (size_t n = 0; n < v.size(); ++n)
                    if (std::fabs(v[n][2] - p[2]) < 0.6)
                        if (const double d = std::hypot(v[n][0] - p[0], v[n][1] - p[1], v[n][2] - p[2]); d < nearest) nearest = d, best = n;
                // The thread's direction, the surface's normal (near-radial on these gentle slopes) and across.
                const auto& a = thread.pointsMm[k - 1];
                const auto& b = thread.pointsMm[k + 1];
                Eigen::Vector3d tangent(b[0] - a[0], b[1] - a[1], b[2] - a[2]), normal(p[0], p[1], 0), offset(v[best][0] - p[0], v[best][1] - p[1], v[best][2] - p[2]);
                tangent.normalize();
                normal = (normal - normal.dot(tangent) * tangent).normalized();
                const Eigen::Vector3d across = tangent.cross(normal).normalized();
                worstAcross = std::max(worstAcross, std::fabs(offset.dot(across)));
                worstDepth = std::max(worstDepth, std::fabs(-offset.dot(normal) - first.guides.depthMm));
                ++checked;
            }
        EXPECT_GT(checked, 200);
        EXPECT_LT(worstAcross, 0.1 * part.thicknessMm) << "the groove's bottom across the thread from it, mm";
        EXPECT_LT(worstDepth, 0.05) << "the groove's depth under the thread, mm";
        // The layer and its molds are valid solids that fill their block.
        const auto a = sim::MeshBounds(layer.shellA), b = sim::MeshBounds(layer.shellB);
        const double block = (std::max(a[3], b[3]) - std::min(a[0], b[0])) * (std::max(a[4], b[4]) - std::min(a[1], b[1])) * (a[5] - a[2]);
        const double pieces = sim::MeshVolume(layer.shellA) + sim::MeshVolume(layer.shellB) + sim::MeshVolume(layer.actuator) + sim::MeshVolume(layer.core) -
                              layer.coreOutsideBlockMm3 + layer.openingsMm3 + layer.markMm3 - layer.pinsLessHolesMm3;
        EXPECT_NEAR(pieces / block, 1, 1e-6);
        EXPECT_LT(sim::MeshVolume(layer.actuator), 0.5 * sim::MeshVolume(full.actuator)) << "the inner half, less its grooves";
        EXPECT_EQ(layer.core.vertices, full.core.vertices) << "one core for both stages";
    }
}

// The core is held at both ends; a plain tube's bends microns under the fill's head, a thin neck's
// a wall's worth, and spacers then split its span until each part bends less than a tenth of the wall.
TEST(Casting, ASlenderCoreGetsSpacersAndAStoutOneNone) {
    const sim::PartDef part;
    const sim::MoldDef mold;
    const sim::MaterialDef ecoflex = sim::MaterialPresetDef(sim::MaterialPreset::Ecoflex0030);
    const sim::CoreSupport stout = sim::CheckCoreSupport(Cylinder(mold), part, mold, ecoflex);
    // w = rho g H D over a clamped-clamped span L: w L^4 / (384 E pi D^4 / 64), D the 9 mm core.
    const double D = 9e-3 * 120 / std::numbers::pi * std::sin(std::numbers::pi / 120), L = 0.16, H = 0.255;  // H: the funnel 100 mm over the block's top
    const double w = 1070 * 9.81 * H * D, EI = 3.5e9 * std::numbers::pi * std::pow(D, 4) / 64;
    EXPECT_NEAR(stout.deflectionMm, w * std::pow(L, 4) / (384 * EI) * 1e3, 1e-6 * stout.deflectionMm);
    EXPECT_LT(stout.deflectionMm, 0.05) << "a 9 mm PLA core bends under 50 um";
    EXPECT_TRUE(stout.stationsMm.empty());
    EXPECT_NEAR(stout.slenderness, 160 / D / 1e3, 1e-9);
    // A neck of half the radius over the middle: a 4 mm core there.
    sim::PartSolids necked;
    ASSERT_EQ(sim::BuildPartSolids(sim::BSplineShape{sim::SplineRegion::Middle, {{1, 0.5, 0.5, 0.5, 1}}}, part, mold, &necked), "");
    const sim::CoreSupport slender = sim::CheckCoreSupport(necked, part, mold, ecoflex);
    EXPECT_GT(slender.deflectionMm, slender.allowedMm);
    ASSERT_FALSE(slender.stationsMm.empty());
    const double parts = slender.stationsMm.size() + 1.0;
    EXPECT_LE(slender.deflectionMm / std::pow(parts, 4), slender.allowedMm) << "each part within a tenth of the wall";
    EXPECT_GT(slender.deflectionMm / std::pow(parts - 1, 4), slender.allowedMm) << "and no more stations than that needs";
    for (const double z : slender.stationsMm) EXPECT_TRUE(z > 0 && z < part.lengthMm) << z;
}

TEST_F(CastingCli, TheBulbIsRefusedWholeAndCastInHalvesBondedAtTheirFlanges) {
    const std::string bulb = "export --model shell --shape bspline --region middle --control-points 1,8,8,1";
    Result r = Run(bulb + " --out " + Path("whole"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_THAT(r.err, HasSubstr("--cast halves"));
    EXPECT_FALSE(fs::exists(dir_ / "whole"));
    r = Run(bulb + " --cast halves --out " + Path("halves"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto manifest = nlohmann::json::parse(Slurp(dir_ / "halves" / "manifest.json"));
    EXPECT_NEAR(manifest["halves"]["cut_z_mm"].get<double>(), 75, 1e-9);
    ASSERT_EQ(manifest["halves"]["pieces"].size(), 2u);
    for (const auto& piece : manifest["halves"]["pieces"]) EXPECT_LT(piece["demoulding_stretch"].get<double>(), 1.01);
    for (const char* file : {"bottom_half.stl", "bottom_mold_core.stl", "bottom_mold_shell_a.stl", "top_mold_shell_b.stl", "mold_assembly_top.png"})
        EXPECT_TRUE(fs::exists(dir_ / "halves" / file)) << file;
    EXPECT_FALSE(fs::exists(dir_ / "halves" / "mold_core.stl")) << "the halves' molds replace the whole one's";
    const std::string sheet = Slurp(dir_ / "halves" / "casting.md");
    EXPECT_LT(sheet.find("The bottom half"), sheet.find("The top half"));
    EXPECT_LT(sheet.find("The top half"), sheet.find("Bond the halves"));
    // It also casts with a lost core; halves refuse fibres, and a flange without halves.
    EXPECT_EQ(Run(bulb + " --core lost --out " + Path("lost")).exitCode, 0);
    r = Run(bulb + " --cast halves --fibres braid --out " + Path("fibres"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_THAT(r.err, HasSubstr("without fibres"));
    EXPECT_EQ(Run(bulb + " --flange-mm 2 --core lost --out " + Path("flange")).exitCode, 2);
    EXPECT_FALSE(fs::exists(dir_ / "fibres"));
    EXPECT_FALSE(fs::exists(dir_ / "flange"));
    // A plain tube is widest everywhere (its first ring): halves are refused, it is cast whole.
    r = Run("export --model shell --shape cylinder --cast halves --out " + Path("tube"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_THAT(r.err, HasSubstr("cast it whole"));
}
