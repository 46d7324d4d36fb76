#include "evaluation/characterize.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <fmt/format.h>

#include "formats/csv.h"
#include "formats/json_out.h"
#include "sim/batch.h"

namespace app {
namespace {

sim::EvalJob AtLoad(sim::EvalJob job, sim::ShellLoad kind, double pressureKpa) {
    job.Shell().load.kind = kind;
    job.Shell().load.pressureKpa = pressureKpa;
    return job;
}

}  // namespace

std::string PressuresError(const std::vector<double>& pressures) {
    if (pressures.empty() || pressures.size() > 20) return "give 1 to 20 pressures";
    for (double p : pressures)
        if (!std::isfinite(p) || p <= 0 || p > 1e6) return fmt::format("{} is not a pressure in kPa above 0", p);
    if (!std::is_sorted(pressures.begin(), pressures.end()) || std::adjacent_find(pressures.begin(), pressures.end()) != pressures.end())
        return "give the pressures in increasing order, each once";
    return "";
}

CharacterizeRefusal CharacterizeJobError(const sim::EvalJob& job) {
    if (!sim::ModelOf(job).physical)
        return {"model", sim::Name(job.model), "characterize needs the membrane or shell model (forces in newtons at equilibrium)"};
    const sim::LoadDef& load = job.Shell().load;
    if (load.kind != sim::ShellLoad::Inflate) return {"load", sim::Name(load.kind), "characterize sets the load at each point of its curves"};
    if (load.forceN != 0) return {"force_n", "", "the curves are of the muscle alone; the isobaric curve gives the force at each stroke"};
    if (load.isobaricPoints != 0) return {"isobaric_points", "", "characterize sets each isobaric curve's points (give its points)"};
    return {};
}

CharacteristicCurves Characterize(const sim::EvalJob& base, const std::vector<double>& pressuresKpa, int points, int threads) {
    CharacteristicCurves c;
    const size_t n = pressuresKpa.size();
    c.pressuresKpa = pressuresKpa;
    c.pointsPerCurve = points;
    c.free.resize(n);
    c.points.resize(n);
    // Each isobaric curve as a bench takes it: inflated freely (the free stroke; the highest
    // pressure's load steps are the free-stroke curve), then the top held at the free stroke's
    // fractions from the largest down to none, each held state from the last. Beside them the
    // isometric test at the highest pressure (its load steps are the isometric curve). One task
    // per thread; each result has its own place, so the threads change nothing.
    const bool bending = base.model == sim::ModelKind::Shell;  // the shell model is the membrane with bending
    const int n1 = static_cast<int>(n) + 1;
    // The longest tasks first (the highest pressures), so that no thread is left with one at the end.
    sim::ParallelFor(n1, threads, [&](int task) {
        const size_t k = task == 0 ? n - 1 : task == 1 ? n : n - static_cast<size_t>(task);  // the top pressure, the isometric test, then down
        if (k == n) {
            c.isometric = sim::Evaluate(AtLoad(base, sim::ShellLoad::Blocked, pressuresKpa.back()));
            return;
        }
        sim::EvalJob job = AtLoad(base, sim::ShellLoad::Inflate, pressuresKpa[k]);
        job.Shell().load.isobaricPoints = points;
        sim::IsobaricCurve curve = sim::IsobaricForces(job.shape, job.Shell(), bending);
        c.free[k] = std::move(curve.free);
        c.points[k] = std::move(curve.points);
        if (c.free[k].status == sim::Status::Ok)  // the free state closes the curve: no force
            c.points[k].push_back({c.free[k].contractionPercent, 0.0, c.free[k].shell.twistDeg, sim::Status::Ok});
    });

    c.contractionPercent.resize(n);
    c.forceN.resize(n);
    for (size_t k = 0; k < n; ++k) {
        c.contractionPercent[k] = c.free[k].shell.isobaricContractionPercent;
        c.forceN[k] = c.free[k].shell.isobaricForceN;
        c.workPerStrokeMj.push_back(c.free[k].shell.workPerStrokeMj);
    }
    const double density = base.Shell().material.densityKgPerM3;
    if (density > 0) c.siliconeMassG = sim::WallVolumeMm3(base.shape, base.Shell()) * density * 1e-6;  // kg/m^3 = 1e-6 g/mm^3
    return c;
}

// The summary a user reads: per pressure the free stroke, the force at no contraction and the work
// of one stroke (and per gram of silicone), the isometric force, the design and its model.
Json CharacteristicSummary(const sim::EvalJob& base, const CharacteristicCurves& c) {
    auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
    Json curves = Json::array();
    for (size_t k = 0; k < c.pressuresKpa.size(); ++k) {
        const sim::SimResult& free = c.free[k];
        curves.push_back({{"pressure_kpa", c.pressuresKpa[k]},
                          {"status", sim::Name(free.status)},
                          {"free_stroke_percent", free.status == sim::Status::Ok ? Json(free.contractionPercent) : Json(nullptr)},
                          {"force_at_no_contraction_n", c.forceN[k].empty() ? Json(nullptr) : number(c.forceN[k][0])},
                          {"work_per_stroke_mj", number(c.workPerStrokeMj[k])},
                          {"work_per_gram_mj_per_g", number(c.workPerStrokeMj[k] / c.siliconeMassG)}});
    }
    Json summary;
    summary["isobaric"] = curves;
    summary["isometric_force_n"] = c.isometric.status == sim::Status::Ok ? Json(c.isometric.shell.blockingForceN) : Json(nullptr);
    summary["silicone_mass_g"] = number(c.siliconeMassG);
    summary["shape"] = ShapeJson(base.shape);
    summary["model"] = ModelJson(base);
    return summary;
}

std::vector<ArchiveRecord> CharacteristicRecords(const sim::EvalJob& base, const CharacteristicCurves& c) {
    std::vector<ArchiveRecord> records;
    auto add = [&](sim::EvalJob job, const sim::SimResult& result, std::string label) {
        records.push_back({records.size(), "characterize", 0, -1, Role::Characteristic, std::move(label), std::move(job), result});
    };
    for (size_t k = 0; k < c.pressuresKpa.size(); ++k) {
        const double p = c.pressuresKpa[k];
        sim::EvalJob free = AtLoad(base, sim::ShellLoad::Inflate, p);
        free.Shell().load.isobaricPoints = c.pointsPerCurve;  // replays with its curve
        add(std::move(free), c.free[k], fmt::format("free inflation at {:g} kPa with its isobaric curve", p));
        for (const sim::IsobaricPoint& point : c.points[k]) {
            if (point.state.initial.Size() == 0) continue;  // the free state that closes the curve: archived above
            sim::EvalJob held = AtLoad(base, sim::ShellLoad::Blocked, p);
            held.Shell().load.strokePercent = point.strokePercent;
            add(std::move(held), point.state, fmt::format("held at {:.4g} % contraction at {:g} kPa", point.strokePercent, p));
        }
    }
    add(AtLoad(base, sim::ShellLoad::Blocked, c.pressuresKpa.back()), c.isometric,
        fmt::format("isometric (the top held at its rest place) to {:g} kPa", c.pressuresKpa.back()));
    return records;
}

Table CharacteristicTable(const CharacteristicCurves& c) {
    Table table(std::vector<std::string>{"curve", "pressure_kpa", "contraction_percent", "force_n", "twist_deg", "status"});
    for (size_t k = 0; k < c.pressuresKpa.size(); ++k) {
        const std::string pressure = CsvNumber(c.pressuresKpa[k]);
        for (const sim::IsobaricPoint& point : c.points[k]) {
            const bool ok = point.status == sim::Status::Ok;
            table.AddRow({"isobaric", pressure, CsvNumber(point.strokePercent), ok ? CsvNumber(point.forceN) : "", ok ? CsvNumber(point.twistDeg) : "",
                          sim::Name(point.status)});
        }
        if (c.free[k].status != sim::Status::Ok) table.AddRow({"isobaric", pressure, "", "", "", sim::Name(c.free[k].status)});
    }
    const sim::ShellOutputs& iso = c.isometric.shell;
    for (size_t s = 0; s < iso.curvePressureKpa.size() && s < iso.curveForceN.size(); ++s)
        table.AddRow({"isometric", CsvNumber(iso.curvePressureKpa[s]), "0", CsvNumber(iso.curveForceN[s]), CsvNumber(iso.curveTwistDeg[s]), "ok"});
    if (c.isometric.status != sim::Status::Ok) table.AddRow({"isometric", CsvNumber(c.pressuresKpa.back()), "0", "", "", sim::Name(c.isometric.status)});
    const sim::SimResult& top = c.free.back();
    for (size_t s = 0; s < top.shell.curvePressureKpa.size(); ++s)
        table.AddRow({"free_stroke", CsvNumber(top.shell.curvePressureKpa[s]), CsvNumber(top.shell.curveContractionPercent[s]), "0",
                      CsvNumber(top.shell.curveTwistDeg[s]), "ok"});
    if (top.status != sim::Status::Ok) table.AddRow({"free_stroke", CsvNumber(c.pressuresKpa.back()), "", "0", "", sim::Name(top.status)});
    return table;
}

std::vector<std::vector<double>> IdealMuscleForces(const sim::EvalJob& base, const CharacteristicCurves& c) {
    const sim::FibreDef& fibres = base.Shell().fibres;
    std::vector<std::vector<double>> ideal;
    if (!std::holds_alternative<sim::CylinderShape>(base.shape) || fibres.layout != sim::FibreLayout::Braid || !fibres.plus || !fibres.minus ||
        !fibres.bands.empty() || !fibres.sectorAnglesDeg.empty() || fibres.angleDeg == 0)
        return ideal;
    const double r0 = base.Shell().geometry.radiusMm, a = fibres.angleDeg * std::numbers::pi / 180;
    for (size_t k = 0; k < c.pressuresKpa.size(); ++k) {
        ideal.emplace_back();
        for (double contraction : c.contractionPercent[k]) {
            const double eps = contraction / 100;
            ideal.back().push_back(std::numbers::pi * r0 * r0 * c.pressuresKpa[k] * 1e-3 *
                                   (3 * (1 - eps) * (1 - eps) / std::pow(std::tan(a), 2) - 1 / std::pow(std::sin(a), 2)));
        }
    }
    return ideal;
}

}  // namespace app
