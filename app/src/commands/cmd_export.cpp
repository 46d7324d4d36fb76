// `actuator export`: a design as the files that go to the printer. The wall as a closed solid of the
// given thickness, the mold's core and its two shells, and manifest.json with every file's volume,
// bounds and triangle count and the silicone's volume and mass. Everything is built and checked
// before the first file is written: a design that cannot be made writes nothing.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "formats/archive.h"
#include "options/cli.h"
#include "commands/registry.h"
#include "pictures/figures.h"
#include "formats/files.h"
#include "formats/json_out.h"
#include "options/model_options.h"
#include "options/part_options.h"
#include "options/shape_options.h"
#include "formats/solid_io.h"
#include "report/part_export.h"
#include "sim/casting.h"
#include "sim/shell.h"
#include "sim/solid.h"

namespace app {


static int RunExport(int argc, char** argv, int first) {
    namespace fs = std::filesystem;
    Cli cli("export", "Writes a design as solids to print and cast, into --out DIR (new or empty): actuator.stl (the wall as a closed solid of "
                      "the given thickness around the rest surface, ends closed by flat annuli), mold_core.stl (the inner cavity with a "
                      "handle through each end of the block), mold_shell_a.stl and mold_shell_b.stl (the block around the actuator split "
                      "through its axis at y = 0, with registration pins on A and holes in B, a sprue in A's bottom wall to fill from below "
                      "and four vents in the top wall), "
                      "with --fittings fitting_bottom.stl and fitting_top.stl (end plugs, the bottom one bored for the air line), for a fibre design "
                      "the first stage's mold (stage1_shell_a.stl, stage1_shell_b.stl: the wall's inner half with guide grooves along the "
                      "threads, stage1_layer.stl) and winding_guides.png, "
                      "mold_assembly.png (the parts side by side), casting.md (what to print, mix and pour, in order) and manifest.json "
                      "(each file's volume in mm^3, bounds, triangles, print orientation; the silicone to mix and the fill's time). The design is given as for simulate. Under --model thesis one design unit is --unit-mm "
                      "millimetres (the 30-turn mesh is 30 units long); under membrane and shell the geometry options give radius, length "
                      "and wall. A design that cannot be made is refused naming where and why, and nothing is written.");
    ShapeOptions shape;
    ModelOptions model;
    std::string from, out;
    int index = 0;
    AddShapeOptions(cli, shape);
    AddModelOptions(cli, model);
    cli.Group("Design from an archive");
    cli.Text("--from", from, "export a stored design: an archive (DIR/evaluations.capnp) with --index")->type_name("ARCHIVE");
    cli.Integer("--index", index, "with --from: the evaluation id (see actuator inspect)", 0, 1ll << 40)->default_str("");
    PartOptions partOptions;
    bool ascii = false;
    SolidFormat format = SolidFormat::Stl;
    AddPartOptions(cli, partOptions);
    cli.Group("Files");
    cli.Text("--out", out, "folder for the files; must be new or empty")->type_name("DIR");
    cli.Enum("--format", format, "file format: binary STL (default), OBJ or binary PLY");
    cli.Flag("--ascii", ascii, "ASCII STL instead of binary");
    std::string printerText = "220x220x250";
    cli.Text("--printer-mm", printerText, "the printer's build volume, WIDTHxDEPTHxHEIGHT mm: each printed part's size in its suggested orientation is "
                                          "checked against it")
        ->type_name("WxDxH")
        ->default_str(printerText);
    sim::CastKind cast = sim::CastKind::Whole;
    double flangeMm = 3;
    cli.Group("Casting");
    cli.Enum("--cast", cast, "whole: one mold; halves: cut across the axis at the widest section into two pieces, each in its own mold with a "
                             "one-piece core that leaves through the cut, bonded at their flanges (docs/guide/export.md)");
    cli.Number("--flange-mm", flangeMm, "with --cast halves: the bonding flange beyond the wall's outer face at the cut, mm", 0.5, 50)->default_str("3");
    double threadSpacingMm = 3;
    cli.Number("--thread-spacing-mm", threadSpacingMm, "fibre designs: the threads of a family at most this far apart across, where the tube is "
                                                       "widest (sets the threads per family and the EA each needs)", 0.5, 100)
        ->default_str("3");
    double viscosityCps = 0, potLifeMin = 0;
    cli.Group("Pour");
    cli.Number("--viscosity-cps", viscosityCps, "the mixed silicone's viscosity, cps = mPa s, for the fill-time estimate (default: the preset's bulletin; "
                                                "needed for a material of your own)", 1, 1e7)
        ->default_str("");
    cli.Number("--pot-life-min", potLifeMin, "its pot life, minutes (default: the preset's bulletin)", 0.1, 1e4)->default_str("");
    cli.Examples(
        "  actuator export --model thesis --shape sine --amplitude 1.3 --phase 0.5,pi-0.5 --unit-mm 5 --wall-mm 1 --out part/\n"
        "  actuator export --shape bspline --region middle --control-points \"1,1.3,1.1,1.5\" --thickness-mm 1.5 --out part/\n"
        "  actuator export --from runs/5.2/evaluations.capnp --index 17 --out part/ --wall outward\n"
        "  actuator export --shape cylinder --out part/ --format obj\n");
    if (!cli.Parse(argc, argv, first)) return 0;
    if (!cli.Given("--out")) throw UsageError("--out DIR is required (a new or empty folder)");

    sim::EvalJob job;
    if (cli.Given("--from")) {
        job = ArchivedJob(cli, model, from, index, ModelUse::CastPart);
    } else {
        cli.RefuseIfGiven("--index", "goes with --from ARCHIVE");
        job = BuildJob(cli, shape, model, ModelUse::CastPart);
    }
    ExportDef d;
    d.part = PartDefOf(cli, partOptions, job);
    d.mold = partOptions.mold;
    d.fittings = partOptions.fittings;
    d.format = format;
    d.ascii = ascii;
    d.printerMm = printerText;
    d.cast = cast;
    if (cli.Given("--flange-mm")) d.flangeMm = flangeMm;
    if (cli.Given("--thread-spacing-mm")) d.threadSpacingMm = threadSpacingMm;
    if (cli.Given("--viscosity-cps")) d.viscosityCps = viscosityCps;
    if (cli.Given("--pot-life-min")) d.potLifeMin = potLifeMin;
    if (cli.Given("--from")) d.from = Json{{"archive", from}, {"index", index}};
    std::cout << ExportPart(job, d, out).dump() << "\n";
    return 0;
}

static const RegisterCommand kExportCommand{{"export", "a design as solids to print and cast: the actuator's wall, a mold's core and two shells (STL, OBJ, PLY)", 60, RunExport}};

}  // namespace app
