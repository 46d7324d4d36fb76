// `actuator characterize`: a muscle's characteristic curves, as an artificial-muscle paper shows them
// (docs/models/shell.md section 12): the isobaric force against contraction at each pressure (from
// no contraction to the free stroke, the force being the held stroke's reaction), the isometric
// force against pressure (the blocked test's force at every load step) and the free stroke against
// pressure. One CSV, three plots and a JSON summary.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>

#include "commands/registry.h"
#include "formats/archive.h"
#include "evaluation/characterize.h"
#include "formats/csv.h"
#include "formats/evaluation_log.h"
#include "formats/files.h"
#include "formats/json_out.h"
#include "formats/table.h"
#include "options/cli.h"
#include "options/model_options.h"
#include "options/shape_options.h"
#include "pictures/figures.h"
#include "pictures/plots.h"

namespace app {
namespace {

namespace fs = std::filesystem;

std::vector<double> ParsePressures(const std::string& text) {
    std::vector<double> pressures;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, end - start);
        double value = NAN;
        const auto [rest, error] = std::from_chars(item.data(), item.data() + item.size(), value);
        if (item.empty() || error != std::errc() || rest != item.data() + item.size())
            throw UsageError("--pressures-kpa: " + Quote(item) + " is not a pressure in kPa above 0 (give a list such as 5,10,20)");
        pressures.push_back(value);
        start = end + 1;
    }
    if (const std::string error = PressuresError(pressures); !error.empty()) throw UsageError("--pressures-kpa: " + error + " (such as 5,10,20)");
    return pressures;
}

}  // namespace

