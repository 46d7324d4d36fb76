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
#include <atomic>
#include <iostream>
#include <thread>
#include <numbers>

#include "commands/registry.h"
#include "evaluation/evaluator.h"
#include "formats/csv.h"
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
        if (item.empty() || error != std::errc() || rest != item.data() + item.size() || !std::isfinite(value) || value <= 0 || value > 1e6)
            throw UsageError("--pressures-kpa: " + Quote(item) + " is not a pressure in kPa above 0 (give a list such as 5,10,20)");
        pressures.push_back(value);
        start = end + 1;
    }
    if (pressures.size() > 20) throw UsageError("--pressures-kpa: at most 20 pressures");
    if (!std::is_sorted(pressures.begin(), pressures.end()) || std::adjacent_find(pressures.begin(), pressures.end()) != pressures.end())
        throw UsageError("--pressures-kpa: give the pressures in increasing order, each once");
    return pressures;
}

sim::EvalJob AtLoad(sim::EvalJob job, sim::ShellLoad kind, double pressureKpa) {
    job.Shell().load.kind = kind;
    job.Shell().load.pressureKpa = pressureKpa;
    return job;
}

}  // namespace

static int RunCharacterize(int argc, char** argv, int first) {
    Cli cli("characterize",
            "A muscle's characteristic curves under --model membrane or shell: at each pressure the force it pulls with against its "
            "contraction, from none to its free stroke (the isobaric test: the top held at each contraction); the force with the top held at "
            "its rest place against pressure (isometric); and the free stroke against pressure. The top may turn as the design's --twist "
            "says (free by default, as on a bench). Writes DIR/characteristic.csv, DIR/force_contraction.png, DIR/force_pressure.png and "
            "DIR/stroke_pressure.png, and prints a JSON summary. Forces in N (positive = the muscle pulls on its supports), contraction in "
            "percent of the length (positive = shorter), pressures in kPa.");
    ShapeOptions shape;
    ModelOptions model;
    std::string pressuresText = "5,10,20", out;
    int points = 6, threads = 0;
    AddShapeOptions(cli, shape);
    AddModelOptions(cli, model);
    cli.Group("Curves");
    cli.Text("--pressures-kpa", pressuresText, "the isobaric curves' pressures, increasing; the highest is the isometric and free-stroke curves' end")
        ->type_name("LIST");
    cli.Integer("--points", points, "points of each isobaric curve, from no contraction to the free stroke", 2, 100);
    cli.Integer("--threads", threads, "evaluation threads (0: every core); results do not depend on it", 0, 1024)->default_str("0 (every core)");
    cli.Text("--out", out, "folder for the table and the plots (created if missing); required")->type_name("DIR");
    cli.Examples(
        "  actuator characterize --shape cylinder --fibres braid --fibre-angle-deg 30 --out curves/braid\n"
        "  actuator characterize --shape sine --amplitude 1.3 --fibres single --fibre-angle-deg 40 --twist held --pressures-kpa 2,4 --out curves/held\n");
    if (!cli.Parse(argc, argv, first)) return 0;

    if (!cli.Given("--out")) throw UsageError("--out DIR is required (where the table and the plots go)");
    for (const char* option : {"--load", "--pressure-kpa", "--stroke-percent", "--volume-ratio"})
        cli.RefuseIfGiven(option, "is set by characterize at each point of its curves (give --pressures-kpa)");
    const std::vector<double> pressures = ParsePressures(pressuresText);
    const sim::EvalJob base = BuildJob(cli, shape, model, ModelUse::Simulate);
    if (!sim::ModelOf(base).physical)
        throw UsageError(std::string("--model ") + sim::Name(base.model) + ": characterize needs --model membrane or shell (forces in newtons at equilibrium)");
    if (base.Shell().load.forceN != 0) throw UsageError("--force-n: the curves are of the muscle alone; the isobaric curve gives the force at each stroke");

    const fs::path folder = out;
    const std::vector<std::string> files{"characteristic.csv", "force_contraction.png", "force_pressure.png", "stroke_pressure.png"};
    CreatedFolders folders;
    folders.Create(folder, "--out");
    for (const auto& name : files) {
        CheckOutputPath((folder / name).string(), "--out");
        RefuseOutputThatIsInput((folder / name).string(), "--out", {shape.meshFile, shape.offsets});
    }

    // First the free stroke at each pressure (the highest one's load steps are the free-stroke
    // curve) and the isometric test at the highest pressure (its load steps are the isometric curve).
    auto evaluator = MakeLocalEvaluator(threads);
    std::vector<sim::EvalJob> firstJobs;
    for (double p : pressures) firstJobs.push_back(AtLoad(base, sim::ShellLoad::Inflate, p));
    firstJobs.push_back(AtLoad(base, sim::ShellLoad::Blocked, pressures.back()));
    const std::vector<sim::SimResult> firstResults = evaluator->EvaluateAll(firstJobs);
    const sim::SimResult& isometric = firstResults.back();
    const sim::SimResult& freeAtTop = firstResults[pressures.size() - 1];

    // Then each isobaric curve as a bench takes it: inflated freely, then the top held at the free
    // stroke's fractions from the largest down to none, each held state from the last. The free
    // state closes the curve (where the muscle pulls with nothing). One pressure per thread.
    std::vector<double> fractions;
    for (int i = 0; i + 1 < points; ++i) fractions.push_back(double(i) / (points - 1));
    const bool bending = base.model == sim::ModelKind::Shell;  // the shell model is the membrane with bending
    std::vector<std::vector<sim::IsobaricPoint>> isobaric(pressures.size());
    {
        std::atomic<size_t> next{0};
        auto work = [&] {
            for (size_t k = next++; k < pressures.size(); k = next++) {
                const sim::EvalJob job = AtLoad(base, sim::ShellLoad::Inflate, pressures[k]);
                isobaric[k] = sim::IsobaricForces(job.shape, job.Shell(), bending, fractions, firstResults[k]);
            }
        };
        const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
        const unsigned count = std::min<unsigned>(static_cast<unsigned>(pressures.size()), threads > 0 ? static_cast<unsigned>(threads) : hardware);
        std::vector<std::thread> pool;
        for (unsigned w = 1; w < count; ++w) pool.emplace_back(work);
        work();
        for (auto& thread : pool) thread.join();
    }

    Table table(std::vector<std::string>{"curve", "pressure_kpa", "contraction_percent", "force_n", "twist_deg", "status"});
    std::vector<std::vector<double>> curveContraction(pressures.size()), curveForce(pressures.size());
    for (size_t k = 0; k < pressures.size(); ++k) {
        const sim::SimResult& free = firstResults[k];
        for (const sim::IsobaricPoint& point : isobaric[k]) {
            const bool ok = point.status == sim::Status::Ok;
            table.AddRow({"isobaric", CsvNumber(pressures[k]), CsvNumber(point.strokePercent), ok ? CsvNumber(point.forceN) : "",
                          ok ? CsvNumber(point.twistDeg) : "", sim::Name(point.status)});
            curveContraction[k].push_back(point.strokePercent);
            curveForce[k].push_back(ok ? point.forceN : NAN);
        }
        if (free.status == sim::Status::Ok) {  // the free state closes the curve
            table.AddRow({"isobaric", CsvNumber(pressures[k]), CsvNumber(free.contractionPercent), "0", CsvNumber(free.shell.twistDeg), "ok"});
            curveContraction[k].push_back(free.contractionPercent);
            curveForce[k].push_back(0);
        } else {
            table.AddRow({"isobaric", CsvNumber(pressures[k]), "", "", "", sim::Name(free.status)});
        }
    }
    const sim::ShellOutputs& iso = isometric.shell;
    for (size_t s = 0; s < iso.curvePressureKpa.size() && s < iso.curveForceN.size(); ++s)
        table.AddRow({"isometric", CsvNumber(iso.curvePressureKpa[s]), "0", CsvNumber(iso.curveForceN[s]), CsvNumber(iso.curveTwistDeg[s]), "ok"});
    if (isometric.status != sim::Status::Ok)
        table.AddRow({"isometric", CsvNumber(pressures.back()), "0", "", "", sim::Name(isometric.status)});
    const sim::ShellOutputs& freeCurve = freeAtTop.shell;
    for (size_t s = 0; s < freeCurve.curvePressureKpa.size(); ++s)
        table.AddRow({"free_stroke", CsvNumber(freeCurve.curvePressureKpa[s]), CsvNumber(freeCurve.curveContractionPercent[s]), "0",
                      CsvNumber(freeCurve.curveTwistDeg[s]), "ok"});
    if (freeAtTop.status != sim::Status::Ok) table.AddRow({"free_stroke", CsvNumber(pressures.back()), "", "0", "", sim::Name(freeAtTop.status)});

    const sim::FibreDef& fibres = base.Shell().fibres;
    // A braided cylinder is an ideal muscle's real counterpart: its force beside Tondu and Lopez's,
    // F = pi r0^2 p (3 (1 - eps)^2 / tan^2 a0 - 1 / sin^2 a0).
    std::vector<std::vector<double>> ideal;
    if (std::holds_alternative<sim::CylinderShape>(base.shape) && fibres.layout == sim::FibreLayout::Braid && fibres.plus && fibres.minus &&
        fibres.bands.empty() && fibres.sectorAnglesDeg.empty() && fibres.angleDeg != 0) {
        const double r0 = base.Shell().geometry.radiusMm, a = fibres.angleDeg * std::numbers::pi / 180;
        for (size_t k = 0; k < pressures.size(); ++k) {
            ideal.emplace_back();
            for (double c : curveContraction[k]) {
                const double eps = c / 100;
                ideal.back().push_back(std::numbers::pi * r0 * r0 * pressures[k] * 1e-3 *
                                       (3 * (1 - eps) * (1 - eps) / std::pow(std::tan(a), 2) - 1 / std::pow(std::sin(a), 2)));
            }
        }
    }
    const std::string title = fmt::format("{}{}, {} model", ShapeTitle(base.shape),
                                          fibres.layout == sim::FibreLayout::None ? std::string()
                                          : fibres.layout == sim::FibreLayout::Braid || fibres.layout == sim::FibreLayout::Single
                                              ? fmt::format(", {} at {:g} deg", sim::Name(fibres.layout), fibres.angleDeg)
                                              : fmt::format(", {} fibres", sim::Name(fibres.layout)),
                                          sim::Name(base.model));
    OutputBatch batch;
    WriteFileAtomically((folder / "characteristic.csv").string(), table.Csv());
    const CharacteristicImages images = CharacteristicCurveImages(title, pressures, curveContraction, curveForce, ideal, isometric, freeAtTop);
    WritePng((folder / "force_contraction.png").string(), images.forceContraction, 6);
    WritePng((folder / "force_pressure.png").string(), images.forcePressure, 6);
    WritePng((folder / "stroke_pressure.png").string(), images.strokePressure, 6);
    batch.Commit();

    Json summary;
    Json curves = Json::array();
    for (size_t k = 0; k < pressures.size(); ++k) {
        const sim::SimResult& free = firstResults[k];
        // The work of one stroke at this pressure: the force integrated over the top's travel from
        // rest to the free stroke (trapezoids over the curve's points), N mm = mJ.
        double work = 0;
        for (size_t i = 1; i < curveContraction[k].size(); ++i)
            work += 0.5 * (curveForce[k][i] + curveForce[k][i - 1]) * (curveContraction[k][i] - curveContraction[k][i - 1]) / 100 *
                    base.Shell().geometry.lengthMm;
        curves.push_back({{"pressure_kpa", pressures[k]},
                          {"status", sim::Name(free.status)},
                          {"free_stroke_percent", free.status == sim::Status::Ok ? Json(free.contractionPercent) : Json(nullptr)},
                          {"force_at_no_contraction_n", curveForce[k].empty() || !std::isfinite(curveForce[k][0]) ? Json(nullptr) : Json(curveForce[k][0])},
                          {"work_per_stroke_mj", std::isfinite(work) && curveContraction[k].size() > 1 ? Json(work) : Json(nullptr)}});
    }
    summary["isobaric"] = curves;
    summary["isometric_force_n"] = isometric.status == sim::Status::Ok ? Json(iso.blockingForceN) : Json(nullptr);
    summary["files"] = files;
    summary["shape"] = ShapeJson(base.shape);
    summary["model"] = ModelJson(base);
    std::cout << summary.dump() << "\n";
    return 0;
}

static const RegisterCommand kCharacterizeCommand{{"characterize", "a muscle's force-contraction, force-pressure and stroke-pressure curves", 15, RunCharacterize}};

}  // namespace app
