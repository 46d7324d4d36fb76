#include "experiment.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_options.h"
#include "mesh_io.h"
#include <filesystem>

namespace app {
namespace {

using nlohmann::json;

// Reads one JSON object, remembering its key path for messages and which keys were used, so that
// anything left over (a typo, a key from another optimizer) is reported instead of ignored.
class ObjectReader {
public:
    ObjectReader(const json& object, std::string path, const std::string& file) : object_(object), path_(std::move(path)), file_(file) {
        if (!object_.is_object()) Fail(path_.empty() ? "the file must hold a JSON object" : "expected an object");
    }

    bool Has(const std::string& key) const { return object_.contains(key); }

    [[noreturn]] void Fail(const std::string& reason, const std::string& key = "") const {
        const std::string where = path_.empty() ? key : (key.empty() ? path_ : path_ + "." + key);
        throw UsageError(file_ + ": " + (where.empty() ? "" : "'" + where + "': ") + reason);
    }

    const json& Get(const std::string& key) {
        used_.insert(key);
        if (!object_.contains(key)) Fail("missing (required)", key);
        return object_.at(key);
    }

    // Numbers may be JSON numbers or strings with pi and arithmetic ("pi-0.5").
    double Number(const std::string& key, std::optional<double> fallback, double min = -1e300, double max = 1e300) {
        if (!Has(key) && fallback) { used_.insert(key); return *fallback; }
        return NumberValue(Get(key), key, min, max);
    }

    double NumberValue(const json& value, const std::string& key, double min, double max) const {
        double number;
        if (value.is_number()) number = value.get<double>();
        else if (value.is_string()) {
            try { number = ParseNumber(value.get<std::string>(), "x"); }
            catch (const UsageError&) { Fail("'" + value.get<std::string>() + "' is not a number", key); }
        } else Fail("expected a number, got " + std::string(value.type_name()), key);
        if (!(number >= min && number <= max)) {
            std::ostringstream range;
            range << "out of range: " << number << " (allowed " << min << " to " << max << ")";
            Fail(range.str(), key);
        }
        return number;
    }

    long long Integer(const std::string& key, std::optional<long long> fallback, long long min, long long max) {
        if (!Has(key) && fallback) { used_.insert(key); return *fallback; }
        const json& value = Get(key);
        if (!value.is_number_integer() && !value.is_number_unsigned()) Fail("expected a whole number, got " + value.dump(), key);
        const long long number = value.is_number_unsigned() && value.get<unsigned long long>() > 9e18 ? max + 1 : value.get<long long>();
        if (number < min || number > max)
            Fail("out of range: " + std::to_string(number) + " (allowed " + std::to_string(min) + " to " + std::to_string(max) + ")", key);
        return number;
    }

    std::string String(const std::string& key, std::optional<std::string> fallback) {
        if (!Has(key) && fallback) { used_.insert(key); return *fallback; }
        const json& value = Get(key);
        if (!value.is_string()) Fail("expected a string, got " + std::string(value.type_name()), key);
        return value.get<std::string>();
    }

    std::string Choice(const std::string& key, std::optional<std::string> fallback, const std::vector<std::string>& choices) {
        const std::string value = String(key, fallback);
        for (const auto& c : choices) if (c == value) return value;
        std::string list;
        for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
        Fail("unknown value '" + value + "' (choose from " + list + ")", key);
    }

    bool Bool(const std::string& key, bool fallback) {
        if (!Has(key)) { used_.insert(key); return fallback; }
        const json& value = Get(key);
        if (!value.is_boolean()) Fail("expected true or false", key);
        return value.get<bool>();
    }

    ObjectReader Object(const std::string& key) { return ObjectReader(Get(key), Child(key), file_); }

    std::pair<double, double> Range(const std::string& key, std::optional<std::pair<double, double>> fallback, double min, double max) {
        if (!Has(key) && fallback) { used_.insert(key); return *fallback; }
        const json& value = Get(key);
        if (!value.is_array() || value.size() != 2) Fail("expected [low, high]", key);
        const double low = NumberValue(value[0], key, min, max), high = NumberValue(value[1], key, min, max);
        if (low > high) Fail("low end above high end", key);
        return {low, high};
    }