static int RunCharacterize(int argc, char** argv, int first) {
    Cli cli("characterize",
            "A muscle's characteristic curves under --model membrane or shell: at each pressure the force it pulls with against its "
            "contraction, from none to its free stroke (the isobaric test: the top held at each contraction); the force with the top held at "
            "its rest place against pressure (isometric); and the free stroke against pressure. The top may turn as the design's --twist "
            "says (free by default, as on a bench). Writes DIR/characteristic.csv, DIR/force_contraction.png, DIR/force_pressure.png and "
            "DIR/stroke_pressure.png; every evaluation behind them in DIR/evaluations.capnp (for inspect, render and simulate --from) and in "
            "DIR/evaluations.csv, and prints a JSON summary. Forces in N (positive = the muscle pulls on its supports), contraction in "
            "percent of the length (positive = shorter), pressures in kPa.");
    ShapeOptions shape;
    ModelOptions model;
    std::string pressuresText = "5,10,20", out;
    int points = 6, threads = 0;
    AddShapeOptions(cli, shape);
    AddModelOptions(cli, model);
    std::string from;
    int index = 0;
    cli.Group("Design from an archive");
    cli.Text("--from", from, "characterize a stored design: an archive (DIR/evaluations.capnp) with --index; its model settings are kept")
        ->type_name("ARCHIVE");
    cli.Integer("--index", index, "with --from: the evaluation id (see actuator inspect)", 0, 1ll << 40)->default_str("");
    cli.Group("Curves");
    cli.Text("--pressures-kpa", pressuresText, "the isobaric curves' pressures, increasing; the highest is the isometric and free-stroke curves' end")
        ->type_name("LIST");
    cli.Integer("--points", points, "points of each isobaric curve, from no contraction to the free stroke", 2, 100);
    cli.Integer("--threads", threads, "evaluation threads (0: every core); results do not depend on it", 0, 1024)->default_str("0 (every core)");
    bool overwrite = false;
    cli.Text("--out", out, "folder for the table, the plots and the archive (created if missing); required")->type_name("DIR");
    cli.Flag("--overwrite", overwrite, "replace the files of an earlier characterize in --out");
    cli.Examples(
        "  actuator characterize --shape cylinder --fibres braid --fibre-angle-deg 30 --out curves/braid\n"
        "  actuator characterize --shape sine --amplitude 1.3 --fibres single --fibre-angle-deg 40 --twist held --pressures-kpa 2,4 --out curves/held\n"
        "  actuator characterize --from runs/pareto/evaluations.capnp --index 91 --pressures-kpa 0.2,0.4 --out curves/best\n");
    if (!cli.Parse(argc, argv, first)) return 0;

    if (!cli.Given("--out")) throw UsageError("--out DIR is required (where the table and the plots go)");
    for (const char* option : {"--load", "--pressure-kpa", "--stroke-percent", "--stroke-mm", "--volume-ratio", "--isobaric-points"})
        cli.RefuseIfGiven(option, "is set by characterize at each point of its curves (give --pressures-kpa)");
    const std::vector<double> pressures = ParsePressures(pressuresText);
    sim::EvalJob base;
    if (cli.Given("--from")) {
        // The design and its model are the record's; the load is characterize's to set at each point
        // (a record may be a held stroke or a blocked test).
        base = ArchivedJob(cli, model, from, index, ModelUse::Weighed, [](sim::EvalJob& job) {
            if (!sim::ModelOf(job).physical) return;
            sim::LoadDef& load = job.Shell().load;
            load.kind = sim::ShellLoad::Inflate;
            load.forceN = 0;
            load.isobaricPoints = 0;
            load.strokePercent = load.strokeMm = 0;
        });
    } else {
        cli.RefuseIfGiven("--index", "goes with --from ARCHIVE");
        base = BuildJob(cli, shape, model, ModelUse::Weighed);
    }
    if (const CharacterizeRefusal refusal = CharacterizeJobError(base); !refusal.reason.empty())
        throw UsageError(refusal.Text(OptionName(refusal.key.c_str())));

    const fs::path folder = out;
    const std::vector<std::string> files{"characteristic.csv", "force_contraction.png", "force_pressure.png", "stroke_pressure.png",
                                         "evaluations.capnp", "evaluations.csv"};
    for (const auto& name : files)
        if (!overwrite && fs::exists(fs::symlink_status(folder / name)))
            throw UsageError(Quote(out) + " already holds " + name + " (an earlier characterize?); add --overwrite to replace its files, or give another --out");
    CreatedFolders folders;
    folders.Create(folder, "--out");
    for (const auto& name : files) {
        CheckOutputPath((folder / name).string(), "--out");
        RefuseOutputThatIsInput((folder / name).string(), "--out", {shape.meshFile, shape.offsets, from});
    }

    const CharacteristicCurves curves = Characterize(base, pressures, points, threads);
    const std::vector<std::vector<double>> ideal = IdealMuscleForces(base, curves);
    const sim::FibreDef& fibres = base.Shell().fibres;
    const std::string title = fmt::format("{}{}, {} model", ShapeTitle(base.shape),
                                          fibres.layout == sim::FibreLayout::None ? std::string()
                                          : fibres.layout == sim::FibreLayout::Braid || fibres.layout == sim::FibreLayout::Single
                                              ? fmt::format(", {} at {:g} deg", sim::Name(fibres.layout), fibres.angleDeg)
                                              : fmt::format(", {} fibres", sim::Name(fibres.layout)),
                                          sim::Name(base.model));
    OutputBatch batch;
    WriteFileAtomically((folder / "characteristic.csv").string(), CharacteristicTable(curves).Csv());
    const CharacteristicImages images =
        CharacteristicCurveImages(title, pressures, curves.contractionPercent, curves.forceN, ideal, curves.isometric, curves.free.back());
    WritePng((folder / "force_contraction.png").string(), images.forceContraction, 6);
    WritePng((folder / "force_pressure.png").string(), images.forcePressure, 6);
    WritePng((folder / "stroke_pressure.png").string(), images.strokePressure, 6);
    const std::vector<ArchiveRecord> records = CharacteristicRecords(base, curves);
    WriteFileAtomically((folder / "evaluations.capnp").string(), ArchiveBytes(records));
    WriteFileAtomically((folder / "evaluations.csv").string(), EvaluationTable(records).Csv());
    batch.Commit();

    Json summary = CharacteristicSummary(base, curves);
    summary["files"] = files;
    std::cout << summary.dump() << "\n";
    return 0;
}
static const RegisterCommand kCharacterizeCommand{{"characterize", "a muscle's force-contraction, force-pressure and stroke-pressure curves", 15, RunCharacterize}};

}  // namespace app
