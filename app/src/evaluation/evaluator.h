// The one path every simulation of every command takes: an Evaluator runs jobs (on this machine's
// threads, or on evaluation servers with this machine as an ordinary worker among them) and hands
// each result to a sink in job order, on the calling thread, as soon as it and every earlier one are
// done. Results stream: a 100,000-point sweep holds only a window of meshes in memory, and the sink
// may draw (GL contexts belong to the calling thread). Results depend only on the job, never on the
// threads, the workers or the order of completion.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/batch.h"

namespace app {

using ResultSink = std::function<void(size_t index, sim::SimResult&& result)>;

class Evaluator {
public:
    virtual ~Evaluator() = default;
    // Throws WorkersGone when no worker is left (remote pools). Exceptions thrown by the sink
    // propagate after the work in flight has stopped.
    virtual void Evaluate(const std::vector<sim::EvalJob>& jobs, const ResultSink& sink) = 0;
    // All results at once, for small batches.
    std::vector<sim::SimResult> EvaluateAll(const std::vector<sim::EvalJob>& jobs);
    virtual std::string Describe() const = 0;  // e.g. "2 threads"
};

// This machine's cores; 0 threads means one per core.
std::unique_ptr<Evaluator> MakeLocalEvaluator(int threads);

// Runs jobs[begin, end) on `threads` threads and calls `done(index, result)` in index order from
// the calling thread. At most `window` results wait for an earlier one. Used by the local evaluator,
// the local worker of a pool and the server.
void EvaluateInOrder(const std::vector<sim::EvalJob>& jobs, size_t begin, size_t end, int threads, size_t window,
                     const ResultSink& done);

}  // namespace app
