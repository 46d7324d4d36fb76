#include "map_evaluator.h"

#include <pybind11/stl.h>

#include <fmt/format.h>

#include <chrono>

#include "evaluation/remote.h"
#include "formats/schema_convert.h"
#include "sim/batch.h"

namespace pybinding {
namespace {

class MapEvaluator final : public app::Evaluator {
public:
    MapEvaluator(py::object map, py::object gather, size_t batch) : map_(std::move(map)), gather_(std::move(gather)), batch_(batch) {}

    ~MapEvaluator() override {
        py::gil_scoped_acquire gil;
        map_ = py::object();
        gather_ = py::object();
    }

    void Evaluate(const std::vector<sim::EvalJob>& jobs, const app::ResultSink& sink) override {
        for (size_t begin = 0; begin < jobs.size(); begin += batch_) {
            const size_t end = std::min(jobs.size(), begin + batch_);
            std::vector<sim::SimResult> results;
            {
                py::gil_scoped_acquire gil;
                results = MapBatch(jobs, begin, end);
            }
            // The sink records and may draw: it runs without the GIL, like the local evaluator's.
            for (size_t k = begin; k < end; ++k) sink(k, std::move(results[k - begin]));
        }
    }

    std::string Describe() const override {
        py::gil_scoped_acquire gil;
        return "Python map " + std::string(py::repr(gather_ ? map_.attr("__self__") : map_));
    }

private:
    std::vector<sim::SimResult> MapBatch(const std::vector<sim::EvalJob>& jobs, size_t begin, size_t end) {
        py::list items;
        for (size_t k = begin; k < end; ++k) items.append(py::bytes(app::JobBytes(jobs[k])));
        const py::object worker = py::module_::import("actuator").attr("_evaluate_job");
        py::object mapped = map_(worker, items);
        if (gather_) mapped = gather_(mapped);
        std::vector<sim::SimResult> results;
        for (const py::handle item : mapped) {
            if (!py::isinstance<py::bytes>(item))
                throw py::value_error(fmt::format("map: gave back a {} where actuator._evaluate_job's bytes were expected; pass a map "
                                                  "that applies the function it is given (map(f, items) -> f(item) for each, in order)",
                                                  std::string(py::str(py::type::of(item).attr("__name__")))));
            try {
                results.push_back(app::ResultFromBytes(item.cast<std::string>()));
            } catch (const std::runtime_error& e) {
                throw py::value_error(std::string("map: a result did not decode: ") + e.what());
            }
        }
        if (results.size() != end - begin)
            throw py::value_error(fmt::format("map: gave back {} results for {} jobs; it must give one per item, in order", results.size(), end - begin));
        return results;
    }

    py::object map_, gather_;
    size_t batch_;
};

// Any evaluator, made stoppable from Python: between results (at most every 0.1 s) the calling
// thread takes the GIL and lets Python run its signal handlers, so Ctrl-C (or a notebook's
// interrupt) raises KeyboardInterrupt out of a long run. The work in flight stops; what was
// recorded stays, and resume=True continues from it.
class Interruptible final : public app::Evaluator {
public:
    explicit Interruptible(std::unique_ptr<app::Evaluator> inner) : inner_(std::move(inner)) {}

    void Evaluate(const std::vector<sim::EvalJob>& jobs, const app::ResultSink& sink) override {
        auto checked = std::chrono::steady_clock::now();
        inner_->Evaluate(jobs, [&](size_t index, sim::SimResult&& result) {
            sink(index, std::move(result));
            if (std::chrono::steady_clock::now() - checked < std::chrono::milliseconds(100)) return;
            checked = std::chrono::steady_clock::now();
            py::gil_scoped_acquire gil;
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        });
    }
    std::string Describe() const override { return inner_->Describe(); }

private:
    std::unique_ptr<app::Evaluator> inner_;
};

}  // namespace

std::unique_ptr<app::Evaluator> MakePythonEvaluator(int threads, const py::object& map, const py::object& workers, size_t batch) {
    if (threads < 0) throw py::value_error("threads: must be 0 (one per core) or more");
    if (batch == 0) throw py::value_error("batch: must be 1 or more");
    const bool hasMap = map && !map.is_none(), hasWorkers = workers && !workers.is_none();
    if (hasMap && hasWorkers) throw py::value_error("map and workers: give one of them (workers are evaluation servers, map any map-like callable)");
    if (hasWorkers) {
        app::WorkerPoolOptions options;
        options.localThreads = threads;
        options.workers = py::isinstance<py::str>(workers) ? app::ParseWorkerList(workers.cast<std::string>())
                                                           : workers.cast<std::vector<std::string>>();
        if (options.workers.empty()) throw py::value_error("workers: the list is empty");
        return std::make_unique<Interruptible>(app::MakeWorkerPool(options));
    }
    if (!hasMap) return std::make_unique<Interruptible>(app::MakeLocalEvaluator(threads));
    // A Dask client (or anything with map and gather): submit, then gather, in order.
    if (py::hasattr(map, "map") && py::hasattr(map, "gather")) return std::make_unique<MapEvaluator>(map.attr("map"), map.attr("gather"), batch);
    if (PyCallable_Check(map.ptr())) return std::make_unique<MapEvaluator>(map, py::object(), batch);
    throw py::value_error(fmt::format("map: {} is neither callable like map(f, items) nor a client with map and gather (e.g. a Dask client)",
                                      std::string(py::repr(map))));
}

py::bytes EvaluateJobBytes(const py::bytes& job) {
    sim::EvalJob decoded;
    try {
        decoded = app::JobFromBytes(job.cast<std::string>());
    } catch (const std::runtime_error& e) {
        throw py::value_error(e.what());
    }
    if (const std::string error = sim::JobError(decoded); !error.empty()) throw py::value_error(error);
    std::string bytes;
    {
        py::gil_scoped_release release;
        bytes = app::ResultBytes(sim::Evaluate(decoded), decoded.model);
    }
    return py::bytes(bytes);
}

}  // namespace pybinding
