// The workbench's Evaluator interface implemented in Python terms: a batch's jobs go, as bytes, to
// any `map`-like callable (DEAP's toolbox.map idea): builtins.map, a concurrent.futures executor's
// map, a multiprocessing pool's map, or a Dask client (its map, then gather). Each item is evaluated
// by actuator._evaluate_job wherever the map runs it, and the results come back at full precision,
// so a run through any map equals the local run bit for bit.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "evaluation/evaluator.h"

namespace pybinding {

namespace py = pybind11;

// Results stream to the sink batch by batch: at most `batch` results wait in memory.
constexpr size_t kDefaultMapBatch = 1024;

// Where a Python call's evaluations run: this machine's threads (map and workers None), a Python
// map, or evaluation servers (`workers`, "host:port" strings, as the command line's --workers).
// Throws ValueError for a map that is neither callable nor a Dask-like client, or for both map and
// workers. Made and destroyed with the GIL held; its Evaluate takes the GIL when it needs it. Threads
// and servers check Python's signals between results: Ctrl-C raises KeyboardInterrupt.
std::unique_ptr<app::Evaluator> MakePythonEvaluator(int threads, const py::object& map, const py::object& workers, size_t batch = kDefaultMapBatch);

// What runs on the map's side: job bytes in, result bytes out (app/schema_convert.h).
py::bytes EvaluateJobBytes(const py::bytes& job);

}  // namespace pybinding
