#include "report/part_export.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "pictures/figures.h"
#include "formats/files.h"
#include "formats/json_out.h"
#include "options/part_options.h"
#include "formats/solid_io.h"
#include "report/casting_sheet.h"
#include "sim/casting.h"
#include "sim/shell.h"
#include "sim/solid.h"

#include "support/errors.h"

namespace app {

namespace {

// "220x220x250": a printer's build volume, mm.
std::array<double, 3> PrinterVolume(const std::string& text) {
    std::array<double, 3> size{};
    char x1 = 0, x2 = 0, rest = 0;
    if (std::sscanf(text.c_str(), "%lf%c%lf%c%lf%c", &size[0], &x1, &size[1], &x2, &size[2], &rest) != 5 || x1 != 'x' || x2 != 'x' ||
        !(size[0] > 0 && size[1] > 0 && size[2] > 0 && size[0] < 1e5 && size[1] < 1e5 && size[2] < 1e5))
        throw UsageError("--printer-mm: expected WIDTHxDEPTHxHEIGHT in mm, e.g. 220x220x250, got " + Quote(text));
    return size;
}

// How a printed part goes on the bed, its size there, and whether it fits the printer. The shells lie
// on their split face, cavity up (no support in the cavity); the core stands on its handle when it
// is short enough, else lies along the bed; fittings stand on their collar.
Json PrintHint(const std::string& name, const std::array<double, 6>& b, const std::array<double, 3>& printer) {
    const double dx = b[3] - b[0], dy = b[4] - b[1], dz = b[5] - b[2];
    std::string orientation;
    std::array<double, 3> size{};  // on the bed: two sides, then the height
    if (name.find("_shell_") != std::string::npos) {
        orientation = "split face (y = 0) on the bed, cavity facing up";
        size = {dx, dz, dy};
    } else if (name.find("mold_core") != std::string::npos) {
        const bool upright = dz <= printer[2];
        orientation = upright ? "standing on its bottom handle, axis vertical" : "lying along the bed, axis horizontal, with supports";
        size = upright ? std::array<double, 3>{dx, dy, dz} : std::array<double, 3>{dz, dx, dy};
    } else {
        orientation = "standing on its collar, axis vertical";
        size = {dx, dy, dz};
    }
    const bool fits = size[2] <= printer[2] && ((size[0] <= printer[0] && size[1] <= printer[1]) || (size[0] <= printer[1] && size[1] <= printer[0]));
    return Json{{"orientation", orientation}, {"size_mm", {size[0], size[1], size[2]}}, {"fits_printer", fits}};
}

}  // namespace

nlohmann::json ExportPart(const sim::EvalJob& job, const ExportDef& d, const std::string& out) {
    namespace fs = std::filesystem;
    using Json = nlohmann::json;
    const auto started = std::chrono::steady_clock::now();
    if (d.ascii && d.format != SolidFormat::Stl) throw UsageError("--ascii is for STL; OBJ is text already and PLY is written binary");
    const std::array<double, 3> printer = PrinterVolume(d.printerMm);
    const sim::PartDef& part = d.part;
    const sim::MoldDef& mold = d.mold;
    const sim::PartSolids solids = BuildSolids(job, part, mold, d.fittings);
    // A one-piece core must leave the cured part through an end, the wall stretched over it.
    const double flangeMm = d.flangeMm.value_or(ExportDef{}.defaultFlangeMm);
    const double threadSpacingMm = d.threadSpacingMm.value_or(ExportDef{}.defaultThreadSpacingMm);
    const sim::MaterialDef material = CastMaterialOf(job);
    const sim::CoreExit& exit = solids.coreExit;
    const double demouldLimit = sim::DemouldingStretchLimit(material);
    const bool halves = d.cast == sim::CastKind::Halves;
    if (d.flangeMm && !halves) throw UsageError("--flange-mm goes with --cast halves (the flange the halves are bonded at)");
    auto refuseCore = [&](const sim::CoreExit& e, const std::string& which, double offsetMm, const std::string& ways) {
        if (mold.core == sim::CoreKind::Rigid && e.stretch > demouldLimit)
            throw UsageError(fmt::format(
                "cannot demould {}one-piece core: to leave through the {} end, its {:.1f} mm section must pass the wall's {:.1f} mm section at "
                "z = {:.1f} mm, a hoop stretch of {:.2f}, more than the {:.2f} {} allows (docs/guide/export.md); {}",
                which, e.top ? "top" : "bottom", e.coreAcrossMm, e.openingMm, e.zMm + offsetMm, e.stretch, demouldLimit, sim::Name(material.preset), ways));
    };
    if (!halves)
        refuseCore(exit, "this design's ", 0,
                   "give --core lost for a core printed to dissolve or melt out, or --cast halves to cut it at its widest section");
    // Cast in halves: cut across the axis at the widest section (of the core, the inner wall), each
    // half's core leaving through the cut.
    struct Half {
        std::string name;
        sim::PartDef part;
        sim::PartSolids solids;
    };
    std::vector<Half> pieces;
    if (halves) {
        if (job.model != sim::ModelKind::Thesis && job.Shell().fibres.layout != sim::FibreLayout::None)
            throw UsageError("--cast halves is for designs without fibres (a wound layer would cross the cut); cast a fibre design whole");
        if (mold.core == sim::CoreKind::Rigid && exit.stretch <= demouldLimit)
            throw UsageError(fmt::format("--cast halves: the whole part's one-piece core leaves through its {} end (a hoop stretch of {:.2f}, within "
                                         "{:.2f}); cast it whole, without a bond line",
                                         exit.top ? "top" : "bottom", exit.stretch, demouldLimit));
        const auto& perimeter = solids.corePerimeterMm;
        const int nz = static_cast<int>(perimeter.size());
        const int widest = static_cast<int>(std::max_element(perimeter.begin(), perimeter.end()) - perimeter.begin());
        if (widest < 2 || widest > nz - 3)
            throw UsageError(fmt::format("--cast halves: the design is widest at its {} end; a one-piece core leaves through it, so cast it whole",
                                         widest < 2 ? "bottom" : "top"));
        for (const bool top : {false, true}) {
            Half h{top ? "top" : "bottom", part, {}};
            const double cut = static_cast<double>(widest) / (nz - 1);
            (top ? h.part.fromFraction : h.part.toFraction) = cut;
            h.part.axialSamples = top ? nz - widest : widest + 1;  // the whole part's rings
            h.part.flangeMm = flangeMm;
            h.solids = BuildSolids(job, h.part, mold);
            refuseCore(h.solids.coreExit, "the " + h.name + " half's ", top ? cut * part.lengthMm : 0,
                       "give --core lost: one cut at the widest section is not enough for this design");
            pieces.push_back(std::move(h));
        }
    }

    // The fibres as threads to wind (the models' fibres; the thesis model has none).
    std::vector<sim::FibreWinding> winding;
    const sim::FibreDef fibres = job.model == sim::ModelKind::Thesis ? sim::FibreDef{} : job.Shell().fibres;
    if (d.threadSpacingMm && (fibres.layout == sim::FibreLayout::None || (!fibres.plus && !fibres.minus)))
        throw UsageError("--thread-spacing-mm applies to a design with fibres (it spaces their threads); this one has none");
    {
        std::string error;
        winding = sim::PlanWinding(solids, part, fibres, threadSpacingMm, &error);
        if (!error.empty()) throw UsageError("cannot wind this design's fibres: " + error);
    }
    // A fibre design is cast in two stages: the wall's inner half in a first mold whose cavity has
    // ribs along the threads (the layer's guide grooves), wound, then overmoulded in the full mold.
    const bool twoStages = !winding.empty();
    const sim::PartDef firstPart = twoStages ? sim::FirstStagePart(part, winding) : part;
    const sim::PartSolids firstStage = twoStages ? BuildSolids(job, firstPart, mold) : sim::PartSolids{};

    // The folder: new or empty, so that a part's files never mix with another's.
    CheckNewOrEmptyFolder(out, "--out");
    // Every file or none: a full disk leaves no part of the set, and no folder that was not there.
    CreatedFolders folders;
    folders.Create(out, "--out");
    OutputBatch batch;

    const std::string extension = Extension(d.format);
    std::vector<std::pair<std::string, const sim::TriangleMesh*>> files{
        {"actuator", &solids.actuator}, {"mold_core", &solids.core}, {"mold_shell_a", &solids.shellA}, {"mold_shell_b", &solids.shellB}};
    if (d.fittings.enabled) files.insert(files.end(), {{"fitting_bottom", &solids.fittingBottom}, {"fitting_top", &solids.fittingTop}});
    if (twoStages)
        files.insert(files.end(), {{"stage1_layer", &firstStage.actuator}, {"stage1_shell_a", &firstStage.shellA}, {"stage1_shell_b", &firstStage.shellB}});
    if (halves) {  // the halves' own molds replace the whole one's
        files.erase(std::remove_if(files.begin(), files.end(), [](const auto& f) { return f.first.rfind("mold_", 0) == 0; }), files.end());
        for (const Half& h : pieces)
            files.insert(files.end(), {{h.name + "_half", &h.solids.actuator}, {h.name + "_mold_core", &h.solids.core},
                                       {h.name + "_mold_shell_a", &h.solids.shellA}, {h.name + "_mold_shell_b", &h.solids.shellB}});
    }
    Json manifest;
    manifest["units"] = "mm";
    Json list = Json::array();
    std::vector<std::string> tooLarge;
    for (const auto& [name, mesh] : files) {
        const std::string file = name + extension;
        WriteFileAtomically((fs::path(out) / file).string(), FormatSolid(*mesh, d.format, d.ascii, name + " (actuator workbench)"));
        const auto b = sim::MeshBounds(*mesh);
        list.push_back(Json{{"file", file},
                            {"volume_mm3", sim::MeshVolume(*mesh)},
                            {"bounds_mm", Json{{"min", {b[0], b[1], b[2]}}, {"max", {b[3], b[4], b[5]}}}},
                            {"triangles", mesh->triangles.size()},
                            {"vertices", mesh->vertices.size()}});
        if (name == "actuator" || name == "stage1_layer" || (name.size() > 5 && name.compare(name.size() - 5, 5, "_half") == 0)) {
            list.back()["print"] = Json{{"orientation", name == "actuator"       ? (halves ? "the bonded halves, cast in silicone, not printed" : "cast in silicone, not printed")
                                                        : name == "stage1_layer" ? "the first stage's silicone layer, not printed"
                                                                                 : "a half, cast in silicone, not printed"}};
            continue;
        }
        list.back()["print"] = PrintHint(name, b, printer);
        if (!list.back()["print"]["fits_printer"].get<bool>()) tooLarge.push_back(file);
    }
    {  // The exploded assembly, to look at before printing.
        auto renderer = MakeRenderer(1400, 1000);
        WritePng((fs::path(out) / "mold_assembly.png").string(),
                 renderer->Render(ExplodedMoldScene(halves ? pieces[0].solids : solids,
                                                    fmt::format("{}mold for {}  -  wall {:g} mm", halves ? "bottom half's " : twoStages ? "two-stage " : "",
                                                                ShapeTitle(job.shape), part.thicknessMm),
                                                    twoStages ? &firstStage : nullptr)),
                 6);
        if (halves)
            WritePng((fs::path(out) / "mold_assembly_top.png").string(),
                     renderer->Render(ExplodedMoldScene(pieces[1].solids, fmt::format("top half's mold for {}  -  wall {:g} mm", ShapeTitle(job.shape),
                                                                                      part.thicknessMm))),
                     6);
    }
    if (twoStages) {  // the layer with its grooves and the threads to wind in them
        auto renderer = MakeRenderer(1400, 1000);
        WritePng((fs::path(out) / "winding_guides.png").string(),
                 renderer->Render(WindingGuidesScene(firstStage, winding, fmt::format("winding guides for {}", ShapeTitle(job.shape)))), 6);
    }
    manifest["files"] = list;
    manifest["printer_mm"] = {printer[0], printer[1], printer[2]};
    const double silicone = sim::MeshVolume(solids.actuator);
    manifest["silicone"] = Json{{"volume_mm3", silicone},
                                {"material", sim::Name(material.preset)},
                                {"density_kg_per_m3", material.densityKgPerM3},
                                {"mass_g", silicone * 1e-9 * material.densityKgPerM3 * 1e3}};
    manifest["core_outside_block_mm3"] = solids.coreOutsideBlockMm3;
    manifest["core"] = Json{{"kind", sim::Name(mold.core)},
                            {"exit", exit.top ? "top" : "bottom"},
                            {"demoulding_stretch", exit.stretch},
                            {"demoulding_stretch_allowed", demouldLimit},
                            {"tightest_section_z_mm", exit.zMm}};
    if (mold.core == sim::CoreKind::Lost) {
        manifest["core"]["drain_mm"] = solids.drainMm;
        manifest["core"]["drain_in_block_mm3"] = solids.drainInBlockMm3;
        manifest["core"]["how"] =
            "print mold_core in a material that leaves the cured part without a pull: PVA or BVOH (dissolve in warm water), or a wax or "
            "low-melt alloy (melt out below the silicone's limit); after curing, open the shells, cut the handles flush and let the "
            "solvent in, or the melt out, through the drain along the core's axis";
    } else {
        manifest["core"]["how"] = std::string("pull mold_core out through the ") + (exit.top ? "top" : "bottom") + " end by its handle";
    }
    // The pour: from below, the mixing amounts, and the fill's time by gravity and by syringe.
    sim::CastingDef casting = sim::CastingPresetDef(material.preset);
    if (d.viscosityCps) casting.mixedViscosityPaS = *d.viscosityCps / 1000, casting.source = "given (--viscosity-cps)";
    if (d.potLifeMin) casting.potLifeMin = *d.potLifeMin;
    const sim::PourDef pourDef;
    // The pour of a mold (the only one, or the second stage over the wound layer): from below, what
    // to mix, the fill's time.
    auto pourJson = [&](const sim::PourPlan& plan, const sim::PartSolids& mouldSolids, const char* shell) {
        const std::string upright = mouldSolids.markDepthMm > 0 ? fmt::format("upright, the arrow engraved on {}'s back pointing up", shell) : std::string("upright");
        Json pour{{"orientation", fmt::format("{}: the axis vertical, the bottom end (z = 0) down, the sprue in {}'s bottom end wall, the vents up", upright, shell)},
                  {"mark", Json{{"what", "an arrow pointing up, engraved on the back of " + std::string(shell) + ", over the sprue"},
                                {"depth_mm", mouldSolids.markDepthMm},
                                {"volume_mm3", mouldSolids.markMm3}}},
                  {"sprue", Json{{"where", fmt::format("{}, bottom end wall, centred at 90 deg", shell)},
                                 {"arc_deg", mouldSolids.sprueDegreesBuilt},
                                 {"across_mm", mouldSolids.sprueGapMm},
                                 {"volume_mm3", mouldSolids.sprueMm3},
                                 {"share_of_fill_resistance", mouldSolids.sprueResistanceShare}}},
                  {"vents", Json{{"where", "top end wall at 45 and 135 deg (shell A), 225 and 315 deg (shell B)"}, {"arc_deg", mold.ventDegrees}}},
                  {"silicone_ml", Json{{"cavity", plan.cavityMl}, {"sprue_and_vents", plan.slotsMl}, {"to_mix", plan.mixMl}}},
                  {"margin", fmt::format("{:g} % of cavity and slots, at least {:g} ml", 100 * pourDef.marginFraction, pourDef.marginMinMl)},
                  {"to_mix_g", Json{{"total", plan.mixG}, {"part_a", plan.partAG}, {"part_b", plan.partBG}}},
                  {"mix_ratio_a_to_b_by_weight", fmt::format("{:g}:1", casting.partsAPerB)}};
        if (casting.mixedViscosityPaS > 0) {
            pour["handling"] = Json{{"mixed_viscosity_cps", casting.mixedViscosityPaS * 1000},
                                    {"pot_life_min", NumberJson(casting.potLifeMin > 0 ? casting.potLifeMin : NAN)},
                                    {"cure_h", NumberJson(casting.cureHours > 0 ? casting.cureHours : NAN)},
                                    {"source", casting.source}};
            pour["fill"] = Json{{"gravity_min", NumberJson(plan.gravityMin)},
                                {"funnel_above_top_mm", pourDef.funnelAboveTopMm},
                                {"syringe_min", NumberJson(plan.syringeMin)},
                                {"syringe_kpa", pourDef.syringeKpa},
                                {"method", casting.potLifeMin > 0 ? (plan.gravity ? "gravity" : plan.tooSlow ? "too slow" : "syringe") : "either"}};
        } else {
            pour["handling"] = Json{{"source", "not known for this material: give --viscosity-cps and --pot-life-min for a fill time"}};
        }
        return pour;
    };
    // Halves are poured each in its own mold (below); a whole part in the one, or over its first stage.
    const sim::PourPlan plan = halves      ? sim::PourPlan{}
                               : twoStages ? sim::PlanPour(solids, part, mold, material, casting, pourDef, firstPart.layerMm, sim::MeshVolume(firstStage.actuator))
                                           : sim::PlanPour(solids, part, mold, material, casting, pourDef);
    if (!halves) manifest["pour"] = pourJson(plan, solids, "mold_shell_a");
    if (halves) {
        Json list = Json::array();
        for (const Half& h : pieces) {
            const sim::PourPlan p = sim::PlanPour(h.solids, h.part, mold, material, casting, pourDef);
            list.push_back(Json{{"half", h.name},
                                {"from_mm", h.part.fromFraction * part.lengthMm},
                                {"to_mm", h.part.toFraction * part.lengthMm},
                                {"files", {h.name + "_mold_core" + extension, h.name + "_mold_shell_a" + extension, h.name + "_mold_shell_b" + extension}},
                                {"core_exit", h.solids.coreExit.top ? "top" : "bottom"},
                                {"demoulding_stretch", h.solids.coreExit.stretch},
                                {"pour", pourJson(p, h.solids, (h.name + "_mold_shell_a").c_str())}});
        }
        const double cutMm = pieces[0].part.toFraction * part.lengthMm;
        manifest["halves"] = Json{
            {"cut_z_mm", cutMm},
            {"flange_mm", flangeMm},
            {"pieces", list},
            {"bond", fmt::format("the halves meet at z = {:.1f} mm, the design's widest section: coat both flanges' faces with a silicone adhesive "
                                 "for platinum silicone (or a thin layer of the same silicone, freshly mixed), align the halves on a rod through both "
                                 "cores' channels, press the flanges together with a clamp ring or tape and cure; the flange stays, {:g} mm proud of "
                                 "the wall",
                                 cutMm, flangeMm)}};
    }
    // The core held at both ends; spacers where it is too slender to stay centred while filling.
    const sim::CoreSupport support = sim::CheckCoreSupport(solids, part, mold, material, pourDef);
    Json spacers = Json::array();
    for (const double z : support.stationsMm) spacers.push_back(Json{{"z_mm", z}, {"angles_deg", {30, 150, 270}}});
    manifest["core"]["support"] = Json{{"held", "at both ends, its handles in both shells' end walls"},
                                       {"slenderness", support.slenderness},
                                       {"thinnest_mm", support.thinnestMm},
                                       {"deflection_mm", support.deflectionMm},
                                       {"allowed_mm", support.allowedMm},
                                       {"modulus_gpa", support.modulusGpa},
                                       {"spacers", spacers}};
    if (!spacers.empty())
        manifest["core"]["support"]["how"] = fmt::format(
            "before closing each mold, press a pad of the same cured silicone, {0:g} mm thick and about 3 x 3 mm (cut from a sheet cast "
            "{0:g} mm thick), onto the core at each spacer's height and angles: the pads hold the core centred and cure into the wall, "
            "where they show as faint squares",
            twoStages ? firstPart.layerMm : part.thicknessMm);
    const sim::PourPlan firstPlan = twoStages ? sim::PlanPour(firstStage, firstPart, mold, material, casting, pourDef) : sim::PourPlan{};
    if (twoStages)
        manifest["first_stage"] = Json{{"layer_mm", firstPart.layerMm},
                                       {"guides", Json{{"depth_mm", firstPart.guides.depthMm}, {"width_mm", firstPart.guides.widthMm}}},
                                       {"files", {"mold_core" + extension, "stage1_shell_a" + extension, "stage1_shell_b" + extension}},
                                       {"pour", pourJson(firstPlan, firstStage, "stage1_shell_a")}};
    if (!winding.empty()) {
        Json families = Json::array();
        for (const sim::FibreWinding& w : winding) {
            Json bands = Json::array();
            for (const sim::WindingBand& b : w.bands)
                bands.push_back(Json{{"from_mm", b.fromMm}, {"to_mm", b.toMm}, {"angle_deg", NumberJson(b.angleDeg)}, {"turns", b.turns},
                                     {"pitch_mm", NumberJson(b.pitchMm)}});
            Json starts = Json::array();
            for (const sim::ThreadPath& t : w.threads) starts.push_back(t.startDeg);
            families.push_back(Json{{"family", w.family},
                                    {"hand", w.hand},
                                    {"threads", w.threads.size()},
                                    {"start_angles_deg", starts},
                                    {"thread_mm", w.pathMm},
                                    {"turns", w.turns},
                                    {"spacing_mm", {w.spacingMinMm, w.spacingMaxMm}},
                                    {"ea_per_thread_n", w.eaPerThreadN},
                                    {"bands", bands}});
        }
        manifest["fibres"] = Json{
            {"layout", sim::Name(fibres.layout)},
            {"stiffness_n_per_mm", fibres.stiffnessNPerMm},
            {"families", families},
            {"thread_spacing_mm", threadSpacingMm},
            {"order", winding.size() > 1 ? "the +alpha family's threads first, each bottom to top, then the -alpha family's over them"
                                         : "one family, each thread bottom to top"},
            {"how", fmt::format("wound on the first stage's layer (the wall's inner {:g} mm, on the core) in its guide grooves ({:g} mm deep, "
                                "{:g} mm wide), each thread from its groove's start on the bottom end, then overmoulded",
                                firstPart.layerMm, firstPart.guides.depthMm, firstPart.guides.widthMm)}};
    }
    // The block = the shells + the actuator + the core inside it + the sprue and vents - (pins - holes).
    manifest["sprue_and_vents_mm3"] = solids.openingsMm3;
    manifest["pins_less_holes_mm3"] = solids.pinsLessHolesMm3;
    manifest["part"] = Json{{"radius_mm", part.radiusMm},
                            {"length_mm", part.lengthMm},
                            {"wall_mm", part.thicknessMm},
                            {"wall", sim::Name(part.wall)},
                            {"samples_around", part.angularSamples},
                            {"samples_along", part.axialSamples}};
    if (d.fittings.enabled) manifest["fittings"] = Json{{"port_mm", d.fittings.portMm}, {"collar_mm", d.fittings.collarMm}};
    manifest["mold"] = Json{{"margin_mm", mold.marginMm}, {"end_wall_mm", mold.endWallMm}, {"handle_mm", mold.handleMm},
                            {"sprue_deg", mold.sprueDegrees}, {"vent_deg", mold.ventDegrees}, {"pin_clearance_mm", mold.pinClearanceMm},
                            {"sector_blend_deg", sim::SectorBlendRadians(part) * 180 / 3.141592653589793}};
    manifest["design"] = Json{{"shape", ShapeJson(job.shape)}, {"model", ModelJson(job)}};
    if (!d.from.is_null()) manifest["design"]["from"] = d.from;
    WriteFileAtomically((fs::path(out) / "manifest.json").string(), manifest.dump(2) + "\n");
    WriteFileAtomically((fs::path(out) / "casting.md").string(), CastingSheet(manifest));
    batch.Commit();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    Json summary{{"out", out}, {"silicone_volume_mm3", silicone}, {"files", files.size() + 3 + (twoStages ? 1 : 0) + (halves ? 1 : 0)}, {"seconds", seconds}};
    if (plan.tooSlow || firstPlan.tooSlow)
        summary["warning_pour"] = fmt::format("{:.1f} min to fill by syringe, more than half the {:g} min pot life (casting.md, pour)", plan.syringeMin,
                                              casting.potLifeMin);
    if (!tooLarge.empty()) {
        std::string names;
        for (const std::string& f : tooLarge) names += (names.empty() ? "" : ", ") + f;
        summary["warning"] = "larger than the " + d.printerMm + " mm printer in the suggested orientation: " + names + " (manifest.json, print)";
    }
    return summary;
}

}  // namespace app
