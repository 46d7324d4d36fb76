// The model table: one row per model. A new model is a row here (and its folder, def and outputs).
#include "sim/model.h"

#include "sim/names.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sim {
namespace {

// [SECTION] thesis: the 2019 mass-spring model (docs/models/thesis.md)

SimResult ThesisEvaluate(const EvalJob& job) { return Evaluate(job.shape, job.Thesis().mesh, job.Thesis().params); }

std::string ThesisError(const EvalJob& job) {
    if (std::string error = SimParamsError(job.Thesis().params); !error.empty()) return error;
    return ShapeError(job.shape, job.Thesis().mesh);
}

Surface ThesisSurface(const EvalJob& job) { return HelixSurface(job.Thesis().mesh); }
MeshDef ThesisDesignMesh(const EvalJob& job) { return job.Thesis().mesh; }
int ThesisVertices(const EvalJob& job) { return std::max(0, VertexCount(job.Thesis().mesh)); }

// A relaxation step per vertex.
std::uint64_t ThesisWork(const EvalJob& job) {
    return static_cast<std::uint64_t>(ThesisVertices(job)) * static_cast<std::uint64_t>(std::max(1, job.Thesis().params.iterations));
}

void ThesisOutputs(const SimResult& r, const EvalJob& job, OutputVisitor& v) {
    v.Count("iterations", r.iterationsRun);
    v.Count("iterations_requested", job.Thesis().params.iterations);
}

// [SECTION] membrane and shell: silicone at equilibrium (docs/models/shell.md)

SimResult MembraneEvaluate(const EvalJob& job) { return EvaluateShell(job.shape, job.Shell(), false); }
SimResult ShellEvaluate(const EvalJob& job) { return EvaluateShell(job.shape, job.Shell(), true); }

MeshDef ShellDesignMesh(const EvalJob& job) { return {job.Shell().geometry.ringVertices, RingCount(job.Shell().geometry)}; }

std::string ShellError(const EvalJob& job) {
    if (std::string error = ShellDefError(job.Shell()); !error.empty()) return error;
    // Shapes are checked as the thesis defines them; sizes that depend on the ring mesh (free-xy,
    // mesh) are checked when the tube is built, and a design that cannot be built is the status
    // invalid-geometry, not an input error.
    const MeshDef ringMesh = ShellDesignMesh(job);
    if (std::holds_alternative<FreeXYShape>(job.shape) || std::holds_alternative<MeshShape>(job.shape)) {
        const size_t n = static_cast<size_t>(ringMesh.resolution) * ringMesh.turns;
        const size_t got = std::holds_alternative<FreeXYShape>(job.shape) ? std::get<FreeXYShape>(job.shape).dx.size()
                                                                         : static_cast<size_t>(std::get<MeshShape>(job.shape).positions.Size());
        if (got != n)
            return std::string(ShapeName(job.shape)) + " needs one entry per vertex of the " + std::to_string(ringMesh.resolution) + " x " +
                   std::to_string(ringMesh.turns) + " ring mesh: " + std::to_string(n) + ", got " + std::to_string(got);
        return "";
    }
    return ShapeError(job.shape, DefaultMeshDef());
}

void ShellOutputList(const SimResult& r, const EvalJob& job, OutputVisitor& v) {
    const ShellOutputs& s = r.shell;
    v.Number("pressure_kpa", "kPa", s.targetPressureKpa);
    v.Number("limit_pressure_kpa", "kPa", s.limitPressureKpa);
    if (job.Shell().load.pressureKpa < 0) v.Number("collapse_pressure_kpa", "kPa", s.collapsePressureKpa);
    v.Number("blocking_force_n", "N", s.blockingForceN);
    v.Number("stroke_force_n", "N", s.strokeForceN);
    v.Number("held_bow_mm", "mm", s.heldBowMm);
    v.Number("axial_stiffness_n_per_mm", "N/mm", s.axialStiffnessNPerMm);
    v.Number("displacement_mm", "mm", s.displacementMm);
    v.Number("twist_deg", "deg", s.twistDeg);
    v.Number("twist_per_length_deg_per_mm", "deg/mm", s.twistPerLengthDegPerMm);
    v.Number("torque_n_mm", "N mm", s.torqueNMm);
    v.Number("tip_lateral_mm", "mm", s.tipLateralMm);
    v.Number("tip_tilt_deg", "deg", s.tipTiltDeg);
    v.Number("tip_force_n", "N", s.tipForceN);
    v.Number("tip_moment_n_mm", "N mm", s.tipMomentNMm);
    v.Number("work_per_stroke_mj", "mJ", s.workPerStrokeMj);
    v.Number("work_per_gram_mj_per_g", "mJ/g", s.workPerGramMjPerG);
    v.Number("silicone_g", "g", s.siliconeG);
    v.Number("rest_max_radius_mm", "mm", s.restMaxRadiusMm);
    v.Number("rest_volume_mm3", "mm^3", s.restVolumeMm3);
    v.Number("volume_mm3", "mm^3", s.volumeMm3);
    v.Number("max_stretch", "", s.maxStretch);
    v.Number("stretch_limit", "", s.stretchLimit);
    v.Number("max_stress_kpa", "kPa", s.maxStressKpa);
    v.Number("tensile_strength_kpa", "kPa", s.tensileStrengthKpa);
    if (job.Shell().fibres.layout != FibreLayout::None) {
        v.Number("max_fibre_strain", "", s.maxFibreStrain);
        v.Number("mean_fibre_strain", "", s.meanFibreStrain);
        v.Number("deformed_fibre_angle_deg", "deg", s.fibreAngleDeg);  // beside the laid angle, the setting fibre_angle_deg
    }
    if (job.Shell().contact.mode == ContactMode::On) {
        v.Count("contact_pairs", s.contactPairs);
        v.Number("min_gap_mm", "mm", s.minGapMm);
        v.Number("contact_force_n", "N", s.contactForceN);
    }
    v.Count("newton_iterations", s.newtonIterations);
    v.Count("factorizations", s.factorizations);
    v.Curve("curve_pressure_kpa", "kPa", s.curvePressureKpa);
    v.Curve("curve_contraction_percent", "%", s.curveContractionPercent);
    v.Curve("curve_volume_mm3", "mm^3", s.curveVolumeMm3);
    v.Curve("curve_force_n", "N", s.curveForceN);
    v.Curve("curve_twist_deg", "deg", s.curveTwistDeg);
    v.Curve("isobaric_contraction_percent", "%", s.isobaricContractionPercent);
    v.Curve("isobaric_force_n", "N", s.isobaricForceN);
}

Surface ShellModelSurface(const EvalJob& job) { return ShellSurface(job.Shell().geometry); }

int ShellVertices(const EvalJob& job) {
    const MeshDef rings = ShellDesignMesh(job);
    return std::max(0, rings.resolution) * std::max(0, rings.turns) + 2;
}

// A Newton iteration (assembly and a sparse factorisation) costs about as much per vertex as ten
// thousand relaxation steps of the thesis model (measured at 30 x 30); the estimate counts the
// whole budget: every load step's Newton iterations, or the evaluation's budget when it is smaller.
constexpr std::uint64_t kNewtonIterationWork = 10000;
std::uint64_t ShellWork(const EvalJob& job) {
    const ShellDef& d = job.Shell();
    std::uint64_t iterations = static_cast<std::uint64_t>(std::max(1, d.load.steps)) * static_cast<std::uint64_t>(std::max(1, d.solver.maxIterations));
    if (d.solver.newtonBudget > 0) iterations = std::min<std::uint64_t>(iterations, static_cast<std::uint64_t>(d.solver.newtonBudget));
    return static_cast<std::uint64_t>(ShellVertices(job)) * iterations * kNewtonIterationWork;
}

const char* kThesisFitness = "the thesis's contraction measure, mesh units";
const char* kContraction = "contraction at the target pressure, % (positive = shorter)";

ModelDef ThesisDefault() { return ThesisDef{}; }
ModelDef ShellDefault() { return DefaultShellDef(); }

std::string ThesisMeshText(const EvalJob& job) {
    return std::to_string(job.Thesis().mesh.resolution) + " vertices per turn x " + std::to_string(job.Thesis().mesh.turns) + " turns, vertices in helix order";
}
std::string ShellMeshText(const EvalJob& job) {
    const MeshDef rings = ShellDesignMesh(job);
    const GeometryDef& g = job.Shell().geometry;
    char graded[96] = "";
    if (RingsGraded(g)) std::snprintf(graded, sizeof graded, " (%.3g mm apart at the clamps' edges)", g.edgeSpacingMm);
    return std::to_string(rings.resolution) + " vertices per ring x " + std::to_string(rings.turns) + " rings" + graded +
           " and two cap centres, millimetres";
}
const char* ThesisLoadName(const EvalJob& job) { return Name(job.Thesis().params.load); }
const char* ShellLoadName(const EvalJob& job) { return Name(job.Shell().load.kind); }
int NoCurve(const EvalJob&) { return 0; }
int ShellCurvePoints(const EvalJob& job) { return std::max(0, job.Shell().load.steps); }

const Model kModels[] = {
    {ModelKind::Thesis, "thesis", ThesisEvaluate, ThesisError, ThesisSurface, ThesisVertices, ThesisDesignMesh, ThesisWork, ThesisDefault, ThesisMeshText, ThesisLoadName, NoCurve, ThesisOutputs, kThesisFitness,
     "mesh units", false},
    {ModelKind::Membrane, "membrane", MembraneEvaluate, ShellError, ShellModelSurface, ShellVertices, ShellDesignMesh, ShellWork, ShellDefault, ShellMeshText, ShellLoadName, ShellCurvePoints, ShellOutputList,
     kContraction, "mm", true},
    {ModelKind::Shell, "shell", ShellEvaluate, ShellError, ShellModelSurface, ShellVertices, ShellDesignMesh, ShellWork, ShellDefault, ShellMeshText, ShellLoadName, ShellCurvePoints, ShellOutputList, kContraction, "mm",
     true},
};

}  // namespace

