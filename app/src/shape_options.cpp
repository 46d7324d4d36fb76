#include "shape_options.h"

#include <numbers>
#include <sstream>

#include "mesh_io.h"

namespace app {
namespace {

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};

// Control points: splines separated by ';', points by ','. "8,8,0,4" is one spline.
std::vector<std::vector<double>> ParseControlPoints(const std::string& text) {
    std::vector<std::vector<double>> splines;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, ';')) splines.push_back(ParseNumberList(part, "--control-points"));
    if (splines.empty() || (!text.empty() && text.back() == ';'))
        throw UsageError("--control-points: expected lists like \"8,8,0,4\" or \"4,6,2,5;2,3,7,4\", got '" + text + "'");
    return splines;
}

// Which options belong to which shape, so that a misplaced option is an error, not silently ignored.
void RefuseOptionsNotFor(const ParsedArgs& args, const std::string& shape, const std::vector<std::string>& allowed) {
    for (const char* option : {"amplitude", "phase", "region", "control-points", "offsets"}) {
        if (!args.Has(option)) continue;
        bool ok = false;
        for (const auto& a : allowed) ok = ok || a == option;
        if (!ok) throw UsageError("--" + std::string(option) + " does not apply to --shape " + shape);
    }
}

}  // namespace

std::vector<OptionSpec> ShapeOptionSpecs() {
    return {
        {"shape", "NAME", "cylinder", "cylinder, sine, abs-sine, bspline, free-xy or mesh"},
        {"amplitude", "A", "4.1 for sine, 4 for abs-sine", "sine amplitude: rho = A*sin(phase) (mesh units; base radius 1)"},
        {"phase", "START,END", "0.5,pi-0.5 for sine; 0,4pi for abs-sine",
         "phase range in radians from bottom to top vertex; numbers may use pi and + - * /, e.g. 0,4pi or 0.5,pi-0.5"},
        {"region", "entire|middle", "middle", "bspline: span all vertices, or leave the two clamped turns at each end at radius 1"},
        {"control-points", "LIST", "",
         "bspline control points (radius multipliers), ',' between points and ';' between the 1, 2 or 4 sector "
         "splines, at least 4 each: \"8,8,0,4,0,0,2\" or \"4,6,2,5;2,3,7,4,6;5,5,1,2;3,3,3,3\""},
        {"offsets", "FILE", "", "free-xy: file of 'dx dy' per vertex (2*R*H numbers), added to the bare helix"},
        {"mesh", "FILE", "", "start from an OBJ file's vertices in helix order (as written by --save-mesh); implies --shape mesh"},
        {"resolution", "R", "30", "vertices per turn of the helix"},
        {"turns", "H", "30", "turns of the helix (at least 5: two clamped at each end)"},
    };
}

std::vector<OptionSpec> SimulationOptionSpecs() {
    const sim::SimParams d = sim::DefaultSimParams();
    auto str = [](double v) { std::ostringstream o; o << v; return o.str(); };
    return {
        {"load", "inflate|stretch|none", "inflate", "inflation pressure, the stretch test's pull on the end turns, or no load"},
        {"iterations", "N", std::to_string(d.iterations), "relaxation steps; the fitness is read after the last"},
        {"precision", "float|double", "float", "solver arithmetic; float is faster and within 0.005 of double in fitness"},
        {"spring-constant", "K", str(d.springConstant), "spring stiffness k"},
        {"pressure", "C", str(d.pressureScale), "inflation scale c_p on the cross-product force"},
        {"pull-force", "F", str(d.pullForce), "stretch load on each end-turn vertex"},
        {"step", "S", str(d.stepScale), "displacement per unit force per iteration"},
        {"divergence-limit", "L", str(d.divergenceLimit), "a coordinate beyond this ends the run with status 'diverged'"},
    };
}

