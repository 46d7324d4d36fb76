// The options that describe one evaluation (shape, mesh size, load, model constants), shared by every
// subcommand that simulates: simulate now, render and the searches later.
#pragma once

#include <vector>

#include "cli_options.h"
#include "json_writer.h"
#include "sim/solver.h"

namespace app {

struct EvaluationRequest {
    sim::Shape shape;
    sim::MeshDef mesh;
    sim::SimParams params;
};

std::vector<OptionSpec> ShapeOptionSpecs();       // --shape, --amplitude, --phase, --region, ...
std::vector<OptionSpec> SimulationOptionSpecs();  // --load, --iterations, --precision, constants

// Builds and validates the request. Throws UsageError naming the option at fault.
EvaluationRequest ParseEvaluationRequest(const ParsedArgs& args);

// The shape's name and parameters as a JSON object value (after a Key()).
void WriteShapeJson(JsonWriter& json, const sim::Shape& shape);

}  // namespace app