const Model& ModelOf(ModelKind kind) {
    for (const Model& m : kModels)
        if (m.kind == kind) return m;
    throw std::logic_error("a model kind without a row");
}

void EvalJob::SetModel(ModelKind kind) {
    model = kind;
    ModelDef fresh = ModelOf(kind).defaultDef();
    if (fresh.index() != def.index()) def = std::move(fresh);  // a def of that kind already given is kept
}

void VisitOutputs(const SimResult& r, const EvalJob& job, OutputVisitor& v) {
    const bool ok = r.status == Status::Ok;
    const Model& model = ModelOf(job);
    v.Number("fitness", model.physical ? "%" : "mesh units", ok ? r.fitness : NAN);
    v.Number("contraction_percent", "%", ok ? r.contractionPercent : NAN);
    model.outputs(r, job, v);
    v.Number("elapsed_ms", "ms", r.elapsedMs);
}

std::vector<std::string> OutputNames(const std::vector<EvalJob>& jobs, bool withTime) {
    struct Names final : OutputVisitor {
        std::vector<std::string> names;
        bool withTime = false;
        void Add(const char* name) {
            if (!withTime && std::string(name) == "elapsed_ms") return;
            if (std::find(names.begin(), names.end(), name) == names.end()) names.emplace_back(name);
        }
        void Number(const char* name, const char*, double) override { Add(name); }
        void Count(const char* name, long long) override { Add(name); }
        void Curve(const char*, const char*, const std::vector<double>&) override {}
    } names;
    names.withTime = withTime;
    for (const EvalJob& job : jobs) VisitOutputs(SimResult{}, job, names);
    return names.names;
}

std::vector<std::string> OutputNames(bool withTime) {
    std::vector<EvalJob> jobs;
    for (const Model& model : kModels) {
        EvalJob& job = jobs.emplace_back();
        job.SetModel(model.kind);
        if (auto* shell = std::get_if<ShellDef>(&job.def)) {  // every output a shell job can have
            shell->fibres.layout = FibreLayout::Braid;
            shell->load.pressureKpa = -1;  // vacuum: the collapse pressure
            shell->contact.mode = ContactMode::On;
        }
    }
    return OutputNames(jobs, withTime);
}

std::string JobError(const EvalJob& job) {
    const Model& model = ModelOf(job);
    if (model.defaultDef().index() != job.def.index()) return std::string("the job's settings are not the ") + Name(job.model) + " model's";
    return model.error(job);
}

}  // namespace sim
