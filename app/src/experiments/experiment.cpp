// [SECTION] Reading one JSON object strictly
// [SECTION] --set
// [SECTION] Experiment files
// [SECTION] Saved experiments, hashes, titles
#include "formats/json_out.h"
#include "materials/material_file.h"
#include "pictures/plots.h"
#include "experiments/experiment.h"
#include "experiments/experiment_library.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <set>

#include "support/errors.h"
#include "sim/fields.h"
#include "formats/files.h"
#include "support/number_expression.h"

namespace app {
namespace {

// [SECTION] Each model's def in an experiment (a new def adds one overload of each): whether fibres are on the wall to be
// searched, and how `--quick` shrinks it.

sim::FibreDef FibresOn(const sim::ThesisDef&) { return {}; }
sim::FibreDef FibresOn(const sim::ShellDef& def) { return def.fibres; }

void ShrinkForQuick(Json& document, const sim::ThesisDef& def) { document["sim"]["iterations"] = std::min(def.params.iterations, 2000); }
void ShrinkForQuick(Json& document, const sim::ShellDef& def) {
    // A coarse ring mesh and two load steps: the membrane and shell models' cost is in the mesh.
    Json& model = document["model"];
    model["load"]["steps"] = std::min(def.load.steps, 2);
    model["geometry"]["ring_vertices"] = std::min(def.geometry.ringVertices, 12);
    model["geometry"]["rings"] = std::min(def.geometry.rings > 0 ? def.geometry.rings : sim::RingCount(def.geometry), 16);
    // Evenly spaced: graded rings toward the clamps would add more than the coarse mesh saves.
    if (def.geometry.ends == sim::EndCondition::Clamped) model["geometry"]["edge_spacing_mm"] = 0;
}


using Json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// [SECTION] Reading one JSON object strictly
// ---------------------------------------------------------------------------------------------

size_t EditDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

std::string Shown(const Json& value) {
    return value.is_string() ? Quote(value.get<std::string>()) : Quote(value.dump());
}

// Where messages point: the file, and which key paths were set on the command line.
struct Source {
    std::string file;
    const std::vector<Override>* overrides = nullptr;

    // "--set evolve.generations=x: " when the key (or an object above it) was set by --set.
    std::string Prefix(const std::string& where) const {
        if (overrides)
            for (const auto& o : *overrides)
                if (where == o.path || where.rfind(o.path + ".", 0) == 0 || where.rfind(o.path + "[", 0) == 0 ||
                    o.path.rfind(where + ".", 0) == 0)
                    return file + " with --set " + o.path + "=" + o.value + ": ";
        return file + ": ";
    }
};

// Reads one JSON object, remembering its key path for messages, which keys were used and which were
// asked for, so that anything left over (a typo, a key from another section) is reported with the
// nearest valid key instead of ignored.
class ObjectReader {
public:
    ObjectReader(const Json& object, std::string path, const Source& source) : object_(object), path_(std::move(path)), source_(source) {
        if (!object_.is_object()) Fail(path_.empty() ? "the file must hold a JSON object" : "expected an object, got " + Shown(object_));
    }

