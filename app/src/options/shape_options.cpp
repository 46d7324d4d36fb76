#include "options/shape_options.h"

#include <filesystem>
#include <set>

#include "formats/files.h"
#include "options/model_options.h"
#include "formats/obj_io.h"

namespace app {
namespace {

// Which options each shape takes; the rest are refused when given.
std::vector<std::string> OptionsFor(sim::ShapeKind kind) {
    switch (kind) {
        case sim::ShapeKind::Sine:
        case sim::ShapeKind::AbsSine: return {"--amplitude", "--phase"};
        case sim::ShapeKind::BSpline: return {"--region", "--control-points"};
        case sim::ShapeKind::FreeXY: return {"--offsets"};
        case sim::ShapeKind::Mesh: return {"--mesh"};
        case sim::ShapeKind::Cylinder: return {};
    }
    return {};
}

// Offsets as numbers separated by spaces, commas, semicolons or lines (so a genome copied from
// evaluations.csv works as it is): a file, or the list itself when no such file exists.
std::vector<double> ReadOffsets(const std::string& text) {
    std::error_code ec;
    const bool isFile = std::filesystem::exists(text, ec);
    std::string numbers = isFile ? ReadInputFile(text) : text;
    std::string cleaned;
    cleaned.reserve(numbers.size());
    bool comment = false;
    for (char c : numbers) {
        if (c == '#') comment = true;
        if (c == '\n') comment = false;
        cleaned += comment || c == ',' || c == ';' ? ' ' : c;
    }
    if (!isFile && cleaned.find_first_not_of(" \t\n\r") == std::string::npos)
        throw UsageError("--offsets: " + Quote(text) + " is neither a file nor a list of numbers");
    std::vector<double> values;
    std::istringstream words(cleaned);
    for (std::string word; words >> word;) {
        if (!isFile && !TryParseNumber(word, &values.emplace_back()))
            throw UsageError("--offsets: no file " + Quote(text) + ", and it is not a list of numbers either");
        if (isFile) values.push_back(ParseNumber(word, "--offsets " + Quote(text)));
    }
    return values;
}

}  // namespace

const std::vector<std::string>& ShapeOptionNames() {
    static const std::vector<std::string> names{"--shape", "--amplitude", "--phase", "--region", "--control-points",
                                                "--offsets", "--mesh", "--resolution", "--turns"};
    return names;
}

std::vector<std::vector<double>> ParseControlPoints(const std::string& text, const std::string& what) {
    std::vector<std::vector<double>> splines;
    size_t start = 0;
    for (;;) {
        const size_t next = text.find(';', start);
        splines.push_back(ParseNumberList(text.substr(start, next == std::string::npos ? std::string::npos : next - start), what));
        if (next == std::string::npos) break;
        start = next + 1;
    }
    return splines;
}

void AddShapeOptions(Cli& cli, ShapeOptions& o) {
    cli.Group("Shape options");
    cli.Enum("--shape", o.kind, "the design's family (--mesh implies mesh)");
    cli.Number("--amplitude", o.amplitude, "sine and abs-sine: rho = A*sin(phase), mesh units (base radius 1)")
        ->default_str(fmt::format("{} for sine, {} for abs-sine", sim::SineShape{}.amplitude, sim::AbsSineShape{}.amplitude));
    cli.Text("--phase", o.phase, "phase range in radians from bottom to top vertex; numbers may use pi and + - * /, e.g. 0,4pi")
        ->type_name("START,END")
        ->default_str(fmt::format("{},{} for sine; {},{} for abs-sine", FormatRadians(sim::SineShape{}.phaseStart), FormatRadians(sim::SineShape{}.phaseEnd),
                                  FormatRadians(sim::AbsSineShape{}.phaseStart), FormatRadians(sim::AbsSineShape{}.phaseEnd)));
    cli.Enum("--region", o.region, "bspline: span all vertices, or leave the two clamped turns at each end at radius 1");
    cli.Text("--control-points", o.controlPoints,
             "bspline control points (radius multipliers), ',' between points and ';' between the 1, 2 or 4 sector splines, at least 4 "
             "each: \"8,8,0,4,0,0,2\" or \"4,6,2,5;2,3,7,4,6;5,5,1,2;3,3,3,3\"")
        ->type_name("LIST");
    cli.Text("--offsets", o.offsets, "free-xy: a file (or the list itself) of dx dy per vertex, 2*R*H numbers; spaces, commas or ';' between them")
        ->type_name("FILE");
    cli.Text("--mesh", o.meshFile, "start from an OBJ file's vertices in helix order (as written by --save-mesh)")->type_name("FILE");
    cli.Fields(o.mesh);
}

namespace {

// A triangle with its smallest index first, orientation kept: the same face however it was listed.
std::array<int, 3> Canonical(std::array<int, 3> t) {
    while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
    return t;
}

// The mesh an OBJ file gives, checked against the model's surface: its vertex count (with or without
// the shell models' cap centres, which the model places itself) and, when it has faces, its triangles.
sim::MeshShape MeshOfObj(const std::string& path, const sim::Surface& surface, int designVertices) {
    ObjMesh obj = ReadObj(path);
    const int n = obj.positions.Size();
    if (n != designVertices && n != surface.vertexCount)
        throw UsageError("--mesh " + Quote(path) + ": " + std::to_string(n) + " vertices; the model's mesh has " + std::to_string(designVertices) +
                         (surface.vertexCount != designVertices ? " (or " + std::to_string(surface.vertexCount) + " with the cap centres)" : std::string()) +
                         "; set its size with --resolution and --turns (thesis) or --ring-vertices and --rings");
    if (!obj.triangles.empty()) {
        std::set<std::array<int, 3>> expected, given;
        for (const auto& t : surface.triangles)
            if (std::max({t[0], t[1], t[2]}) < n) expected.insert(Canonical(t));
        for (const auto& t : obj.triangles) given.insert(Canonical(t));
        if (given != expected)
            throw UsageError("--mesh " + Quote(path) + ": its triangles are not the model's (" + std::to_string(obj.triangles.size()) + " given, " +
                             std::to_string(expected.size()) + " expected): not a surface of the expected topology, or in another vertex order");
    }
    obj.positions.x.resize(static_cast<size_t>(designVertices));
    obj.positions.y.resize(static_cast<size_t>(designVertices));
    obj.positions.z.resize(static_cast<size_t>(designVertices));
    return sim::MeshShape{std::move(obj.positions)};
}

}  // namespace

sim::Shape BuildShape(const Cli& cli, const ShapeOptions& o, const sim::Surface& surface, int vertices) {
    sim::ShapeKind kind = o.kind;
    if (cli.Given("--mesh")) {
        if (cli.Given("--shape") && kind != sim::ShapeKind::Mesh) throw UsageError("--mesh gives the shape itself; drop --shape " + std::string(sim::Name(kind)));
        kind = sim::ShapeKind::Mesh;
    }
    const std::vector<std::string> allowed = OptionsFor(kind);
    for (const char* option : {"--amplitude", "--phase", "--region", "--control-points", "--offsets", "--mesh"})
        if (cli.Given(option) && std::find(allowed.begin(), allowed.end(), option) == allowed.end())
            throw UsageError(std::string(option) + " does not apply to --shape " + sim::Name(kind));

    sim::Shape shape;
    switch (kind) {
        case sim::ShapeKind::Cylinder: shape = sim::CylinderShape{}; break;
        case sim::ShapeKind::Sine:
        case sim::ShapeKind::AbsSine: {
            sim::SineShape sine;
            if (kind == sim::ShapeKind::AbsSine) {
                const sim::AbsSineShape a;
                sine = {a.amplitude, a.phaseStart, a.phaseEnd};
            }
            if (cli.Given("--amplitude")) sine.amplitude = o.amplitude;
            if (cli.Given("--phase")) {
                const auto phase = ParseNumberList(o.phase, "--phase");
                if (phase.size() != 2) throw UsageError("--phase: expected START,END (two numbers), got " + Quote(o.phase));
                sine.phaseStart = phase[0];
                sine.phaseEnd = phase[1];
            }
            if (kind == sim::ShapeKind::Sine) shape = sine;
            else shape = sim::AbsSineShape{sine.amplitude, sine.phaseStart, sine.phaseEnd};
            break;
        }
        case sim::ShapeKind::BSpline: {
            if (!cli.Given("--control-points")) throw UsageError("--shape bspline needs --control-points, e.g. \"8,8,0,4,0,0,2\"");
            shape = sim::BSplineShape{o.region, ParseControlPoints(o.controlPoints, "--control-points")};
            break;
        }
        case sim::ShapeKind::FreeXY: {
            if (!cli.Given("--offsets")) throw UsageError("--shape free-xy needs --offsets FILE ('dx dy' per vertex)");
            const auto numbers = ReadOffsets(o.offsets);
            const size_t n = static_cast<size_t>(vertices);
            if (numbers.size() != 2 * n)
                throw UsageError("--offsets: " + Quote(o.offsets) + " has " + std::to_string(numbers.size()) + " numbers, expected " +
                                 std::to_string(2 * n) + " (dx dy for each of " + std::to_string(n) + " vertices)");
            sim::FreeXYShape s;
            for (size_t i = 0; i < n; ++i) {
                s.dx.push_back(numbers[2 * i]);
                s.dy.push_back(numbers[2 * i + 1]);
            }
            shape = std::move(s);
            break;
        }
        case sim::ShapeKind::Mesh:
            if (!cli.Given("--mesh")) throw UsageError("--shape mesh needs --mesh FILE");
            shape = MeshOfObj(o.meshFile, surface, vertices);
            break;
    }
    return shape;
}

namespace {

// [SECTION] Each model's mesh from the shape options (a new def adds its overload): the thesis
// helix is --resolution x --turns; the shell models' ring mesh is their geometry's.
void SetDesignMesh(const Cli&, const ShapeOptions& o, sim::ModelKind, sim::ThesisDef& def) {
    def.mesh = o.mesh;
    if (static_cast<long long>(def.mesh.resolution) * def.mesh.turns > sim::kMaxVertices)
        throw UsageError("--resolution x --turns: more than " + std::to_string(sim::kMaxVertices) + " vertices");
}
void SetDesignMesh(const Cli& cli, const ShapeOptions&, sim::ModelKind model, sim::ShellDef&) {
    for (const char* option : {"--resolution", "--turns"})
        cli.RefuseIfGiven(option, std::string("is the thesis helix's; the ") + sim::Name(model) + " model's mesh is --ring-vertices and --rings");
}

}  // namespace

sim::EvalJob BuildJob(const Cli& cli, const ShapeOptions& shapeOptions, const ModelOptions& model, ModelUse use) {
    sim::EvalJob job;
    ApplyModelOptions(cli, model, job, use);
    std::visit([&](auto& def) { SetDesignMesh(cli, shapeOptions, job.model, def); }, job.def);
    // The vertices a design sets: free-xy offsets and OBJ files count them.
    job.shape = BuildShape(cli, shapeOptions, sim::SurfaceOf(job), sim::VertexCount(sim::DesignMeshOf(job)));
    if (const std::string error = sim::JobError(job); !error.empty()) {
        const bool mesh = std::holds_alternative<sim::MeshShape>(job.shape);
        throw UsageError((mesh ? "--mesh " + Quote(shapeOptions.meshFile) : "--shape " + std::string(sim::ShapeName(job.shape))) + ": " + error);
    }
    return job;
}

}  // namespace app
