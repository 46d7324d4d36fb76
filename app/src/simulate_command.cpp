// `actuator simulate`: one evaluation, one JSON object on stdout, optionally the meshes as OBJ.
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "mesh_io.h"
#include "shape_options.h"

namespace app {
namespace {

std::vector<OptionSpec> SimulateOnlySpecs() {
    return {
        {"save-mesh", "FILE", "", "write the final positions as OBJ (full precision; reads back with --mesh)"},
        {"save-initial", "FILE", "", "write the initial (shaped) mesh as OBJ"},
        {"help", "", "", "show this help"},
    };
}

std::vector<OptionSpec> AllSpecs() {
    auto specs = ShapeOptionSpecs();
    for (auto& s : SimulationOptionSpecs()) specs.push_back(s);
    for (auto& s : SimulateOnlySpecs()) specs.push_back(s);
    return specs;
}

std::string ResultJson(const EvaluationRequest& request, const sim::SimResult& result) {
    JsonWriter json;
    json.BeginObject();
    json.Key("status").String(sim::StatusName(result.status));
    json.Key("fitness").Number(result.fitness);
    json.Key("contraction_percent").Number(result.contractionPercent);
    json.Key("iterations").Integer(result.iterationsRun);
    json.Key("iterations_requested").Integer(request.params.iterations);
    json.Key("elapsed_ms").Number(result.elapsedMs);
    json.Key("shape");
    WriteShapeJson(json, request.shape);
    json.Key("load").String(sim::LoadName(request.params.load));
    json.Key("precision").String(sim::PrecisionName(request.params.precision));
    json.Key("resolution").Integer(request.mesh.resolution);
    json.Key("turns").Integer(request.mesh.turns);
    json.Key("vertices").Integer(sim::VertexCount(request.mesh));
    json.Key("springs").Integer(sim::SpringCount(request.mesh));
    char hash[20];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(sim::PositionsHash(result.final)));
    json.Key("final_positions_hash").String(hash);
    json.EndObject();
    return json.Text();
}

}  // namespace

std::string SimulateHelp() {
    return "usage: actuator simulate [shape options] [simulation options] [--save-mesh FILE]\n\n"
           "Evaluates one actuator shape with the thesis model (shared/MODEL.md) and prints one JSON object:\n"
           "status (ok, nan, diverged), fitness (contraction in mesh units; null unless ok), contraction_percent,\n"
           "iterations, elapsed_ms, the shape and the settings. Exit code 0 when it ran (whatever the status),\n"
           "2 on bad input.\n\n"
           "Shape options:\n" + FormatOptions(ShapeOptionSpecs()) +
           "\nSimulation options:\n" + FormatOptions(SimulationOptionSpecs()) +
           "\nOutput options:\n" + FormatOptions(SimulateOnlySpecs()) +
           "\nExamples:\n"
           "  actuator simulate --shape sine --amplitude 4.1 --phase 0.5,2.6415926535\n"
           "  actuator simulate --shape abs-sine --amplitude 4 --phase 0,4pi\n"
           "  actuator simulate --shape bspline --region middle --control-points \"8,8,0,4,0,0,2\"\n"
           "  actuator simulate --shape sine --load stretch --save-mesh stretched.obj\n"
           "  actuator simulate --mesh stretched.obj --iterations 5000\n";
}

int RunSimulate(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, AllSpecs(), 0);
    if (args.Has("help")) {
        std::cout << SimulateHelp();
        return 0;
    }
    const EvaluationRequest request = ParseEvaluationRequest(args);
    // Refuse unwritable outputs before the work, not after it.
    for (const char* option : {"save-mesh", "save-initial"})
        if (args.Has(option)) CheckOutputPath(args.Get(option), std::string("--") + option);

    const sim::SimResult result = sim::Simulate(sim::BuildInitialPositions(request.shape, request.mesh), request.mesh, request.params);

    if (args.Has("save-initial")) WriteFileAtomically(args.Get("save-initial"), FormatObj(result.initial, request.mesh));
    if (args.Has("save-mesh")) WriteFileAtomically(args.Get("save-mesh"), FormatObj(result.final, request.mesh));
    std::cout << ResultJson(request, result) << "\n";
    return 0;
}

}  // namespace app