    bool Has(const std::string& key) {
        known_.insert(key);
        return object_.contains(key);
    }
    std::string Child(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
    // The keys the file gives, in its order.
    std::vector<std::string> GivenKeys() const {
        std::vector<std::string> keys;
        for (const auto& [key, value] : object_.items()) keys.push_back(key);
        return keys;
    }
    const Source& Origin() const { return source_; }

    [[noreturn]] void Fail(const std::string& reason, const std::string& key = "") const {
        const std::string where = key.empty() ? path_ : Child(key);
        throw UsageError(source_.Prefix(where) + (where.empty() ? "" : "'" + where + "': ") + reason);
    }

    const Json& Get(const std::string& key) {
        known_.insert(key);
        used_.insert(key);
        if (!object_.contains(key)) Fail("missing (required)", key);
        return object_.at(key);
    }

    // Numbers may be JSON numbers or strings with pi and arithmetic ("pi-0.5").
    double NumberValue(const Json& value, const std::string& key, double min, double max) const {
        double number = 0;
        if (value.is_number()) number = value.get<double>();
        else if (value.is_string()) {
            if (!TryParseNumber(value.get<std::string>(), &number)) Fail(Shown(value) + " is not a number", key);
        } else {
            Fail("expected a number, got " + Shown(value), key);
        }
        if (!(number >= min && number <= max))
            Fail(fmt::format("{} is out of range ({} to {})", Shown(value), min == -sim::kUnbounded ? "any" : fmt::format("{}", min),
                             max == sim::kUnbounded ? "any" : fmt::format("{}", max)),
                 key);
        return number;
    }
    void Number(const std::string& key, double& target, double min, double max) {
        if (Has(key)) target = NumberValue(Get(key), key, min, max);
    }
    double Number(const std::string& key, double min, double max) { return NumberValue(Get(key), key, min, max); }

    long long IntegerValue(const Json& value, const std::string& key, long long min, long long max) const {
        if (!value.is_number_integer()) Fail("expected a whole number, got " + Shown(value), key);
        if (value.is_number_unsigned() && value.get<unsigned long long>() > static_cast<unsigned long long>(max))
            Fail(Shown(value) + " is out of range (" + std::to_string(min) + " to " + std::to_string(max) + ")", key);
        const long long number = value.get<long long>();
        if (number < min || number > max) Fail(Shown(value) + " is out of range (" + std::to_string(min) + " to " + std::to_string(max) + ")", key);
        return number;
    }
    template <class Int>
    void Integer(const std::string& key, Int& target, long long min, long long max) {
        if (Has(key)) target = static_cast<Int>(IntegerValue(Get(key), key, min, max));
    }

    std::string String(const std::string& key, const std::string& fallback) {
        if (!Has(key)) return fallback;
        const Json& value = Get(key);
        if (!value.is_string()) Fail("expected a string, got " + Shown(value), key);
        return value.get<std::string>();
    }

    template <class E>
    void Enum(const std::string& key, E& target) {
        if (!Has(key)) return;
        const Json& value = Get(key);
        if (!value.is_string()) Fail("expected one of " + sim::Choices<E>() + ", got " + Shown(value), key);
        const auto parsed = sim::FromName<E>(value.get<std::string>());
        if (!parsed) Fail("unknown value " + Shown(value) + " (choose " + sim::Choices<E>() + ")", key);
        target = *parsed;
    }

    void Bool(const std::string& key, bool& target) {
        if (!Has(key)) return;
        const Json& value = Get(key);
        if (!value.is_boolean()) Fail("expected true or false, got " + Shown(value), key);
        target = value.get<bool>();
    }

    ObjectReader Object(const std::string& key) { return ObjectReader(Get(key), Child(key), source_); }

    const Json& Array(const std::string& key, size_t minSize, size_t maxSize, const std::string& what) {
        const Json& value = Get(key);
        if (!value.is_array() || value.size() < minSize || value.size() > maxSize) Fail("expected " + what, key);
        return value;
    }

    std::pair<double, double> Range(const std::string& key, std::pair<double, double> fallback, double min, double max) {
        if (!Has(key)) return fallback;
        const Json& value = Array(key, 2, 2, "[low, high]");
        const double low = NumberValue(value[0], key, min, max), high = NumberValue(value[1], key, min, max);
        if (low > high) Fail("low end above high end", key);
        return {low, high};
    }

    // The fields of a def struct (fields.h), each optional, defaults from the struct.
    template <class Def>
    void Fields(Def& def);

    // A key asked for under another name in earlier versions: named in the message.
    void Moved(const std::string& key, const std::string& where) {
        if (object_.contains(key)) Fail("has moved: write it as " + where, key);
    }

    void Finish() const {
        for (const auto& [key, value] : object_.items()) {
            if (used_.count(key)) continue;
            // The nearest valid key: one that starts with or contains what was typed, else the closest
            // by edit distance when that is small against the key's length.
            std::string nearest;
            size_t best = std::max<size_t>(3, key.size() / 3 + 1);
            for (const auto& k : known_) {
                const size_t d = k.find(key) != std::string::npos || key.find(k) != std::string::npos ? 0 : EditDistance(key, k);
                if (d < best) {
                    best = d;
                    nearest = k;
                }
            }
            std::string valid;
            for (const auto& k : known_) valid += (valid.empty() ? "" : ", ") + k;
            Fail("unknown key" + (nearest.empty() ? std::string(" (valid here: " + valid + ")") : " (did you mean '" + Child(nearest) + "'?)"), key);
        }
    }

private:
    const Json& object_;
    std::string path_;
    const Source& source_;
    std::set<std::string> used_, known_;
};

struct FieldReader {
    ObjectReader& r;
    void Integer(const char* key, int& v, const char*, long long min, long long max) { r.Integer(key, v, min, max); }
    void Number(const char* key, double& v, const char*, double min, double max) { r.Number(key, v, min, max); }
    template <class E>
    void Enum(const char* key, E& v, const char*) {
        r.Enum(key, v);
    }
};

template <class Def>
void ObjectReader::Fields(Def& def) {
    VisitFields(def, FieldReader{*this});
}

// ---------------------------------------------------------------------------------------------
// [SECTION] --set
// ---------------------------------------------------------------------------------------------

// Puts `value` at `path` ("a.b[2].c") in `document`, creating objects on the way.
void Apply(Json& document, const Override& o, const std::string& file) {
    Json* node = &document;
    size_t pos = 0;
    const std::string& path = o.path;
    auto fail = [&](const std::string& why) { throw UsageError("--set " + o.path + "=" + o.value + ": " + why + " (in " + file + ")"); };
    int depth = 0;
    while (pos < path.size()) {
        if (++depth > kMaxJsonDepth) fail("the path is more than " + std::to_string(kMaxJsonDepth) + " levels deep");
        if (path[pos] == '[') {
            const size_t close = path.find(']', pos);
            if (close == std::string::npos) fail("unclosed '['");
            const long long index = ParseInteger(path.substr(pos + 1, close - pos - 1), "--set " + o.path + " index", 0, 1 << 20);
            if (!node->is_array()) fail("'" + path.substr(0, pos) + "' is not a list");
            if (static_cast<size_t>(index) >= node->size())
                fail("'" + path.substr(0, pos) + "' has " + std::to_string(node->size()) + " entries, no [" + std::to_string(index) + "]");
            node = &(*node)[static_cast<size_t>(index)];
            pos = close + 1;
            if (pos < path.size() && path[pos] == '.') ++pos;
            continue;
        }
        const size_t end = path.find_first_of(".[", pos);
        const std::string key = path.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        if (key.empty()) fail("empty key in the path");
        if (node->is_null()) *node = Json::object();
        if (!node->is_object()) fail("'" + path.substr(0, pos ? pos - 1 : 0) + "' is not an object");
        node = &(*node)[key];
        pos = end == std::string::npos ? path.size() : (path[end] == '.' ? end + 1 : end);
    }
    Json value;
    try {
        value = ParseJson(o.value, "--set " + o.path);
    } catch (const Json::exception&) {
        value = o.value;  // not JSON: a string ("sine", "pi/2")
    }
    *node = value;
}

// nlohmann's parse errors carry a byte offset: name the line, column and the key being read there.
std::string ParseErrorWhere(const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    const size_t line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n');
    const size_t lineStart = text.rfind('\n', offset ? offset - 1 : 0);
    const size_t column = offset - (lineStart == std::string::npos ? 0 : lineStart + 1);
    std::string where = "line " + std::to_string(line) + ", column " + std::to_string(column);
    // The last "key": before the error.
    const size_t colon = text.rfind(':', offset ? offset - 1 : 0);
    if (colon != std::string::npos) {
        const size_t close = text.rfind('"', colon);
        const size_t open = close == std::string::npos || close == 0 ? std::string::npos : text.rfind('"', close - 1);
        if (open != std::string::npos) where += ", key '" + text.substr(open + 1, close - open - 1) + "'";
    }
    return where;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Experiment files
// ---------------------------------------------------------------------------------------------

std::vector<std::pair<sim::SweepParameter, double>> SweepPoint(ObjectReader& object) {
    std::vector<std::pair<sim::SweepParameter, double>> at;
    for (const auto& [parameter, name] : sim::EnumNames<sim::SweepParameter>::table)
        if (object.Has(name)) at.push_back({parameter, object.Number(name, -1e6, 1e6)});
    return at;
}

sim::SweepAxis ParseAxis(ObjectReader axis) {
    sim::SweepAxis a;
    if (!axis.Has("parameter")) axis.Fail("missing (required): one of " + sim::Choices<sim::SweepParameter>(), "parameter");
    axis.Enum("parameter", a.parameter);
    if (axis.Has("values")) {
        for (const auto& v : axis.Array("values", 1, 10000, "a list of 1 to 10000 numbers")) a.values.push_back(axis.NumberValue(v, "values", -1e6, 1e6));
    } else {
        const double from = axis.Number("from", -1e6, 1e6), to = axis.Number("to", -1e6, 1e6);
        int points = 0;
        if (!axis.Has("points")) axis.Fail("missing (required)", "points");
        axis.Integer("points", points, 1, 10000);
        a.values = sim::Linspace(from, to, points);
    }
    axis.Finish();
    return a;
}

sim::Shape ParseSineBase(ObjectReader shape) {
    if (!shape.Has("family")) shape.Fail("missing (required): sine or abs-sine", "family");
    sim::ShapeKind family = sim::ShapeKind::Sine;
    shape.Enum("family", family);
    if (family != sim::ShapeKind::Sine && family != sim::ShapeKind::AbsSine) shape.Fail("a sweep varies sine or abs-sine shapes", "family");
    sim::SineShape s;
    if (family == sim::ShapeKind::AbsSine) {
        const sim::AbsSineShape a;
        s = {a.amplitude, a.phaseStart, a.phaseEnd};
    }
    shape.Number("amplitude", s.amplitude, -1e3, 1e3);
    std::tie(s.phaseStart, s.phaseEnd) = shape.Range("phase", {s.phaseStart, s.phaseEnd}, -1e4, 1e4);
    shape.Finish();
    if (family == sim::ShapeKind::Sine) return s;
    return sim::AbsSineShape{s.amplitude, s.phaseStart, s.phaseEnd};
}

LabelledShape ParseListedShape(ObjectReader shape, size_t k, const sim::MeshDef& mesh) {
    LabelledShape labelled;
    labelled.label = shape.String("label", "shape " + std::to_string(k));
    shape.Number("thesis_fitness", labelled.thesisFitness, -1e6, 1e6);
    labelled.source = shape.String("source", "");
    if (!shape.Has("family")) shape.Fail("missing (required): cylinder, sine, abs-sine or bspline", "family");
    sim::ShapeKind family = sim::ShapeKind::Cylinder;
    shape.Enum("family", family);
    switch (family) {
        case sim::ShapeKind::Sine:
        case sim::ShapeKind::AbsSine: {
            const double amplitude = shape.Number("amplitude", -1e3, 1e3);
            const auto phase = shape.Range("phase", {0, 0}, -1e4, 1e4);
            if (!shape.Has("phase")) shape.Fail("missing (required)", "phase");
            if (family == sim::ShapeKind::Sine) labelled.shape = sim::SineShape{amplitude, phase.first, phase.second};
            else labelled.shape = sim::AbsSineShape{amplitude, phase.first, phase.second};
            break;
        }
        case sim::ShapeKind::BSpline: {
            sim::BSplineShape b;
            shape.Enum("region", b.region);
            for (const auto& spline : shape.Array("control_points", 1, 4, "a list of 1, 2 or 4 splines, each a list of numbers")) {
                if (!spline.is_array()) shape.Fail("expected a list of splines, each a list of numbers", "control_points");
                std::vector<double> points;
                for (const auto& c : spline) points.push_back(shape.NumberValue(c, "control_points", -1e3, 1e3));
                b.splines.push_back(points);
            }
            labelled.shape = b;
            break;
        }
        case sim::ShapeKind::Cylinder: labelled.shape = sim::CylinderShape{}; break;
        default: shape.Fail("a listed shape is cylinder, sine, abs-sine or bspline", "family");
    }
    shape.Finish();
    if (const std::string error = sim::ShapeError(labelled.shape, mesh); !error.empty()) shape.Fail(error);
    return labelled;
}

// A given key of a shell model block that has no effect under the definition is refused, naming
// what decides: '"kind": "force"' for the load's keys, '"law"' for the material's, and so on. The
// rules are the def's (sim::ShellFieldUse), the same the command line and Python are held to.
void RefuseKeysWithoutEffect(const ObjectReader& block, const sim::ShellDef& shell) {
    for (const std::string& key : block.GivenKeys()) {
        const sim::FieldUse use = ShellFieldUse(shell, key);
        if (!use.Applies())
            block.Fail(fmt::format("has no effect here: it applies when \"{}\" is {}, not {}", use.decider, use.values, use.now), key);
    }
}

// "model": {"name": "shell", "geometry": {...}, "material": {"preset": ..., "mu_kpa": ...},
// "load": {"kind": ..., "pressure_kpa": ...}, "ends": {"twist": ...}, "solver": {...}}. The thesis model takes only its name
// (its settings are the "sim" and "mesh" blocks).
// Each def reads the rest of the block (a new def adds its overload).
void ParseModelBlock(ObjectReader& model, sim::ThesisDef&) {
    for (const char* key : {"geometry", "material", "load", "ends", "envelope", "solver", "fibres", "fibre_angle_deg", "fibre_stiffness_n_per_mm", "fibre_bands",
                            "fibre_sectors_deg", "contact", "contact_gap_fraction", "contact_stiffness"})
        if (model.Has(key)) model.Fail("does not apply to the thesis model (its settings are the 'sim' and 'mesh' blocks)", key);
    model.Finish();
}
void ParseModelBlock(ObjectReader& model, sim::ShellDef& shell) {
    if (model.Has("geometry")) {
        ObjectReader geometry = model.Object("geometry");
        geometry.Fields(shell.geometry);
        RefuseKeysWithoutEffect(geometry, shell);
        geometry.Finish();
    }
    if (model.Has("material")) {
        ObjectReader material = model.Object("material");
        sim::MaterialPreset preset = shell.material.preset;
        material.Enum("preset", preset);
        sim::MaterialDef given = shell.material;
        material.Fields(given);
        shell.material = MaterialWithOverrides(preset, given, [&](const char* key) { return material.Has(key); });
        RefuseKeysWithoutEffect(material, shell);
        material.Finish();
    }
    if (model.Has("load")) {
        ObjectReader load = model.Object("load");
        load.Enum("kind", shell.load.kind);
        load.Fields(shell.load);
        RefuseKeysWithoutEffect(load, shell);
        load.Finish();
    }
    if (model.Has("ends")) {
        ObjectReader ends = model.Object("ends");
        ends.Fields(shell.ends);
        RefuseKeysWithoutEffect(ends, shell);
        ends.Finish();
    }
    if (model.Has("envelope")) {
        ObjectReader envelope = model.Object("envelope");
        envelope.Fields(shell.envelope);
        envelope.Finish();
    }
    if (model.Has("solver")) {
        ObjectReader solver = model.Object("solver");
        solver.Fields(shell.solver);
        RefuseKeysWithoutEffect(solver, shell);
        solver.Finish();
    }
    // Self-contact and fibres: the command line's keys in the model block ("contact": "on"); fibres
    // also take angles by band along the length or by sector.
    model.Fields(shell.contact);
    model.Fields(shell.fibres);
    if (model.Has("fibre_bands")) {
        const Json& bands = model.Array("fibre_bands", 1, 1000, "a list of bands {\"from\": 0, \"to\": 0.5, \"angle_deg\": 30}");
        for (size_t k = 0; k < bands.size(); ++k) {
            ObjectReader band(bands[k], model.Child("fibre_bands") + "[" + std::to_string(k) + "]", model.Origin());
            sim::FibreBand b;
            b.from = band.Number("from", 0, 1);
            b.to = band.Number("to", 0, 1);
            b.angleDeg = band.Number("angle_deg", -90, 90);
            band.Finish();
            shell.fibres.bands.push_back(b);
        }
    }
    if (model.Has("fibre_sectors_deg"))
        for (const auto& angle : model.Array("fibre_sectors_deg", 1, 4, "a list of 1, 2 or 4 angles (degrees)"))
            shell.fibres.sectorAnglesDeg.push_back(model.NumberValue(angle, "fibre_sectors_deg", -90, 90));
    RefuseKeysWithoutEffect(model, shell);
    model.Finish();
    if (const std::string error = sim::ShellDefError(shell); !error.empty()) model.Fail(error);
}

void ParseModel(ObjectReader model, Experiment& e) {
    if (!model.Has("name")) model.Fail("missing (required): " + sim::Choices<sim::ModelKind>(), "name");
    model.Enum("name", e.model);
    e.def = sim::ModelOf(e.model).defaultDef();
    std::visit([&](auto& def) { ParseModelBlock(model, def); }, e.def);
}

// Keys whose value the experiment itself replaces have no effect, and are refused as the command
// line refuses an option that does not apply: a model setting a sweep axis varies, the shape's
// amplitude under an amplitude axis, fibre angles under the genome's fibre angle genes.
void RefuseReplacedKeys(const Experiment& e) {
    const Json& d = e.document;
    auto given = [&](std::initializer_list<const char*> path) {
        const Json* node = &d;
        for (const char* key : path) {
            if (!node->is_object() || !node->contains(key)) return false;
            node = &(*node)[key];
        }
        return true;
    };
    auto refuse = [&](const std::string& key, const std::string& why) {
        throw UsageError(e.path + ": '" + key + "': has no effect here: " + why + "; leave it out");
    };
    if (e.kind == ExperimentKind::Sweep)
        for (size_t k = 0; k < e.sweep.axes.size(); ++k) {
            const std::string axis = fmt::format("sweep.axes[{}] varies it", k);
            switch (e.sweep.axes[k].parameter) {
                case sim::SweepParameter::PressureKpa:
                    if (given({"model", "load", "pressure_kpa"})) refuse("model.load.pressure_kpa", axis);
                    break;
                case sim::SweepParameter::FibreAngleDeg:
                    if (given({"model", "fibre_angle_deg"})) refuse("model.fibre_angle_deg", axis);
                    break;
                case sim::SweepParameter::Amplitude:
                    if (given({"sweep", "shape", "amplitude"})) refuse("sweep.shape.amplitude", axis);
                    break;
                default: break;
            }
        }
    const sim::GenomeDef* genes = e.kind == ExperimentKind::Evolve ? &e.ga.genome : e.kind == ExperimentKind::Optimize ? &e.optimizer.genome.genes : nullptr;
    if (genes && genes->fibreAngles > 0)
        for (const char* key : {"fibre_angle_deg", "fibre_bands", "fibre_sectors_deg"})
            if (given({"model", key})) refuse(std::string("model.") + key, "the genome's fibre angle genes give the angles");
}

// A B-spline genome's "control": [min, max] and "control_step" (the GA's and the optimizers'): the
// control points' grid, radii in base-radius units.
void ParseControlRange(ObjectReader& genome, sim::GenomeDef& g) {
    const auto control = genome.Range("control", {g.controlMin, g.controlMax}, -1000, 1000);
    g.controlMin = control.first;
    g.controlMax = control.second;
    genome.Number("control_step", g.controlStep, 1e-6, 1000);
    if (const std::string error = sim::ControlGridError(g); !error.empty()) genome.Fail(error, "control_step");
}

// Fibre genes (membrane and shell models with fibres in the model block): how many angle genes,
// on/off switches and the angles' range.
void ParseFibreGenes(ObjectReader& genome, const Experiment& e, sim::GenomeDef& g) {
    genome.Integer("fibre_angles", g.fibreAngles, 0, 64);
    genome.Bool("fibre_switches", g.fibreSwitches);
    const auto fibreRange = genome.Range("fibre_angle_range", {g.fibreAngleMin, g.fibreAngleMax}, -90, 90);
    g.fibreAngleMin = fibreRange.first;
    g.fibreAngleMax = fibreRange.second;
    const sim::FibreLayout fibres = std::visit([](const auto& def) { return FibresOn(def).layout; }, e.def);
    if (g.HasFibreGenes() && fibres == sim::FibreLayout::None)
        genome.Fail("fibre genes need fibres on the wall: a membrane or shell model with \"fibres\": \"braid\" (or single) in the model block",
                    g.fibreAngles > 0 ? "fibre_angles" : "fibre_switches");
}

// "stop": {"evaluations": 0, "seconds": 0, "target": 5, "stagnation": 0} of the GA and the optimizers.
void ParseStop(ObjectReader stop, sim::StopDef& s) {
    stop.Integer("evaluations", s.evaluations, 0, 1ll << 40);
    stop.Number("seconds", s.seconds, 0, 1e9);
    stop.Number("target", s.target, -1e12, 1e12);
    stop.Integer("stagnation", s.stagnation, 0, 100000);
    stop.Finish();
}

void ParseGa(ObjectReader evolve, Experiment& e) {
    sim::GaDef& ga = e.ga;
    evolve.Integer("runs", e.runs, 1, 100);
    evolve.Integer("population", ga.population, 2, 100000);
    evolve.Integer("generations", ga.generations, 0, 100000);
    evolve.Integer("tournament", ga.tournament, 1, 1000);
    evolve.Integer("elite", ga.elite, 0, 100000);
    evolve.Number("mutpb", ga.mutpb, 0, 1);
    evolve.Number("indpb", ga.indpb, 0, 1);
    evolve.Number("cxpb", ga.cxpb, 0, 1);
    if (evolve.Has("stop")) ParseStop(evolve.Object("stop"), ga.stop);
    ObjectReader genome = evolve.Object("genome");
    sim::GenomeDef& g = ga.genome;
    if (!genome.Has("kind")) genome.Fail("missing (required): " + sim::Choices<sim::GenomeKind>(), "kind");
    genome.Enum("kind", g.kind);
    if (g.kind == sim::GenomeKind::BSpline) {
        genome.Enum("region", g.region);
        genome.Integer("splines", g.splines, 1, 4);
        if (g.splines == 3) genome.Fail("must be 1, 2 or 4", "splines");
        ParseControlRange(genome, g);
        const auto length = genome.Range("length", {g.lengthMin, g.lengthMax}, 4, 1000);
        if (length.first != std::floor(length.first) || length.second != std::floor(length.second)) genome.Fail("lengths are whole numbers", "length");
        g.lengthMin = static_cast<int>(length.first);
        g.lengthMax = static_cast<int>(length.second);
    } else {
        genome.Enum("region", g.region);
        genome.Number("init_range", g.initRange, 0, 100);
        genome.Number("sigma", g.sigma, 0, 100);
        genome.Number("bound", g.bound, 1e-9, 100);
    }
    ParseFibreGenes(genome, e, g);
    genome.Number("fibre_sigma_deg", g.fibreSigmaDeg, 0, 180);  // the GA's mutation only
    genome.Finish();
    evolve.Finish();
    if (const std::string error = sim::GaDefError(ga, DesignMesh(e)); !error.empty()) evolve.Fail(error);
}

// "optimizer": {"algorithm": "cmaes", "runs": 1, "population": 16, "parameters": {"sigma0": 0.3},
// "objectives": ["contraction", {"name": "max_stretch", "direction": "min"}],
// "generations": 20, "stop": {"evaluations": 0, "seconds": 0, "target": 5, "stagnation": 0},
// "genome": {"family": "bspline", "region": "middle", "splines": 1, "control_points": 8, ...}}.
void ParseOptimizer(ObjectReader block, Experiment& e) {
    sim::OptimizerDef& o = e.optimizer;
    if (!block.Has("algorithm")) block.Fail("missing (required): " + sim::Choices<sim::Algorithm>(), "algorithm");
    if (block.Get("algorithm") == "ga")
        block.Fail("the thesis's GA (variable-length genomes) is the 'evolve' block; 'optimizer' takes " + sim::Choices<sim::Algorithm>(), "algorithm");
    block.Enum("algorithm", o.algorithm);
    block.Integer("runs", e.runs, 1, 100);
    block.Integer("population", o.population, 1, 100000);
    block.Integer("generations", o.generations, 0, 100000);
    if (block.Has("parameters")) {
        const Json& parameters = block.Get("parameters");
        if (!parameters.is_object()) block.Fail("expected an object of the algorithm's parameters, e.g. {\"sigma0\": 0.3}", "parameters");
        for (const auto& [key, value] : parameters.items()) o.parameters[key] = block.NumberValue(value, "parameters." + key, -1e9, 1e9);
    }
    if (block.Has("objectives")) {
        o.objectives.clear();
        const Json& list = block.Array("objectives", 1, 6, "a list of 1 to 6 objectives: names, or {\"name\": ..., \"direction\": \"max\" or \"min\"}");
        for (size_t k = 0; k < list.size(); ++k) {
            const std::string where = block.Child("objectives") + "[" + std::to_string(k) + "]";
            sim::Objective objective;
            std::string direction;
            if (list[k].is_string()) {
                const auto kind = sim::FromName<sim::ObjectiveKind>(list[k].get<std::string>());
                if (!kind) block.Fail("unknown objective " + Shown(list[k]) + " (choose " + sim::Choices<sim::ObjectiveKind>() + ")", "objectives");
                objective.kind = *kind;
            } else {
                ObjectReader item(list[k], where, block.Origin());
                if (!item.Has("name")) item.Fail("missing (required): " + sim::Choices<sim::ObjectiveKind>(), "name");
                item.Enum("name", objective.kind);
                direction = item.String("direction", "");
                if (!direction.empty() && direction != "max" && direction != "min") item.Fail("expected \"max\" or \"min\", got " + Quote(direction), "direction");
                item.Finish();
            }
            objective.maximise = direction.empty() ? sim::MaximisedByDefault(objective.kind) : direction == "max";
            o.objectives.push_back(objective);
        }
    }
    if (block.Has("stop")) ParseStop(block.Object("stop"), o.stop);
    ObjectReader genome = block.Object("genome");
    sim::VectorGenomeDef& v = o.genome;
    sim::GenomeDef& g = v.genes;
    if (!genome.Has("family")) genome.Fail("missing (required): " + sim::Choices<sim::VectorFamily>(), "family");
    genome.Enum("family", v.family);
    auto range = [&](const char* key, std::array<double, 2>& target, double min, double max) {
        const auto r = genome.Range(key, {target[0], target[1]}, min, max);
        target = {r.first, r.second};
    };
    switch (v.family) {
        case sim::VectorFamily::Sine:
        case sim::VectorFamily::AbsSine:
            if (v.family == sim::VectorFamily::AbsSine) {
                const sim::AbsSineShape a;
                v.phaseStart = {a.phaseStart, a.phaseStart};
                v.phaseEnd = {a.phaseEnd, a.phaseEnd};
            }
            range("amplitude", v.amplitude, -1e3, 1e3);
            range("phase_start", v.phaseStart, -1e4, 1e4);
            range("phase_end", v.phaseEnd, -1e4, 1e4);
            break;
        case sim::VectorFamily::BSpline: {
            g.kind = sim::GenomeKind::BSpline;
            genome.Enum("region", g.region);
            genome.Integer("splines", g.splines, 1, 4);
            genome.Integer("control_points", v.controlPoints, 4, 64);
            ParseControlRange(genome, g);
            break;
        }
        case sim::VectorFamily::FreeXY:
            g.kind = sim::GenomeKind::FreeXY;
            genome.Number("bound", g.bound, 1e-9, 100);
            break;
    }
    ParseFibreGenes(genome, e, g);
    genome.Finish();
    block.Finish();
    e.ga.genome = g;  // JobOfGenome and GenomeOfJob read the genes from here
    if (const std::string error = sim::OptimizerDefError(o, e.model, DesignMesh(e)); !error.empty()) block.Fail(error);
    for (const sim::Objective& objective : o.objectives)
        if (const std::string error = sim::ObjectiveDefError(objective.kind, e.def); !error.empty()) block.Fail(error, "objectives");
}

void ParseThesisResult(ObjectReader result, ThesisResult& t, const sim::MeshDef& mesh) {
    result.Number("best_fitness", t.bestFitness, -1e6, 1e6);
    if (result.Has("best")) {
        ObjectReader best = result.Object("best");
        t.best = SweepPoint(best);
        best.Finish();
    }
    if (result.Has("points")) {
        const Json& points = result.Array("points", 0, 1000, "a list of points");
        for (size_t k = 0; k < points.size(); ++k) {
            ObjectReader point(points[k], result.Child("points") + "[" + std::to_string(k) + "]", result.Origin());
            ThesisResult::Point p;
            p.at = SweepPoint(point);
            p.fitness = point.Number("fitness", -1e6, 1e6);
            p.source = point.String("source", "");
            point.Finish();
            t.points.push_back(p);
        }
    }
    if (result.Has("run_best"))
        for (const auto& v : result.Array("run_best", 0, 100, "a list of numbers")) t.runBest.push_back(result.NumberValue(v, "run_best", -1e6, 1e6));
    result.Number("mean_best", t.meanBest, -1e6, 1e6);
    t.meanBestSource = result.String("mean_best_source", "");
    if (result.Has("claims")) {
        const Json& claims = result.Array("claims", 1, 20, "a list of {\"kind\": ..., \"source\": ...}");
        using Kind = ThesisResult::LandscapeClaim::Kind;
        for (size_t k = 0; k < claims.size(); ++k) {
            ObjectReader claim(claims[k], result.Child("claims") + "[" + std::to_string(k) + "]", result.Origin());
            ThesisResult::LandscapeClaim c;
            const std::string kind = claim.String("kind", "");
            const std::vector<std::pair<std::string, Kind>> kinds{
                {"peaks", Kind::Peaks}, {"rises_with_amplitude", Kind::RisesWith}, {"cycles_order", Kind::CyclesOrder}, {"negative_cycles", Kind::NegativeCycles}};
            const auto found = std::find_if(kinds.begin(), kinds.end(), [&](const auto& kv) { return kv.first == kind; });
            if (found == kinds.end()) claim.Fail("expected one of peaks, rises_with_amplitude, cycles_order, negative_cycles, got " + Quote(kind), "kind");
            c.kind = found->second;
            c.source = claim.String("source", "");
            if (c.source.empty()) claim.Fail("missing (required): the thesis's words the claim reads", "source");
            auto numbers = [&](const Json& list, const std::string& key) {
                std::vector<double> values;
                if (!list.is_array()) claim.Fail("expected a list of numbers", key);
                for (const auto& v : list) values.push_back(claim.NumberValue(v, key, -1e6, 1e6));
                return values;
            };
            switch (c.kind) {
                case Kind::Peaks: claim.Integer("count", c.count, 1, 1000); break;
                case Kind::RisesWith: break;
                case Kind::CyclesOrder: {
                    for (const auto& rank : claim.Array("ranks", 2, 100, "a list of lists of cycle counts, best first")) c.ranks.push_back(numbers(rank, "ranks"));
                    if (claim.Has("nearly"))
                        for (const auto& pair : claim.Array("nearly", 1, 100, "a list of [better, worse] pairs of cycle counts")) {
                            const auto two = numbers(pair, "nearly");
                            if (two.size() != 2) claim.Fail("expected pairs of two cycle counts", "nearly");
                            c.nearly.push_back({two[0], two[1]});
                        }
                    break;
                }
                case Kind::NegativeCycles: c.cycles = numbers(claim.Array("cycles", 0, 100, "a list of cycle counts"), "cycles"); break;
            }
            claim.Finish();
            t.claims.push_back(std::move(c));
        }
    }
    result.Number("minutes", t.minutes, 0, 1e6);
    result.Number("seconds_per_simulation", t.secondsPerSimulation, 0, 1e6);
    if (result.Has("specimens")) {
        const Json& specimens = result.Array("specimens", 0, 100, "a list of designs");
        for (size_t k = 0; k < specimens.size(); ++k) {
            ObjectReader specimen(specimens[k], result.Child("specimens") + "[" + std::to_string(k) + "]", result.Origin());
            ThesisResult::Specimen s;
            specimen.Integer("run", s.run, 1, 100);
            specimen.Integer("length", s.length, 1, 100000);
            s.design = ParseListedShape(specimen, k, mesh);
            const size_t genes = ControlPointCount(s.design.shape);
            if (s.length && genes != static_cast<size_t>(s.length))
                specimen.Fail(fmt::format("{} control points, but the table's length column says {}", genes, s.length), "control_points");
            t.specimens.push_back(std::move(s));
        }
    }
    result.Finish();
}

std::vector<ThesisItem> ParseThesisItems(ObjectReader& top) {
    std::vector<ThesisItem> items;
    const Json& list = top.Array("thesis_items", 0, 1000, "a list of {\"item\": ..., \"quantity\": ...}");
    for (size_t k = 0; k < list.size(); ++k) {
        ObjectReader entry(list[k], top.Child("thesis_items") + "[" + std::to_string(k) + "]", top.Origin());
        ThesisItem item;
        item.item = entry.String("item", "");
        if (item.item.empty()) entry.Fail("missing (required): the thesis table or figure, e.g. \"Figure 4.1\"", "item");
        item.settings = entry.String("settings", "");
        item.quantity = entry.String("quantity", "");
        if (item.quantity.empty() == item.settings.empty()) entry.Fail("give either 'quantity' (our number it is compared with) or 'settings'");
        item.claim = entry.String("claim", item.quantity);
        entry.Number("thesis", item.thesis, -1e6, 1e6);
        entry.Number("tolerance", item.tolerance, 0, 1e6);
        entry.Bool("at_least", item.atLeast);
        item.figure = entry.String("figure", "");
        item.reading = entry.String("reading", "");
        if (entry.Has("also")) {
            const Json& also = entry.Array("also", 1, 20, "a list of {\"item\": \"Figure 4.2\", \"figure\": \"best_inflation.png\"}");
            for (size_t j = 0; j < also.size(); ++j) {
                ObjectReader other(also[j], entry.Child("also") + "[" + std::to_string(j) + "]", entry.Origin());
                ThesisItem::Also a{other.String("item", ""), other.String("figure", "")};
                if (a.item.empty()) other.Fail("missing (required): the thesis figure that shows the same numbers, e.g. \"Figure 4.2\"", "item");
                other.Finish();
                item.also.push_back(std::move(a));
            }
        }
        entry.Finish();
        items.push_back(std::move(item));
    }
    return items;
}

}  // namespace

size_t ControlPointCount(const sim::Shape& shape) {
    size_t genes = 0;
    if (const auto* b = std::get_if<sim::BSplineShape>(&shape))
        for (const auto& spline : b->splines) genes += spline.size();
    return genes;
}

Override ParseOverride(const std::string& text) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        throw UsageError("--set: expected KEY.PATH=VALUE, e.g. evolve.generations=5 or sim.pressure_scale=0.01, got " + Quote(text));
    return {text.substr(0, eq), text.substr(eq + 1)};
}

// A model's "material": {"file": "mix.json", ...} is replaced by the file's keys (with the others given
// over them), so that the experiment kept with its results, its hash and its resume stand on their own.
// The path is relative to the experiment file's folder.
void InlineMaterialFile(Json& root, const std::string& path) {
    if (!root.is_object() || !root.contains("model") || !root["model"].is_object()) return;
    Json& model = root["model"];
    if (!model.contains("material") || !model["material"].is_object() || !model["material"].contains("file")) return;
    Json& block = model["material"];
    const std::string where = path + ": 'model.material.file': ";
    if (!block["file"].is_string()) throw UsageError(where + "expected the name of a material file, got " + Quote(block["file"].dump()));
    if (block.contains("preset")) throw UsageError(where + "give a preset or a material file, not both");
    std::filesystem::path file = block["file"].get<std::string>();
    if (file.is_relative()) file = std::filesystem::path(path).parent_path() / file;
    sim::MaterialDef material;
    try {
        material = ReadMaterialFile(file.string()).material;
    } catch (const UsageError& error) {
        throw UsageError(where + error.what());
    }
    Json inlined = MaterialFieldsJson(material);
    Json result = Json::object();
    result["preset"] = "custom";
    for (const auto& [key, value] : inlined.items()) result[key] = value;
    for (const auto& [key, value] : block.items())
        if (key != "file") result[key] = value;
    block = result;
}

Experiment ParseExperiment(const std::string& text, const std::string& path, const std::vector<Override>& overrides) {
    Json root;
    try {
        root = ParseJson(text, path);
    } catch (const Json::parse_error& error) {
        std::string what = error.what();
        if (auto colon = what.find("syntax error"); colon != std::string::npos) what = what.substr(colon);
        throw UsageError(path + ": not valid JSON at " + ParseErrorWhere(text, error.byte ? error.byte - 1 : 0) + " (" + what + ")");
    } catch (const Json::exception& error) {
        // nlohmann names the number that overflowed ("parsing '1e400'"): find it to say where.
        std::string what = error.what();
        const size_t open = what.find("parsing '");
        if (open != std::string::npos) {
            const std::string token = what.substr(open + 9, what.find('\'', open + 9) - open - 9);
            const size_t at = text.find(token);
            if (at != std::string::npos) throw UsageError(path + ": at " + ParseErrorWhere(text, at) + ": the number " + Quote(token) + " is too large");
        }
        throw UsageError(path + ": not valid JSON (" + what + ")");
    }
    for (const auto& o : overrides) Apply(root, o, path);
    InlineMaterialFile(root, path);
    Source source{path, &overrides};

    Experiment e;
    e.path = path;
    e.document = root;
    ObjectReader top(root, "", source);
    e.id = top.String("id", "");
    e.title = top.String("title", "");
    e.thesis = top.String("thesis", "");
    e.note = top.String("note", "");
    e.explanation = top.String("explanation", "");
    e.compare = top.String("compare", "");
    top.Integer("seed", e.seed, 0, (1ll << 53));
    for (const char* moved : {"iterations", "load", "precision"}) top.Moved(moved, std::string("\"sim\": {\"") + moved + "\": ...}");
    if (top.Has("model")) ParseModel(top.Object("model"), e);
    const bool thesisModel = e.model == sim::ModelKind::Thesis;
    for (const char* thesisOnly : {"sim", "mesh"})
        if (!thesisModel && top.Has(thesisOnly))
            top.Fail(top.Has("model") ? std::string("applies to the thesis model only; the ") + sim::Name(e.model) + " model's settings go in the 'model' block"
                                      : std::string("applies to the thesis model only: name it with \"model\": {\"name\": \"thesis\"} (without a 'model' block "
                                                    "an experiment is under the ") + sim::Name(e.model) + " model)",
                     thesisOnly);
    if (top.Has("sim")) {  // the thesis model's (refused above for the others)
        sim::SimParams& params = std::get<sim::ThesisDef>(e.def).params;
        ObjectReader sim = top.Object("sim");
        sim.Fields(params);
        sim.Finish();
        if (const std::string error = sim::SimParamsError(params); !error.empty()) sim.Fail(error);
    }
    if (top.Has("mesh")) {
        sim::MeshDef& helix = std::get<sim::ThesisDef>(e.def).mesh;
        ObjectReader mesh = top.Object("mesh");
        mesh.Fields(helix);
        mesh.Finish();
        if (static_cast<long long>(helix.resolution) * helix.turns > sim::kMaxVertices)
            mesh.Fail("more than " + std::to_string(sim::kMaxVertices) + " vertices");
    }
    // Listed shapes are checked on the thesis helix (the shell models check theirs on their rings).
    const sim::MeshDef shapeMesh = thesisModel ? std::get<sim::ThesisDef>(e.def).mesh : sim::DefaultMeshDef();
    if (top.Has("thesis_result")) ParseThesisResult(top.Object("thesis_result"), e.thesisResult, shapeMesh);
    if (top.Has("thesis_items")) e.thesisItems = ParseThesisItems(top);

    const int kinds = top.Has("sweep") + top.Has("evolve") + top.Has("evaluate") + top.Has("optimizer");
    if (kinds != 1) top.Fail("needs exactly one of 'sweep', 'evolve', 'optimizer' or 'evaluate'");
    e.kind = top.Has("sweep")       ? ExperimentKind::Sweep
             : top.Has("evolve")    ? ExperimentKind::Evolve
             : top.Has("optimizer") ? ExperimentKind::Optimize
                                    : ExperimentKind::Evaluate;
    top.Moved("shape", "\"sweep\": {\"shape\": ...}");
    switch (e.kind) {
        case ExperimentKind::Evaluate: {
            ObjectReader evaluate = top.Object("evaluate");
            const Json& shapes = evaluate.Array("shapes", 1, 1000, "a list of 1 to 1000 shapes");
            for (size_t k = 0; k < shapes.size(); ++k)
                e.shapes.push_back(ParseListedShape(ObjectReader(shapes[k], evaluate.Child("shapes") + "[" + std::to_string(k) + "]", source), k, shapeMesh));
            if (!thesisModel)
                for (const auto& shape : e.shapes)
                    if (const std::string error = sim::JobError(JobOf(e, shape.shape)); !error.empty()) evaluate.Fail(error);
            evaluate.Finish();
            break;
        }
        case ExperimentKind::Sweep: {
            ObjectReader sweep = top.Object("sweep");
            e.sweep.base = ParseSineBase(sweep.Object("shape"));
            const Json& axes = sweep.Array("axes", 1, 2, "a list of one or two axes");
            const sim::FibreLayout fibreLayout = std::visit([](const auto& def) { return FibresOn(def).layout; }, e.def);
            for (size_t k = 0; k < axes.size(); ++k) {
                e.sweep.axes.push_back(ParseAxis(ObjectReader(axes[k], sweep.Child("axes") + "[" + std::to_string(k) + "]", source)));
                const sim::SweepParameter parameter = e.sweep.axes.back().parameter;
                if (thesisModel && parameter == sim::SweepParameter::PressureKpa)
                    sweep.Fail("a pressure_kpa axis needs a membrane or shell model (\"model\": {\"name\": \"shell\"}); the thesis model has no pressure in kPa", "axes");
                if (parameter == sim::SweepParameter::FibreAngleDeg && (fibreLayout == sim::FibreLayout::None ||
                                                                         fibreLayout == sim::FibreLayout::Meridian ||
                                                                         fibreLayout == sim::FibreLayout::Hoop))
                    sweep.Fail("a fibre_angle_deg axis needs fibres at an angle: a membrane or shell model with \"fibres\": \"braid\" or \"single\"", "axes");
                for (double v : e.sweep.axes.back().values)
                    if (parameter == sim::SweepParameter::FibreAngleDeg && !(v >= -90 && v <= 90)) sweep.Fail("fibre angles lie from -90 to 90 degrees", "axes");
            }
            if (e.sweep.axes.size() == 2 && e.sweep.axes[0].parameter == e.sweep.axes[1].parameter) sweep.Fail("the two axes vary the same parameter", "axes");
            sweep.Finish();
            size_t points = 1;
            for (const auto& axis : e.sweep.axes) points *= axis.values.size();
            if (points > 100000) top.Fail("the grid has " + std::to_string(points) + " points; at most 100000", "sweep");
            break;
        }
        case ExperimentKind::Evolve: ParseGa(top.Object("evolve"), e); break;
        case ExperimentKind::Optimize: ParseOptimizer(top.Object("optimizer"), e); break;
    }
    RefuseReplacedKeys(e);
    if (top.Has("render")) {
        ObjectReader render = top.Object("render");
        render.Bool("figures", e.render.figures);
        render.Bool("thumbnails", e.render.thumbnails);
        render.Enum("turntable", e.render.turntable);
        render.Integer("turntable_frames", e.render.turntableFrames, 1, 3600);
        render.Finish();
    }
    top.Finish();
    return e;
}

Experiment LoadExperiment(const std::string& given, const std::vector<Override>& overrides) {
    const std::string path = FindExperimentFile(given).string();
    return ParseExperiment(ReadInputFile(path, 64ull << 20), path, overrides);
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Saved experiments, hashes, titles
// ---------------------------------------------------------------------------------------------

std::string ExperimentText(const Experiment& e) { return e.document.dump(2) + "\n"; }

std::string ExperimentHash(const Experiment& e) {
    std::uint64_t hash = 1469598103934665603ull;
    for (unsigned char c : e.document.dump()) {
        hash ^= c;
        hash *= 1099511628211ull;
    }
    return fmt::format("{:016x}", hash);
}

std::string ExperimentDifference(const nlohmann::ordered_json& before, const nlohmann::ordered_json& after) {
    const nlohmann::json patch = nlohmann::json::diff(nlohmann::json(before), nlohmann::json(after));
    std::string text;
    int shown = 0;
    for (const auto& op : patch) {
        if (shown == 3) {
            text += ", and " + std::to_string(patch.size() - 3) + " more";
            break;
        }
        std::string key = op.at("path").get<std::string>().substr(1);
        for (char& c : key)
            if (c == '/') c = '.';
        const nlohmann::json::json_pointer pointer(op.at("path").get<std::string>());
        const std::string old = before.contains(pointer) ? Shown(before.at(pointer)) : std::string("(none)");
        const std::string now = op.contains("value") ? Shown(op.at("value")) : std::string("(none)");
        text += (text.empty() ? "" : ", ") + key + ": " + old + " -> " + now;
        ++shown;
    }
    return text;
}

std::string ExperimentTitle(const Experiment& e) {
    std::string title = e.id.empty() ? std::filesystem::path(e.path).stem().string() : e.id;
    if (!e.title.empty()) title += "  " + e.title;
    return title;
}

PlotContext PlotContextOf(const Experiment& e) {
    PlotContext c;
    c.title = ExperimentTitle(e);
    const bool thesis = !sim::ModelOf(e.model).physical;  // fitness in mesh units, after a count of iterations
    if (e.kind == ExperimentKind::Optimize) {
        const sim::Objective& o = e.optimizer.objectives[0];
        c.fitnessLabel = fmt::format("{} ({})", sim::ObjectiveUnit(o.kind), o.maximise ? "maximised" : "minimised");
    } else {
        c.fitnessLabel = thesis ? "fitness (contraction, mesh units)" : "fitness: contraction (percent, positive = shorter)";
    }
    c.valueLabel = thesis ? "fitness" : "contraction (%)";
    c.seriesLabel = thesis ? "fitness after " + std::to_string(std::get<sim::ThesisDef>(e.def).params.iterations) + " iterations"
                           : std::string("contraction at equilibrium, ") + sim::Name(e.model) + " model";
    c.axes = e.sweep.axes;
    for (const auto& point : e.thesisResult.points) c.thesisPoints.push_back({point.at, point.fitness});
    c.objectives = e.optimizer.objectives;
    return c;
}

sim::EvalJob JobOf(const Experiment& e, const sim::Shape& shape) {
    sim::EvalJob job;
    job.shape = shape;
    job.model = e.model;
    job.def = e.def;
    return job;
}

sim::EvalJob JobOfGenome(const Experiment& e, const sim::Genome& genome) {
    sim::EvalJob job = JobOf(e, sim::Shape{});  // its def once: the design mesh is read from it
    job.shape = sim::ShapeOfGenome(genome, e.ga.genome, sim::DesignMeshOf(job));
    if (e.ga.genome.HasFibreGenes()) job.Shell().fibres = sim::FibresOfGenome(genome, e.ga.genome, job.Shell().fibres);
    return job;
}

sim::Genome GenomeOfJob(const Experiment& e, const sim::EvalJob& job) {
    return sim::GenomeOfDesign(job.shape, std::visit([](const auto& def) { return FibresOn(def); }, job.def), e.ga.genome);
}

sim::MeshDef DesignMesh(const Experiment& e) { return sim::DesignMeshOf(JobOf(e, sim::Shape{})); }

Experiment QuickVersion(const Experiment& experiment) {
    // Shrunk through the document, so that the saved experiment re-reads as what ran (a resume).
    Json document = experiment.document;
    std::visit([&](const auto& def) { ShrinkForQuick(document, def); }, experiment.def);
    for (size_t k = 0; k < experiment.sweep.axes.size(); ++k) {
        const auto& values = experiment.sweep.axes[k].values;
        if (values.size() <= 3) continue;
        document["sweep"]["axes"][k] = Json{{"parameter", sim::Name(experiment.sweep.axes[k].parameter)},
                                            {"values", {values.front(), values[values.size() / 2], values.back()}}};
    }
    if (experiment.kind == ExperimentKind::Evolve) {
        Json& evolve = document["evolve"];
        evolve["runs"] = 1;
        evolve["population"] = std::min(experiment.ga.population, 6);
        evolve["elite"] = std::min(experiment.ga.elite, 1);
        evolve["generations"] = std::min(experiment.ga.generations, 2);
    }
    if (experiment.kind == ExperimentKind::Optimize) {
        Json& optimizer = document["optimizer"];
        optimizer["runs"] = 1;
        optimizer["generations"] = std::min(experiment.optimizer.generations, 2);
    }
    if (document.contains("render")) document["render"]["turntable_frames"] = std::min(experiment.render.turntableFrames, 4);
    return ParseExperiment(document.dump(), experiment.path);
}

}  // namespace app
