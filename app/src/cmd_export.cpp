// `actuator export`: a design as the files that go to the printer. The wall as a closed solid of the
// given thickness, the mold's core and its two shells, and manifest.json with every file's volume,
// bounds and triangle count and the silicone's volume and mass. Everything is built and checked
// before the first file is written: a design that cannot be made writes nothing.
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "archive.h"
#include "cli.h"
#include "commands.h"
#include "figures.h"
#include "files.h"
#include "json_out.h"
#include "model_options.h"
#include "shape_options.h"
#include "solid_io.h"
#include "sim/shell.h"
#include "sim/solid.h"

namespace app {

namespace {

// The parts side by side: the core, the actuator, and the block's halves with their split faces
// (and so the cavity) turned to the camera, shell B turned half a turn about the axis to show its
// own; one picture, each part its own colour.
render::Scene ExplodedScene(const sim::PartSolids& solids, const std::string& title) {
    const auto bounds = sim::MeshBounds(solids.shellA);
    const double w = bounds[3], step = 2.7 * w;
    struct Placed {
        const sim::TriangleMesh* mesh;
        double shiftX;
        bool turned;
    };
    const Placed parts[] = {{&solids.actuator, 0, false}, {&solids.core, -step, false}, {&solids.shellA, step, false}, {&solids.shellB, 2 * step, true}};
    auto surface = std::make_shared<sim::Surface>();
    render::Panel panel;
    for (int k = 0; k < 4; ++k) {
        const auto& [mesh, shiftX, turned] = parts[k];
        const int base = surface->vertexCount;
        for (const auto& v : mesh->vertices) {
            panel.positions.x.push_back((turned ? -v[0] : v[0]) + shiftX);
            panel.positions.y.push_back(turned ? -v[1] : v[1]);
            panel.positions.z.push_back(v[2]);
            panel.values.push_back(k);
        }
        for (const auto& t : mesh->triangles) surface->triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
        surface->vertexCount += static_cast<int>(mesh->vertices.size());
    }
    render::Scene scene;
    scene.surface = surface;
    scene.title = title;
    scene.lines = {"left to right: the core, the actuator, the block's halves A and B with their split faces turned to you"};
    scene.panels = {std::move(panel)};
    scene.colorBy = render::ColorBy::Values;
    scene.colorMin = 0;
    scene.colorMax = 3;
    scene.colorLabel = "part: 0 actuator,\n1 core, 2 shell A,\n3 shell B";
    return scene;
}

}  // namespace

int RunExport(int argc, char** argv, int first) {
    namespace fs = std::filesystem;
    Cli cli("export", "Writes a design as solids to print and cast, into --out DIR (new or empty): actuator.stl (the wall as a closed solid of "
                      "the given thickness around the rest surface, ends closed by flat annuli), mold_core.stl (the inner cavity with a "
                      "handle through each end of the block), mold_shell_a.stl and mold_shell_b.stl (the block around the actuator split "
                      "through its axis at y = 0) mold_assembly.png (the parts pulled apart) and manifest.json (each file's volume in mm^3, "
                      "bounds, triangles; the silicone's volume and mass). The design is given as for simulate. Under --model thesis one design unit is --unit-mm millimetres "
                      "(the 30-turn mesh is 30 units long); under membrane and shell the geometry options give radius, length and wall.");
    ShapeOptions shape;
    ModelOptions model;
    std::string from, out;
    int index = 0;
    AddShapeOptions(cli, shape);
    AddModelOptions(cli, model);
    cli.Group("Design from an archive");
    cli.Text("--from", from, "export a stored design: an archive (DIR/evaluations.capnp) with --index")->type_name("ARCHIVE");
    cli.Integer("--index", index, "with --from: the evaluation id (see actuator inspect)", 0, 1ll << 40)->default_str("");
    sim::PartDef part;
    sim::MoldDef mold;
    double unitMm = 5, wallMm = part.thicknessMm;
    int sampling = 4;
    bool ascii = false;
    SolidFormat format = SolidFormat::Stl;
    cli.Group("Part");
    cli.Text("--out", out, "folder for the files; must be new or empty")->type_name("DIR");
    cli.Enum("--wall", part.wall, "centred: half the wall each side of the rest surface; outward: the rest surface is the wall's inside");
    cli.Number("--unit-mm", unitMm, "thesis-model designs: millimetres per design unit (radius 1, length 30 turns)", 1e-3, 1e4)->default_str("5");
    cli.Number("--wall-mm", wallMm, "thesis-model designs: wall thickness, mm (membrane and shell: --thickness-mm)", 1e-3, 1e3)->default_str("1");
    cli.Integer("--sampling", sampling,
                "surface samples per simulation-mesh edge, around and along (smooth designs look faceted at 30 x 30); the helix's "
                "--resolution stays the simulation mesh's",
                1, 64)
        ->default_str("4");
    cli.Enum("--format", format, "file format: binary STL (default), OBJ or binary PLY");
    cli.Flag("--ascii", ascii, "ASCII STL instead of binary");
    cli.Group("Mold");
    cli.Number("--margin-mm", mold.marginMm, "block beyond the actuator's widest point", 0.1, 1e4)->default_str("5");
    cli.Number("--end-wall-mm", mold.endWallMm, "block beyond each end of the actuator", 0.1, 1e4)->default_str("5");
    cli.Number("--handle-mm", mold.handleMm, "core beyond the block at each end, to hold and pull it", 0.1, 1e4)->default_str("15");
    cli.Number("--sprue-deg", mold.sprueDegrees, "arc of the pour slot through shell A's top wall, centred at 90 degrees", 0, 120)->default_str("24");
    cli.Number("--vent-deg", mold.ventDegrees, "arc of each of shell B's two vent slots (225 and 315 degrees)", 0, 60)->default_str("6");
    cli.Examples(
        "  actuator export --shape sine --amplitude 1.3 --phase 0.5,pi-0.5 --unit-mm 5 --wall-mm 1 --out part/\n"
        "  actuator export --model shell --shape bspline --region middle --control-points \"1,1.3,1.1,1.5\" --thickness-mm 1.5 --out part/\n"
        "  actuator export --from runs/5.2/evaluations.capnp --index 17 --out part/ --wall outward\n"
        "  actuator export --shape cylinder --out part/ --format obj\n");
    if (!cli.Parse(argc, argv, first)) return 0;
    const auto started = std::chrono::steady_clock::now();
    if (!cli.Given("--out")) throw UsageError("--out DIR is required (a new or empty folder)");
    if (ascii && format != SolidFormat::Stl) throw UsageError("--ascii is for STL; OBJ is text already and PLY is written binary");

    sim::EvalJob job;
    if (cli.Given("--from")) {
        for (const auto& name : ShapeOptionNames()) cli.RefuseIfGiven(name, "does not go with --from: the design comes from the archive");
        cli.RefuseIfGiven("--model", "does not go with --from: the model comes from the archive");
        if (!cli.Given("--index")) throw UsageError("--from ARCHIVE needs --index K (list them with actuator inspect)");
        job = ReadArchiveRecord(from, static_cast<std::uint64_t>(index)).job;
        if (job.model != sim::ModelKind::Thesis) cli.CopyGivenFields(model.shell.geometry, job.shell.geometry);
    } else {
        cli.RefuseIfGiven("--index", "goes with --from ARCHIVE");
        job = BuildJob(cli, shape, model);
    }
    // The part's size: thesis designs in design units times --unit-mm; the shell models' geometry.
    if (job.model == sim::ModelKind::Thesis) {
        part.radiusMm = unitMm;
        part.lengthMm = unitMm * job.mesh.turns;
        part.thicknessMm = wallMm;
        part.clampFraction = static_cast<double>(sim::kClampedTurns) / job.mesh.turns;
        part.angularSamples = 8 * ((job.mesh.resolution * sampling + 7) / 8);
        part.axialSamples = job.mesh.turns * sampling + 1;
    } else {
        cli.RefuseIfGiven("--unit-mm", "is for thesis-model designs; the membrane and shell models' size is --radius-mm and --length-mm");
        cli.RefuseIfGiven("--wall-mm", "is for thesis-model designs; the membrane and shell models' wall is --thickness-mm");
        const sim::GeometryDef& g = job.shell.geometry;
        const int rings = sim::RingCount(g);
        part.radiusMm = g.radiusMm;
        part.lengthMm = g.lengthMm;
        part.thicknessMm = g.thicknessMm;
        part.clampFraction = rings > 1 ? static_cast<double>(g.clampRings - 1) / (rings - 1) : 0;
        part.angularSamples = 8 * ((g.ringVertices * sampling + 7) / 8);
        part.axialSamples = (rings - 1) * sampling + 1;
    }

    sim::PartSolids solids;
    if (const std::string error = sim::BuildPartSolids(job.shape, part, mold, &solids); !error.empty()) throw UsageError("cannot make this design: " + error);

    // The folder: new or empty, so that a part's files never mix with another's.
    std::error_code ec;
    if (fs::exists(out, ec) && !(fs::is_directory(out, ec) && fs::is_empty(out, ec)))
        throw UsageError("--out " + Quote(out) + " exists and is not an empty folder; export writes into a new or empty one");
    fs::create_directories(out, ec);
    if (!fs::is_directory(out, ec)) throw UsageError("cannot create folder " + Quote(out));

    const std::string extension = Extension(format);
    const std::pair<std::string, const sim::TriangleMesh*> files[] = {{"actuator", &solids.actuator},
                                                                      {"mold_core", &solids.core},
                                                                      {"mold_shell_a", &solids.shellA},
                                                                      {"mold_shell_b", &solids.shellB}};
    Json manifest;
    manifest["units"] = "mm";
    Json list = Json::array();
    for (const auto& [name, mesh] : files) {
        const std::string file = name + extension;
        WriteFileAtomically((fs::path(out) / file).string(), FormatSolid(*mesh, format, ascii, name + " (actuator workbench)"));
        const auto b = sim::MeshBounds(*mesh);
        list.push_back(Json{{"file", file},
                            {"volume_mm3", sim::MeshVolume(*mesh)},
                            {"bounds_mm", Json{{"min", {b[0], b[1], b[2]}}, {"max", {b[3], b[4], b[5]}}}},
                            {"triangles", mesh->triangles.size()},
                            {"vertices", mesh->vertices.size()}});
    }
    {  // The exploded assembly, to look at before printing.
        auto renderer = MakeRenderer(1400, 1000);
        WritePng((fs::path(out) / "mold_assembly.png").string(),
                 renderer->Render(ExplodedScene(solids, fmt::format("mold for {}  -  wall {:g} mm", ShapeTitle(job.shape), part.thicknessMm))), 6);
    }
    manifest["files"] = list;
    const double silicone = sim::MeshVolume(solids.actuator);
    const sim::MaterialDef material = job.model == sim::ModelKind::Thesis ? sim::DefaultShellDef().material : job.shell.material;
    manifest["silicone"] = Json{{"volume_mm3", silicone},
                                {"material", sim::Name(material.preset)},
                                {"density_kg_per_m3", material.densityKgPerM3},
                                {"mass_g", silicone * 1e-9 * material.densityKgPerM3 * 1e3}};
    manifest["core_outside_block_mm3"] = solids.coreOutsideBlockMm3;
    // The block = the shells + the actuator + the core inside it + the sprue and vents - (pins - holes).
    manifest["sprue_and_vents_mm3"] = solids.openingsMm3;
    manifest["pins_less_holes_mm3"] = solids.pinsLessHolesMm3;
    manifest["part"] = Json{{"radius_mm", part.radiusMm},
                            {"length_mm", part.lengthMm},
                            {"wall_mm", part.thicknessMm},
                            {"wall", sim::Name(part.wall)},
                            {"samples_around", part.angularSamples},
                            {"samples_along", part.axialSamples}};
    manifest["mold"] = Json{{"margin_mm", mold.marginMm}, {"end_wall_mm", mold.endWallMm}, {"handle_mm", mold.handleMm},
                            {"sprue_deg", mold.sprueDegrees}, {"vent_deg", mold.ventDegrees}, {"pin_clearance_mm", mold.pinClearanceMm},
                            {"sector_blend_deg", sim::SectorBlendRadians(part) * 180 / 3.141592653589793}};
    manifest["design"] = Json{{"shape", ShapeJson(job.shape)}, {"model", ModelJson(job)}};
    if (cli.Given("--from")) manifest["design"]["from"] = Json{{"archive", from}, {"index", index}};
    WriteFileAtomically((fs::path(out) / "manifest.json").string(), manifest.dump(2) + "\n");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::cout << Json{{"out", out}, {"silicone_volume_mm3", silicone}, {"files", 6}, {"seconds", seconds}}.dump() << "\n";
    return 0;
}

}  // namespace app
