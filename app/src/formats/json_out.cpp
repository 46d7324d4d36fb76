#include "formats/json_out.h"

#include <cmath>
#include <variant>

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

// Each def's block; a def added to sim::ModelDef without one here does not compile.
static void DefJson(const sim::ThesisDef& d, Json& j) {
    VisitFields(d.params, Writer{j});
    VisitFields(d.mesh, Writer{j});
    j["vertices"] = sim::VertexCount(d.mesh);
    j["springs"] = sim::SpringCount(d.mesh);
}

static void DefJson(const sim::ShellDef& s, Json& j) {
    VisitFields(s.geometry, Writer{j});
    j["rings_used"] = sim::RingCount(s.geometry);
    j["material"] = sim::Name(s.material.preset);
    VisitFields(s.material, Writer{j});
    j["shear_modulus_kpa"] = sim::ShearModulusKpa(s.material);
    j["load"] = sim::Name(s.load.kind);
    VisitFields(s.load, Writer{j});
    VisitFields(s.ends, Writer{j});
    VisitFields(s.solver, Writer{j});
    VisitFields(s.fibres, Writer{j});
    VisitFields(s.contact, Writer{j});
    if (s.envelope.Any()) VisitFields(s.envelope, Writer{j});  // written when given: records without one read as before
    if (!s.fibres.bands.empty()) {
        Json bands = Json::array();
        for (const auto& band : s.fibres.bands) bands.push_back(Json{{"from", band.from}, {"to", band.to}, {"angle_deg", band.angleDeg}});
        j["fibre_bands"] = bands;
    }
    if (!s.fibres.sectorAnglesDeg.empty()) j["fibre_sectors_deg"] = s.fibres.sectorAnglesDeg;
    if (!s.fibres.plus || !s.fibres.minus) j["fibre_families_on"] = {s.fibres.plus, s.fibres.minus};
}

Json ModelJson(const sim::EvalJob& job) {
    Json j{{"name", sim::Name(job.model)}};
    std::visit([&](const auto& def) { DefJson(def, j); }, job.def);
    return j;
}

Json ResultNumbersJson(const sim::SimResult& r, const sim::EvalJob& job) {
    // The outputs as they are visited; curves of one kind as one list of points, named by the part
    // of their names before the first '_' ("curve": the load steps; "isobaric": the held strokes),
    // where the visit put them. A kind whose curves are all empty is left out.
    struct Writer final : sim::OutputVisitor {
        Json j;
        std::vector<std::pair<std::string, const std::vector<double>*>> curves;  // full names, in visit order
        void Flush() {
            while (!curves.empty()) {
                const std::string kind = curves.front().first.substr(0, curves.front().first.find('_'));
                size_t length = 0;
                for (const auto& [name, values] : curves)
                    if (name.rfind(kind + "_", 0) == 0) length = std::max(length, values->size());
                Json list = Json::array();
                for (size_t k = 0; k < length; ++k) {
                    Json point = Json::object();
                    for (const auto& [name, values] : curves)
                        if (name.rfind(kind + "_", 0) == 0) point[name.substr(kind.size() + 1)] = NumberJson(k < values->size() ? (*values)[k] : NAN);
                    list.push_back(point);
                }
                if (length > 0 || kind == "curve") j[kind] = list;  // the load steps' curve is always given
                std::erase_if(curves, [&](const auto& c) { return c.first.rfind(kind + "_", 0) == 0; });
            }
        }
        // The curves, as one list, where the visit put them: before the next single number.
        void Number(const char* name, const char*, double value) override {
            Flush();
            j[name] = NumberJson(value);
        }
        void Count(const char* name, long long value) override {
            Flush();
            j[name] = value;
        }
        void Curve(const char* name, const char*, const std::vector<double>& values) override {
            curves.push_back({name, &values});
        }
    } writer;
    writer.j = Json{{"status", sim::Name(r.status)}};
    sim::VisitOutputs(r, job, writer);
    writer.Flush();
    return writer.j;
}

}  // namespace app