    std::string Child(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
    const std::string& File() const { return file_; }

    void Finish() const {
        for (const auto& [key, value] : object_.items())
            if (!used_.count(key)) Fail("unknown key (check its spelling and section)", key);
    }

private:
    const json& object_;
    std::string path_;
    const std::string& file_;
    std::set<std::string> used_;
};

sim::SweepAxis ParseAxis(ObjectReader axis) {
    sim::SweepAxis a;
    const std::string parameter = axis.Choice("parameter", std::nullopt, {"amplitude", "cycles", "phase_end"});
    a.parameter = parameter == "amplitude" ? sim::SweepParameter::Amplitude
                  : parameter == "cycles"  ? sim::SweepParameter::Cycles
                                           : sim::SweepParameter::PhaseEnd;
    if (axis.Has("values")) {
        const auto& values = axis.Get("values");
        if (!values.is_array() || values.empty() || values.size() > 10000) axis.Fail("expected a list of 1 to 10000 numbers", "values");
        for (const auto& v : values) a.values.push_back(axis.NumberValue(v, "values", -1e6, 1e6));
    } else {
        const double from = axis.Number("from", std::nullopt, -1e6, 1e6), to = axis.Number("to", std::nullopt, -1e6, 1e6);
        const int points = static_cast<int>(axis.Integer("points", std::nullopt, 1, 10000));
        a.values = sim::Linspace(from, to, points);
    }
    axis.Finish();
    return a;
}

}  // namespace

Experiment ParseExperiment(const std::string& text, const std::string& path) {
    json root;
    try {
        root = json::parse(text);
    } catch (const json::parse_error& error) {
        throw UsageError(path + ": not valid JSON (" + std::string(error.what()) + ")");
    }
    Experiment e;
    e.path = path;
    e.text = text;
    ObjectReader top(root, "", path);
    e.id = top.String("id", std::string(""));
    e.title = top.String("title", std::string(""));
    e.thesis = top.String("thesis", std::string(""));
    e.note = top.String("note", std::string(""));
    e.explanation = top.String("explanation", std::string(""));
    if (top.Has("thesis_result")) {
        ObjectReader result = top.Object("thesis_result");
        auto parameters = [&](ObjectReader& object, std::vector<std::pair<std::string, double>>& into) {
            for (const char* name : {"amplitude", "cycles", "phase_end"})
                if (object.Has(name)) into.push_back({name, object.Number(name, std::nullopt, -1e6, 1e6)});
        };
        e.thesisResult.bestFitness = result.Number("best_fitness", NAN, -1e6, 1e6);
        if (result.Has("best")) {
            ObjectReader best = result.Object("best");
            parameters(best, e.thesisResult.best);
            best.Finish();
        }
        if (result.Has("points")) {
            const json& points = result.Get("points");
            if (!points.is_array()) result.Fail("expected a list of points", "points");
            for (size_t k = 0; k < points.size(); ++k) {
                ObjectReader point(points[k], result.Child("points[" + std::to_string(k) + "]"), path);
                ThesisResult::Point p;
                parameters(point, p.at);
                p.fitness = point.Number("fitness", std::nullopt, -1e6, 1e6);
                point.Finish();
                e.thesisResult.points.push_back(p);
            }
        }
        if (result.Has("run_best")) {
            const json& runs = result.Get("run_best");
            if (!runs.is_array()) result.Fail("expected a list of numbers", "run_best");
            for (const auto& v : runs) e.thesisResult.runBest.push_back(result.NumberValue(v, "run_best", -1e6, 1e6));
        }
        result.Finish();
    }
    e.seed = static_cast<std::uint64_t>(top.Integer("seed", 1, 0, (1ll << 53)));
    e.params.iterations = static_cast<int>(top.Integer("iterations", 10000, 1, 10'000'000));
    const std::string load = top.Choice("load", std::string("inflate"), {"inflate", "stretch"});
    e.params.load = load == "inflate" ? sim::Load::Inflate : sim::Load::Stretch;
    e.params.precision = top.Choice("precision", std::string("float"), {"float", "double"}) == "float" ? sim::Precision::Float : sim::Precision::Double;
    if (top.Has("mesh")) {
        ObjectReader mesh = top.Object("mesh");
        e.mesh.resolution = static_cast<int>(mesh.Integer("resolution", 30, sim::kMinResolution, 1024));
        e.mesh.turns = static_cast<int>(mesh.Integer("turns", 30, sim::kMinTurns, 1024));
        mesh.Finish();
    }

    const int kinds = top.Has("sweep") + top.Has("evolve") + top.Has("evaluate");
    if (kinds != 1) top.Fail("needs exactly one of 'sweep', 'evolve' or 'evaluate'");
    e.kind = top.Has("sweep") ? ExperimentKind::Sweep : top.Has("evolve") ? ExperimentKind::Evolve : ExperimentKind::Evaluate;
    if (e.kind == ExperimentKind::Evaluate) {
        ObjectReader evaluate = top.Object("evaluate");
        const json& shapes = evaluate.Get("shapes");
        if (!shapes.is_array() || shapes.empty() || shapes.size() > 1000) evaluate.Fail("expected a list of 1 to 1000 shapes", "shapes");
        for (size_t k = 0; k < shapes.size(); ++k) {
            ObjectReader shape(shapes[k], evaluate.Child("shapes[" + std::to_string(k) + "]"), path);
            LabelledShape labelled;
            labelled.label = shape.String("label", "shape " + std::to_string(k + 1));
            labelled.thesisFitness = shape.Number("thesis_fitness", NAN, -1e6, 1e6);
            const std::string family = shape.Choice("family", std::nullopt, {"cylinder", "sine", "abs-sine", "bspline"});
            if (family == "sine" || family == "abs-sine") {
                const double amplitude = shape.Number("amplitude", std::nullopt, -1e3, 1e3);
                const auto phase = shape.Range("phase", std::nullopt, -1e4, 1e4);
                if (family == "sine") labelled.shape = sim::SineShape{amplitude, phase.first, phase.second};
                else labelled.shape = sim::AbsSineShape{amplitude, phase.first, phase.second};
            } else if (family == "bspline") {
                sim::BSplineShape b;
                b.region = shape.Choice("region", std::string("middle"), {"entire", "middle"}) == "entire" ? sim::SplineRegion::Entire : sim::SplineRegion::Middle;
                const json& splines = shape.Get("control_points");
                if (!splines.is_array() || splines.empty()) shape.Fail("expected a list of splines, each a list of numbers", "control_points");
                for (const auto& spline : splines) {
                    if (!spline.is_array()) shape.Fail("expected a list of splines, each a list of numbers", "control_points");
                    std::vector<double> points;
                    for (const auto& c : spline) points.push_back(shape.NumberValue(c, "control_points", -1e3, 1e3));
                    b.splines.push_back(points);
                }
                labelled.shape = b;
            } else {
                labelled.shape = sim::CylinderShape{};
            }
            shape.Finish();
            if (const std::string error = sim::ShapeError(labelled.shape, e.mesh); !error.empty()) shape.Fail(error);
            e.shapes.push_back(labelled);
        }
        evaluate.Finish();
    } else if (e.kind == ExperimentKind::Sweep) {
        ObjectReader shape = top.Object("shape");
        const std::string family = shape.Choice("family", std::nullopt, {"sine", "abs-sine"});
        const double amplitude = shape.Number("amplitude", 1.0, -1e3, 1e3);
        const auto phase = shape.Range("phase", std::pair{0.0, 3.141592653589793}, -1e4, 1e4);
        shape.Finish();
        if (family == "sine") e.sweep.base = sim::SineShape{amplitude, phase.first, phase.second};
        else e.sweep.base = sim::AbsSineShape{amplitude, phase.first, phase.second};
        ObjectReader sweep = top.Object("sweep");
        const json& axes = sweep.Get("axes");
        if (!axes.is_array() || axes.empty() || axes.size() > 2) sweep.Fail("expected a list of one or two axes", "axes");
        for (size_t k = 0; k < axes.size(); ++k) e.sweep.axes.push_back(ParseAxis(ObjectReader(axes[k], sweep.Child("axes[" + std::to_string(k) + "]"), path)));
        sweep.Finish();
        size_t points = 1;
        for (const auto& axis : e.sweep.axes) points *= axis.values.size();
        if (points > 100000) top.Fail("the grid has " + std::to_string(points) + " points; at most 100000", "sweep");
    } else {
        ObjectReader evolve = top.Object("evolve");
        sim::GaDef& ga = e.ga;
        e.runs = static_cast<int>(evolve.Integer("runs", 1, 1, 100));
        ga.population = static_cast<int>(evolve.Integer("population", 30, 2, 100000));
        ga.generations = static_cast<int>(evolve.Integer("generations", 40, 0, 100000));
        ga.tournament = static_cast<int>(evolve.Integer("tournament", 3, 1, 1000));
        ga.elite = static_cast<int>(evolve.Integer("elite", 1, 0, ga.population - 1));
        ga.mutpb = evolve.Number("mutpb", 0.4, 0, 1);
        ga.indpb = evolve.Number("indpb", 0.2, 0, 1);
        ga.cxpb = evolve.Number("cxpb", 0.0, 0, 1);
        ObjectReader genome = evolve.Object("genome");
        const std::string kind = genome.Choice("kind", std::nullopt, {"bspline", "free-xy"});
        sim::GenomeDef& g = ga.genome;
        if (kind == "bspline") {
            g.kind = sim::GenomeKind::BSpline;
            g.region = genome.Choice("region", std::string("middle"), {"entire", "middle"}) == "entire" ? sim::SplineRegion::Entire : sim::SplineRegion::Middle;
            g.splines = static_cast<int>(genome.Integer("splines", 1, 1, 4));
            if (g.splines == 3) genome.Fail("must be 1, 2 or 4", "splines");
            const auto control = genome.Range("control", std::pair{0.0, 8.0}, -1000, 1000);
            g.controlMin = static_cast<int>(control.first);
            g.controlMax = static_cast<int>(control.second);
            if (g.controlMin != control.first || g.controlMax != control.second) genome.Fail("control points are whole numbers", "control");
            const auto length = genome.Range("length", std::pair{5.0, 16.0}, 4, 1000);
            g.lengthMin = static_cast<int>(length.first);
            g.lengthMax = static_cast<int>(length.second);
        } else {
            g.kind = sim::GenomeKind::FreeXY;
            g.initRange = genome.Number("init_range", 0.5, 0, 100);
            g.sigma = genome.Number("sigma", 0.2, 0, 100);
            g.bound = genome.Number("bound", 1.0, 1e-9, 100);
        }
        genome.Finish();
        evolve.Finish();
        if (const std::string error = sim::GaDefError(ga, e.mesh); !error.empty()) top.Fail(error, "evolve");
    }
    if (top.Has("render")) {
        ObjectReader render = top.Object("render");
        e.render.figures = render.Bool("figures", true);
        const std::string turntable = render.Choice("turntable", std::string("none"), {"none", "best", "all"});
        e.render.turntable = turntable == "none" ? TurntablePlan::None : turntable == "best" ? TurntablePlan::Best : TurntablePlan::All;
        e.render.turntableFrames = static_cast<int>(render.Integer("turntable_frames", 36, 1, 3600));
        render.Finish();
    }
    top.Finish();
    return e;
}

Experiment LoadExperiment(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw UsageError("cannot open experiment file '" + path + "'");
    return ParseExperiment(ReadTextFile(path), path);
}

}  // namespace app
