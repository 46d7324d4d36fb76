#include "formats/json_out.h"

#include <cmath>

#include "support/errors.h"
#include "sim/fields.h"
#include "sim/search.h"

namespace app {

Json NumberJson(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

void CheckJsonDepth(std::string_view text, const std::string& source) {
    int depth = 0;
    bool inString = false;
    size_t line = 1, lineStart = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') line += 1, lineStart = i + 1;
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
            continue;
        }
        if (c == '"') inString = true;
        else if (c == ']' || c == '}') --depth;
        else if ((c == '[' || c == '{') && ++depth > kMaxJsonDepth)
            throw UsageError(source + ": JSON nested more than " + std::to_string(kMaxJsonDepth) + " levels deep at line " + std::to_string(line) +
                             ", column " + std::to_string(i - lineStart + 1));
    }
}

Json ParseJson(std::string_view text, const std::string& source) {
    CheckJsonDepth(text, source);
    return Json::parse(text);
}

Json ShapeJson(const sim::Shape& shape) {
    Json j{{"name", sim::ShapeName(shape)}};
    if (const auto* s = std::get_if<sim::SineShape>(&shape)) {
        j["amplitude"] = s->amplitude;
        j["phase"] = {s->phaseStart, s->phaseEnd};
    } else if (const auto* a = std::get_if<sim::AbsSineShape>(&shape)) {
        j["amplitude"] = a->amplitude;
        j["phase"] = {a->phaseStart, a->phaseEnd};
    } else if (const auto* b = std::get_if<sim::BSplineShape>(&shape)) {
        j["region"] = sim::Name(b->region);
        j["control_points"] = b->splines;
    } else if (const auto* f = std::get_if<sim::FreeXYShape>(&shape)) {
        j["dx"] = f->dx;
        j["dy"] = f->dy;
    } else if (const auto* m = std::get_if<sim::MeshShape>(&shape)) {
        j["vertices"] = m->positions.Size();
    }
    return j;
}

namespace {

struct Writer {
    Json& j;
    void Integer(const char* key, const int& v, const char*, long long, long long) { j[key] = v; }
    void Number(const char* key, const double& v, const char*, double, double) { j[key] = NumberJson(v); }
    template <class E>
    void Enum(const char* key, const E& v, const char*) { j[key] = sim::Name(v); }
};

}  // namespace

Json ModelJson(const sim::EvalJob& job) {
    Json j{{"name", sim::Name(job.model)}};
    if (job.model == sim::ModelKind::Thesis) {
        VisitFields(job.Thesis().params, Writer{j});
        VisitFields(job.Thesis().mesh, Writer{j});
        j["vertices"] = sim::VertexCount(job.Thesis().mesh);
        j["springs"] = sim::SpringCount(job.Thesis().mesh);
        return j;
    }
    const sim::ShellDef& s = job.Shell();
    VisitFields(s.geometry, Writer{j});
    j["rings_used"] = sim::RingCount(s.geometry);
    j["material"] = sim::Name(s.material.preset);
    VisitFields(s.material, Writer{j});
    j["shear_modulus_kpa"] = sim::ShearModulusKpa(s.material);
    j["load"] = sim::Name(s.load.kind);
    VisitFields(s.load, Writer{j});
    VisitFields(s.solver, Writer{j});
    VisitFields(s.fibres, Writer{j});
    if (!s.fibres.bands.empty()) {
        Json bands = Json::array();
        for (const auto& band : s.fibres.bands) bands.push_back(Json{{"from", band.from}, {"to", band.to}, {"angle_deg", band.angleDeg}});
        j["fibre_bands"] = bands;
    }
    if (!s.fibres.sectorAnglesDeg.empty()) j["fibre_sectors_deg"] = s.fibres.sectorAnglesDeg;
    if (!s.fibres.plus || !s.fibres.minus) j["fibre_families_on"] = {s.fibres.plus, s.fibres.minus};
    return j;
}

Json ResultNumbersJson(const sim::SimResult& r, const sim::EvalJob& job) {
    const bool ok = r.status == sim::Status::Ok;
    Json j{{"status", sim::Name(r.status)},
           {"fitness", NumberJson(ok ? r.fitness : NAN)},
           {"contraction_percent", NumberJson(ok ? r.contractionPercent : NAN)}};
    if (job.model == sim::ModelKind::Thesis) {
        j["iterations"] = r.iterationsRun;
        j["iterations_requested"] = job.Thesis().params.iterations;
    } else {
        const sim::ShellOutputs& s = r.shell;
        j["pressure_kpa"] = NumberJson(s.targetPressureKpa);
        j["limit_pressure_kpa"] = NumberJson(s.limitPressureKpa);
        j["blocking_force_n"] = NumberJson(s.blockingForceN);
        j["axial_stiffness_n_per_mm"] = NumberJson(s.axialStiffnessNPerMm);
        j["displacement_mm"] = NumberJson(s.displacementMm);
        j["rest_volume_mm3"] = NumberJson(s.restVolumeMm3);
        j["volume_mm3"] = NumberJson(s.volumeMm3);
        j["max_stretch"] = NumberJson(s.maxStretch);
        j["stretch_limit"] = NumberJson(s.stretchLimit);
        j["max_stress_kpa"] = NumberJson(s.maxStressKpa);
        j["tensile_strength_kpa"] = NumberJson(s.tensileStrengthKpa);
        if (job.Shell().fibres.layout != sim::FibreLayout::None) {
            j["max_fibre_strain"] = NumberJson(s.maxFibreStrain);
            j["mean_fibre_strain"] = NumberJson(s.meanFibreStrain);
            j["fibre_angle_deg"] = NumberJson(s.fibreAngleDeg);
        }
        j["newton_iterations"] = s.newtonIterations;
        j["factorizations"] = s.factorizations;
        Json curve = Json::array();
        for (size_t k = 0; k < s.curvePressureKpa.size(); ++k)
            curve.push_back(Json{{"pressure_kpa", s.curvePressureKpa[k]},
                                 {"contraction_percent", NumberJson(s.curveContractionPercent[k])},
                                 {"volume_mm3", NumberJson(s.curveVolumeMm3[k])}});
        j["curve"] = curve;
    }
    j["elapsed_ms"] = r.elapsedMs;
    return j;
}

}  // namespace app
