// JSON outputs, through nlohmann's ordered_json (keys in the order written; numbers with the
// shortest text that reads back as the same double; NaN and infinities as null). One way to write
// a design, a model's settings and a result, shared by simulate, render, inspect and summaries.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "sim/batch.h"

namespace app {

using Json = nlohmann::ordered_json;

Json NumberJson(double value);  // null when not finite

// How deeply JSON we read may nest: our documents need fewer than 10 levels. Deeper ones are refused
// before they are parsed, because copying and destroying a document recurse once per level (100,000
// levels overflow the stack).
constexpr int kMaxJsonDepth = 64;
// Throws UsageError naming `source`, the line and the column where `text` nests deeper than
// kMaxJsonDepth (arrays and objects; brackets inside strings do not count).
void CheckJsonDepth(std::string_view text, const std::string& source);
// Every JSON we read goes through here: the depth check, then nlohmann's parser (whose exceptions,
// for text that is not JSON, pass to the caller).
Json ParseJson(std::string_view text, const std::string& source);

// The design with every parameter: sine amplitude and phase; B-spline region and each spline's
// control points; free-xy offsets; a mesh's vertex count.
Json ShapeJson(const sim::Shape& shape);
// The model's settings: the thesis model's every SimParams field and helix size, or the membrane
// and shell models' geometry, material, load and solver.
Json ModelJson(const sim::EvalJob& job);
// Status, fitness, contraction; the thesis model's iterations, or the shell models' outputs
// (pressure, limit pressure, blocking force, stiffness, volume, stretch and stress beside the
// material's limits, Newton iterations, the contraction-pressure curve); time.
Json ResultNumbersJson(const sim::SimResult& result, const sim::EvalJob& job);

}  // namespace app