EvaluationRequest ParseEvaluationRequest(const ParsedArgs& args) {
    EvaluationRequest request;
    request.mesh.resolution = args.Has("resolution") ? ParseInt(args.Get("resolution"), "--resolution", sim::kMinResolution, 4096) : 30;
    request.mesh.turns = args.Has("turns") ? ParseInt(args.Get("turns"), "--turns", sim::kMinTurns, 4096) : 30;
    if (static_cast<long long>(request.mesh.resolution) * request.mesh.turns > sim::kMaxVertices)
        throw UsageError("--resolution x --turns: more than " + std::to_string(sim::kMaxVertices) + " vertices");

    std::string shapeName = args.Has("shape") ? args.Get("shape") : (args.Has("mesh") ? "mesh" : "cylinder");
    shapeName = ParseChoice(shapeName, "--shape", {"cylinder", "sine", "abs-sine", "bspline", "free-xy", "mesh"});
    if (args.Has("mesh") && shapeName != "mesh") throw UsageError("--mesh gives the shape itself; drop --shape " + shapeName);

    if (shapeName == "cylinder") {
        RefuseOptionsNotFor(args, shapeName, {});
        request.shape = sim::CylinderShape{};
    } else if (shapeName == "sine" || shapeName == "abs-sine") {
        RefuseOptionsNotFor(args, shapeName, {"amplitude", "phase"});
        const bool absolute = shapeName == "abs-sine";
        double amplitude = absolute ? 4.0 : 4.1;
        double a = absolute ? 0.0 : 0.5, b = absolute ? 4 * std::numbers::pi : std::numbers::pi - 0.5;
        if (args.Has("amplitude")) amplitude = ParseNumber(args.Get("amplitude"), "--amplitude");
        if (args.Has("phase")) {
            const auto phase = ParseNumberList(args.Get("phase"), "--phase");
            if (phase.size() != 2) throw UsageError("--phase: expected START,END (two numbers), got '" + args.Get("phase") + "'");
            a = phase[0];
            b = phase[1];
        }
        if (absolute) request.shape = sim::AbsSineShape{amplitude, a, b};
        else request.shape = sim::SineShape{amplitude, a, b};
    } else if (shapeName == "bspline") {
        RefuseOptionsNotFor(args, shapeName, {"region", "control-points"});
        if (!args.Has("control-points")) throw UsageError("--shape bspline needs --control-points, e.g. \"8,8,0,4,0,0,2\"");
        sim::BSplineShape s;
        if (args.Has("region"))
            s.region = ParseChoice(args.Get("region"), "--region", {"entire", "middle"}) == "entire" ? sim::SplineRegion::Entire
                                                                                                 : sim::SplineRegion::Middle;
        s.splines = ParseControlPoints(args.Get("control-points"));
        for (size_t k = 0; k < s.splines.size(); ++k)
            if (s.splines[k].size() < 4)
                throw UsageError("--control-points: spline " + std::to_string(k + 1) + " has " +
                                 std::to_string(s.splines[k].size()) + " points; a cubic B-spline needs at least 4");
        request.shape = s;
    } else if (shapeName == "free-xy") {
        RefuseOptionsNotFor(args, shapeName, {"offsets"});
        if (!args.Has("offsets")) throw UsageError("--shape free-xy needs --offsets FILE ('dx dy' per vertex)");
        const auto numbers = ReadNumberFile(args.Get("offsets"));
        const size_t n = sim::VertexCount(request.mesh);
        if (numbers.size() != 2 * n)
            throw UsageError("--offsets: '" + args.Get("offsets") + "' has " + std::to_string(numbers.size()) +
                             " numbers, expected " + std::to_string(2 * n) + " (dx dy for each of " + std::to_string(n) + " vertices)");
        sim::FreeXYShape s;
        for (size_t i = 0; i < n; ++i) {
            s.dx.push_back(numbers[2 * i]);
            s.dy.push_back(numbers[2 * i + 1]);
        }
        request.shape = s;
    } else {
        RefuseOptionsNotFor(args, shapeName, {});
        if (!args.Has("mesh")) throw UsageError("--shape mesh needs --mesh FILE");
        request.shape = sim::MeshShape{ReadObjVertices(args.Get("mesh"))};
    }
    if (const std::string error = sim::ShapeError(request.shape, request.mesh); !error.empty()) {
        const std::string source = args.Has("mesh") ? "--mesh '" + args.Get("mesh") + "': " : "--shape " + shapeName + ": ";
        throw UsageError(source + error);
    }

    sim::SimParams& p = request.params;
    if (args.Has("load")) {
        const auto load = ParseChoice(args.Get("load"), "--load", {"inflate", "stretch", "none"});
        p.load = load == "inflate" ? sim::Load::Inflate : load == "stretch" ? sim::Load::Stretch : sim::Load::None;
    }
    if (args.Has("iterations")) p.iterations = ParseInt(args.Get("iterations"), "--iterations", 0, 100'000'000);
    if (args.Has("precision"))
        p.precision = ParseChoice(args.Get("precision"), "--precision", {"float", "double"}) == "float" ? sim::Precision::Float
                                                                                                     : sim::Precision::Double;
    auto positive = [&](const char* name, double& field) {
        if (!args.Has(name)) return;
        field = ParseNumber(args.Get(name), std::string("--") + name);
        if (field < 0) throw UsageError(std::string("--") + name + ": must not be negative, got " + args.Get(name));
    };
    positive("spring-constant", p.springConstant);
    positive("pressure", p.pressureScale);
    positive("pull-force", p.pullForce);
    positive("step", p.stepScale);
    positive("divergence-limit", p.divergenceLimit);
    if (args.Has("divergence-limit") && p.divergenceLimit == 0) throw UsageError("--divergence-limit: must be positive");
    return request;
}

void WriteShapeJson(JsonWriter& json, const sim::Shape& shape) {
    json.BeginObject().Key("name").String(sim::ShapeName(shape));
    std::visit(Overloaded{
                   [](const sim::CylinderShape&) {},
                   [&](const sim::SineShape& s) {
                       json.Key("amplitude").Number(s.amplitude).Key("phase").NumberArray({s.phaseStart, s.phaseEnd});
                   },
                   [&](const sim::AbsSineShape& s) {
                       json.Key("amplitude").Number(s.amplitude).Key("phase").NumberArray({s.phaseStart, s.phaseEnd});
                   },
                   [&](const sim::BSplineShape& s) {
                       json.Key("region").String(s.region == sim::SplineRegion::Entire ? "entire" : "middle");
                       json.Key("splines").BeginArray();
                       for (const auto& spline : s.splines) json.NumberArray(spline);
                       json.EndArray();
                   },
                   [](const sim::FreeXYShape&) {},
                   [](const sim::MeshShape&) {},
               },
               shape);
    json.EndObject();
}

}  // namespace app
