// The optimizers' plain parts: objectives, fixed-length genomes, the parameter table, checks and
// Pareto dominance. The pagmo loop is in optimize_pagmo.cpp.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "sim/module_loader.h"
#include "sim/optimize.h"
#include "sim/optimizer_module.h"

#include "algorithms.h"

namespace sim {

bool IsMultiObjective(Algorithm algorithm) { return AlgorithmRowOf(algorithm).multiObjective; }

// [SECTION] Objectives ----------------------------------------------------------------------------

bool MaximisedByDefault(ObjectiveKind kind) {
    return kind != ObjectiveKind::MaxStretch && kind != ObjectiveKind::VolumeChange && kind != ObjectiveKind::Twist;
}

std::string ObjectiveError(ObjectiveKind kind, ModelKind model) {
    const bool thesis = model == ModelKind::Thesis;
    if ((kind == ObjectiveKind::ThesisFitness || kind == ObjectiveKind::StretchFitness) && !thesis)
        return fmt::format("objective {} is the thesis model's; the {} model gives contraction, blocking_force, axial_stiffness, "
                           "max_stretch, volume_change, limit_margin, twist, force_at_stroke, work_per_gram and force_per_gram",
                           Name(kind), Name(model));
    if (thesis && kind != ObjectiveKind::Contraction && kind != ObjectiveKind::ThesisFitness && kind != ObjectiveKind::StretchFitness)
        return fmt::format("objective {} needs units and equilibrium: the thesis model gives only thesis_fitness, stretch_fitness and contraction (use the "
                           "membrane or shell model)",
                           Name(kind));
    return "";
}

std::string ObjectiveDefError(ObjectiveKind kind, const ModelDef& def) {
    const auto* shell = std::get_if<ShellDef>(&def);
    if (!shell) return "";
    if (kind == ObjectiveKind::ForceAtStroke && shell->load.kind != ShellLoad::Blocked)
        return fmt::format("objective force_at_stroke is the force with the top held at the load's stroke_percent: give the load kind blocked (now {})",
                           Name(shell->load.kind));
    if (kind == ObjectiveKind::Twist && shell->ends.twist == TwistEnd::Held) return "objective twist needs a top that may turn: the ends' twist is held";
    if (kind == ObjectiveKind::WorkPerGram) {
        if (shell->load.kind != ShellLoad::Inflate || shell->load.isobaricPoints < 2)
            return fmt::format("objective work_per_gram is the isobaric curve's area per gram: give the load kind inflate (now {}) with isobaric_points "
                               "(2 to 100; 6 as characterize draws it, now {})",
                               Name(shell->load.kind), shell->load.isobaricPoints);
        if (!(shell->material.densityKgPerM3 > 0)) return "objective work_per_gram needs the material's density_kg_per_m3 (the silicone's mass)";
    }
    if (kind == ObjectiveKind::ForcePerGram && !(shell->material.densityKgPerM3 > 0))
        return "objective force_per_gram needs the material's density_kg_per_m3 (the silicone's mass)";
    return "";
}

SecondEvaluation SecondEvaluationOf(const std::vector<Objective>& objectives) {
    for (const Objective& o : objectives) {
        if (o.kind == ObjectiveKind::StretchFitness) return SecondEvaluation::StretchTest;
        if (o.kind == ObjectiveKind::LimitMargin) return SecondEvaluation::TwiceThePressure;
    }
    return SecondEvaluation::None;
}

double ObjectiveValue(ObjectiveKind kind, const SimResult& r, const SimResult* second) {
    if (r.status != Status::Ok) return NAN;
    if (kind == ObjectiveKind::StretchFitness) return second && second->status == Status::Ok ? second->fitness : NAN;
    if (kind == ObjectiveKind::LimitMargin) {
        // The pressure maximum met on the way to twice the target; none met: a margin of 1 (or more).
        if (!second) return NAN;
        const double target = r.shell.targetPressureKpa;
        if (std::isfinite(second->shell.limitPressureKpa) && target > 0) return std::min(1.0, second->shell.limitPressureKpa / target - 1.0);
        return second->status == Status::Ok ? 1.0 : NAN;
    }
    const ShellOutputs& s = r.shell;
    switch (kind) {
        case ObjectiveKind::Contraction: return r.contractionPercent;
        case ObjectiveKind::ThesisFitness: return r.fitness;
        case ObjectiveKind::StretchFitness:
        case ObjectiveKind::LimitMargin: return NAN;
        case ObjectiveKind::BlockingForce: return s.blockingForceN;
        case ObjectiveKind::AxialStiffness: return s.axialStiffnessNPerMm;
        case ObjectiveKind::MaxStretch: return s.maxStretch;
        case ObjectiveKind::VolumeChange: return 100.0 * (s.volumeMm3 / s.restVolumeMm3 - 1.0);
        case ObjectiveKind::Twist: return std::fabs(s.twistDeg);
        case ObjectiveKind::ForceAtStroke: return s.strokeForceN;
        case ObjectiveKind::WorkPerGram: return s.workPerGramMjPerG;
        case ObjectiveKind::ForcePerGram: return s.siliconeG > 0 ? s.blockingForceN / s.siliconeG : NAN;
    }
    return NAN;
}

const char* ObjectiveUnit(ObjectiveKind kind) {
    switch (kind) {
        case ObjectiveKind::Contraction: return "contraction, %";
        case ObjectiveKind::ThesisFitness: return "thesis fitness, mesh units";
        case ObjectiveKind::StretchFitness: return "stretch test fitness, mesh units";
        case ObjectiveKind::LimitMargin: return "limit pressure margin, fraction of the target";
        case ObjectiveKind::BlockingForce: return "blocking force, N";
        case ObjectiveKind::AxialStiffness: return "axial stiffness, N/mm";
        case ObjectiveKind::MaxStretch: return "largest stretch";
        case ObjectiveKind::VolumeChange: return "volume change, %";
        case ObjectiveKind::Twist: return "twist magnitude, deg";
        case ObjectiveKind::ForceAtStroke: return "force at the held stroke, N";
        case ObjectiveKind::WorkPerGram: return "work per stroke per gram, mJ/g";
        case ObjectiveKind::ForcePerGram: return "blocking force per gram, N/g";
    }
    return "?";
}

std::vector<double> MinimisedForm(const OptimizerDef& def, const DesignScore& score) {
    std::vector<double> f(def.objectives.size(), kFailedPenalty);
    if (score.status != Status::Ok) return f;
    for (size_t k = 0; k < f.size(); ++k) {
        const double v = k < score.values.size() ? score.values[k] : NAN;
        // A valid design without this output (a blocked solve that failed) counts as failed here.
        if (std::isfinite(v)) f[k] = def.objectives[k].maximise ? -v : v;
    }
    return f;
}

std::vector<size_t> NonDominated(const std::vector<std::vector<double>>& points) {
    auto dominates = [](const std::vector<double>& a, const std::vector<double>& b) {
        bool better = false;
        for (size_t k = 0; k < a.size(); ++k) {
            if (a[k] > b[k]) return false;
            if (a[k] < b[k]) better = true;
        }
        return better;
    };
    std::vector<size_t> front;
    for (size_t i = 0; i < points.size(); ++i) {
        bool dominated = false;
        for (size_t j = 0; j < points.size() && !dominated; ++j) dominated = j != i && dominates(points[j], points[i]);
        // Of equal points, the first stands for them all.
        for (size_t j = 0; j < i && !dominated; ++j) dominated = points[j] == points[i];
        if (!dominated) front.push_back(i);
    }
    return front;
}

// [SECTION] Genomes -------------------------------------------------------------------------------

namespace {

int FibreGeneCount(const GenomeDef& g) { return g.fibreAngles + (g.fibreSwitches ? 2 : 0); }

bool IsSine(VectorFamily f) { return f == VectorFamily::Sine || f == VectorFamily::AbsSine; }

}  // namespace

std::pair<std::vector<double>, std::vector<double>> VectorBounds(const VectorGenomeDef& def, const MeshDef& mesh) {
    std::vector<double> lo, hi;
    auto add = [&](double a, double b, int times) {
        for (int k = 0; k < times; ++k) {
            lo.push_back(a);
            hi.push_back(b);
        }
    };
    const GenomeDef& g = def.genes;
    if (IsSine(def.family)) {
        for (const auto& range : {def.amplitude, def.phaseStart, def.phaseEnd})
            if (range[0] != range[1]) add(range[0], range[1], 1);
    } else if (def.family == VectorFamily::BSpline) {
        // Each grid point gets an equal share of the real line: [min - step/2, max + step/2) rounds onto it.
        add(g.controlMin - 0.5 * g.controlStep, g.controlMax + 0.5 * g.controlStep, g.splines * def.controlPoints);
    } else {
        add(-g.bound, g.bound, 2 * VertexCount(mesh));
    }
    add(g.fibreAngleMin, g.fibreAngleMax, g.fibreAngles);
    add(0, 1, g.fibreSwitches ? 2 : 0);
    return {lo, hi};
}

std::vector<std::string> VectorGeneNames(const VectorGenomeDef& def, const MeshDef& mesh) {
    std::vector<std::string> names;
    const GenomeDef& g = def.genes;
    if (IsSine(def.family)) {
        const char* labels[] = {"amplitude", "phase_start", "phase_end"};
        const std::array<double, 2> ranges[] = {def.amplitude, def.phaseStart, def.phaseEnd};
        for (int k = 0; k < 3; ++k)
            if (ranges[k][0] != ranges[k][1]) names.push_back(labels[k]);
    } else if (def.family == VectorFamily::BSpline) {
        for (int s = 0; s < g.splines; ++s)
            for (int c = 0; c < def.controlPoints; ++c) names.push_back(fmt::format("spline{}.c{}", s + 1, c + 1));
    } else {
        for (int v = 0; v < VertexCount(mesh); ++v) {
            names.push_back(fmt::format("dx{}", v));
            names.push_back(fmt::format("dy{}", v));
        }
    }
    for (int k = 0; k < g.fibreAngles; ++k) names.push_back(g.fibreAngles == 1 ? std::string("fibre_angle_deg") : fmt::format("fibre_angle_deg{}", k + 1));
    if (g.fibreSwitches) {
        names.push_back("fibre_plus_on");
        names.push_back("fibre_minus_on");
    }
    return names;
}

VectorDesign DesignOfVector(const VectorGenomeDef& def, const std::vector<double>& x, const MeshDef& mesh) {
    const GenomeDef& g = def.genes;
    const auto [lo, hi] = VectorBounds(def, mesh);
    // pagmo keeps vectors inside their bounds; clamping here keeps a hand-made one in them too.
    auto gene = [&](size_t k) { return std::clamp(k < x.size() ? x[k] : lo[k], lo[k], hi[k]); };
    VectorDesign d;
    size_t k = 0;
    if (IsSine(def.family)) {
        double values[3];
        const std::array<double, 2> ranges[] = {def.amplitude, def.phaseStart, def.phaseEnd};
        for (int p = 0; p < 3; ++p) values[p] = ranges[p][0] == ranges[p][1] ? ranges[p][0] : gene(k++);
        if (def.family == VectorFamily::Sine) d.shape = SineShape{values[0], values[1], values[2]};
        else d.shape = AbsSineShape{values[0], values[1], values[2]};
    } else if (def.family == VectorFamily::BSpline) {
        // Control points lie on the genome's grid (the thesis's: integers): the one place a real gene
        // is rounded (to the nearest grid point, half up, the top of the range onto the last).
        BSplineShape b;
        b.region = g.region;
        for (int s = 0; s < g.splines; ++s) {
            std::vector<double> control;
            for (int c = 0; c < def.controlPoints; ++c)
                control.push_back(g.ControlValue(std::clamp<long long>(std::llround(std::floor((gene(k++) - g.controlMin) / g.controlStep + 0.5)), 0, g.ControlLevels())));
            b.splines.push_back(control);
        }
        d.genome = b.splines;
        d.shape = std::move(b);
    } else {
        FreeXYShape f;
        const size_t n = static_cast<size_t>(VertexCount(mesh));
        std::vector<double> offsets;
        for (size_t v = 0; v < n; ++v) {
            f.dx.push_back(gene(k++));
            f.dy.push_back(gene(k++));
            offsets.push_back(f.dx.back());
            offsets.push_back(f.dy.back());
        }
        d.genome.push_back(offsets);
        d.shape = std::move(f);
    }
    if (FibreGeneCount(g) > 0) {
        std::vector<double> fibres;
        for (int a = 0; a < g.fibreAngles; ++a) fibres.push_back(gene(k++));
        for (int s = 0; g.fibreSwitches && s < 2; ++s) fibres.push_back(gene(k++) >= 0.5 ? 1.0 : 0.0);
        d.genome.push_back(fibres);
    }
    return d;
}

// [SECTION] Parameters and checks -----------------------------------------------------------------

const std::vector<AlgorithmParameter>& AlgorithmParameters() {
    // Every row's parameters, in the table's order (algorithms.cpp).
    static const std::vector<AlgorithmParameter> table = [] {
        std::vector<AlgorithmParameter> all;
        for (const AlgorithmRow& row : AlgorithmRows())
            for (const AlgorithmParameterRow& p : row.parameters) all.push_back({row.id, p.name, p.defaultValue, p.min, p.max, p.integer, p.meaning});
        return all;
    }();
    return table;
}

double ParameterValue(const OptimizerDef& def, const char* name) {
    if (auto given = def.parameters.find(name); given != def.parameters.end()) return given->second;
    for (const AlgorithmParameter& p : AlgorithmParameters())
        if (p.algorithm == def.algorithm && std::string(p.name) == name) return p.defaultValue;
    return NAN;
}

namespace {
// The algorithms that optimise several objectives (or one), named as experiment files name them.
std::string AlgorithmsFor(bool multiObjective) {
    std::vector<std::string> names;
    for (const AlgorithmRow& row : AlgorithmRows())
        if (row.multiObjective == multiObjective) names.push_back(Name(row.id));
    return ListText(names);
}
}  // namespace

std::string OptimizerDefError(const OptimizerDef& def, ModelKind model, const MeshDef& mesh) {
    const char* name = Name(def.algorithm);
    const int smallest = AlgorithmRowOf(def.algorithm).smallestPopulation;
    if (def.population < smallest || def.population > 100000)
        return fmt::format("{} needs a population of at least {} (got {})", name, smallest, def.population);
    for (const auto& [key, value] : def.parameters) {
        const AlgorithmParameter* found = nullptr;
        std::string valid;
        for (const AlgorithmParameter& p : AlgorithmParameters()) {
            if (p.algorithm != def.algorithm) continue;
            valid += (valid.empty() ? "" : ", ") + std::string(p.name);
            if (key == p.name) found = &p;
        }
        if (!found) return fmt::format("{} has no parameter '{}' (valid: {})", name, key, valid);
        if (!(value >= found->min && value <= found->max) || (found->integer && value != std::floor(value)))
            return fmt::format("{} parameter '{}' must be {} in [{:g}, {:g}] (got {:g})", name, key, found->integer ? "an integer" : "a number",
                               found->min, found->max, value);
    }
    if (const auto rule = AlgorithmRowOf(def.algorithm).error) {
        const std::string error = rule(def);
        if (!error.empty()) return error;
    }
    if (def.objectives.empty()) return "at least one objective is needed";
    const bool multi = IsMultiObjective(def.algorithm);
    if (multi && def.objectives.size() < 2)
        return fmt::format("{} optimises several objectives: give two or more (one objective: {})", name, AlgorithmsFor(false));
    if (!multi && def.objectives.size() != 1)
        return fmt::format("{} optimises one objective (got {}); for several use {}", name, def.objectives.size(), AlgorithmsFor(true));
    for (size_t i = 0; i < def.objectives.size(); ++i) {
        if (std::string e = ObjectiveError(def.objectives[i].kind, model); !e.empty()) return e;
        for (size_t j = 0; j < i; ++j)
            if (def.objectives[j].kind == def.objectives[i].kind) return fmt::format("objective {} is given twice", Name(def.objectives[i].kind));
    }
    const VectorGenomeDef& v = def.genome;
    const GenomeDef& g = v.genes;
    if (IsSine(v.family)) {
        if (!(v.amplitude[0] <= v.amplitude[1]) || !(v.phaseStart[0] <= v.phaseStart[1]) || !(v.phaseEnd[0] <= v.phaseEnd[1]))
            return "a sine gene's bounds are reversed (give the low end first)";
        for (const auto& r : {v.amplitude, v.phaseStart, v.phaseEnd})
            if (!std::isfinite(r[0]) || !std::isfinite(r[1])) return "a sine gene's bounds must be finite";
    } else if (v.family == VectorFamily::BSpline) {
        if (g.splines != 1 && g.splines != 2 && g.splines != 4) return "splines must be 1, 2 or 4";
        if (std::string e = ControlGridError(g); !e.empty()) return e;
        if (v.controlPoints < 4 || v.controlPoints > 64) return "a spline needs 4 to 64 control points";
        if (g.splines > mesh.resolution) return "more splines than vertices per turn";
    } else if (!(g.bound > 0) || !std::isfinite(g.bound)) {
        return "free-xy bound must be > 0";
    }
    if (g.fibreAngles < 0 || g.fibreAngles > 64) return "fibre angle genes must number 0 to 64";
    if (!(g.fibreAngleMin >= -90 && g.fibreAngleMax <= 90 && g.fibreAngleMin <= g.fibreAngleMax))
        return "the fibre angle range must lie within -90 to 90 degrees, low end first";
    if (g.fibreAngles > 0 && g.fibreAngleMin == g.fibreAngleMax)
        return "the fibre angle range is a single value: a gene needs a range (to fix the angle, give no fibre_angles and the model's fibre_angle_deg)";
    if (g.HasFibreGenes() && model == ModelKind::Thesis) return "fibre genes need the membrane or shell model";
    if (VectorBounds(v, mesh).first.empty()) return "the genome has no gene: every bound is fixed";
    const StopDef& s = def.stop;
    if (def.generations < 0 || s.evaluations < 0 || !(s.seconds >= 0) || s.stagnation < 0) return "stop criteria must not be negative";
    if (std::isfinite(s.target) && multi) return "a target stops one objective's run; with several objectives use stagnation";
    return "";
}

OptimizerRun RunOptimizer(const OptimizerDef& def, const MeshDef& mesh, std::uint64_t seed, const VectorEvaluator& evaluate,
                          const GenerationHook& onGeneration) {
    // Loaded once, on the first run (thread-safe static initialisation); it stays mapped.
    static const std::pair<const OptimizerModuleApi*, std::string> module = [] {
        std::string error;
        using Entry = const OptimizerModuleApi* (*)();
        const auto entry = reinterpret_cast<Entry>(OpenModuleEntry("libactuator_optimizer.so", "actuator_optimizer_module", "optimizer", &error));
        const OptimizerModuleApi* api = entry ? entry() : nullptr;
        if (entry && (!api || api->abiVersion != kOptimizerModuleAbiVersion)) {
            api = nullptr;
            error = "the optimizer module is not of this build (rebuild and reinstall)";
        }
        return std::make_pair(api, error);
    }();
    if (!module.first) throw std::runtime_error(module.second);
    return module.first->runOptimizer(def, mesh, seed, evaluate, onGeneration);
}

}  // namespace sim
