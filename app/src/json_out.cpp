#include "json_out.h"

#include <cmath>

#include "fields.h"
#include "sim/search.h"

namespace app {

Json NumberJson(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

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
    Json j{{"name", "thesis"}};
    VisitFields(job.params, Writer{j});
    VisitFields(job.mesh, Writer{j});
    j["vertices"] = sim::VertexCount(job.mesh);
    j["springs"] = sim::SpringCount(job.mesh);
    return j;
}

Json ResultNumbersJson(const sim::SimResult& r, const sim::SimParams& params) {
    return Json{{"status", sim::Name(r.status)},
                {"fitness", NumberJson(r.status == sim::Status::Ok ? r.fitness : NAN)},
                {"contraction_percent", NumberJson(r.status == sim::Status::Ok ? r.contractionPercent : NAN)},
                {"iterations", r.iterationsRun},
                {"iterations_requested", params.iterations},
                {"elapsed_ms", r.elapsedMs}};
}

}  // namespace app
