// Evaluation spread over machines: `actuator serve` runs an evaluation server (Cap'n Proto RPC,
// interface Evaluator in sim/actuator.capnp); a WorkerPool sends batches of shapes to servers
// (and, with "local", to this machine's cores) and gives back results identical to a local run.
// A worker that fails, drops its connection or passes the timeout loses its shapes to the others.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/batch.h"

namespace app {

// What a server accepts, at most.
constexpr unsigned kServerMaxVertices = 65536;
constexpr unsigned kServerMaxIterations = 1'000'000;
constexpr unsigned kServerMaxRequests = 4096;        // shapes in one call
constexpr std::uint64_t kServerMaxWords = 16u << 20; // 128 MiB per message (Cap'n Proto traversal limit)

struct ServeOptions {
    std::string listen = "127.0.0.1:7300";  // ADDRESS:PORT; port 0 picks a free one
    int threads = 0;                        // 0: all cores
};

// Serves until the process is killed. Prints "listening on ADDRESS:PORT" on stdout once bound.
void Serve(const ServeOptions& options);

// Every worker failed: the run cannot continue here (exit code 3; GA runs keep their checkpoint).
struct WorkersGone : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct WorkerPoolOptions {
    std::vector<std::string> workers;  // "host:port" or "local"
    int localThreads = 0;              // threads for "local"; 0: all cores
    double timeoutSeconds = 300;       // a batch that takes longer counts as a hung worker
};

class WorkerPool {
public:
    explicit WorkerPool(const WorkerPoolOptions& options);
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    // Results in job order. Throws WorkersGone when no worker is left.
    std::vector<sim::SimResult> Evaluate(const std::vector<sim::EvalJob>& jobs, const sim::BatchProgress& progress = {});

private:
    struct State;
    std::unique_ptr<State> state_;
};

// "a:1,b:2,local" -> list; throws UsageError on an empty entry.
std::vector<std::string> ParseWorkerList(const std::string& text);

}  // namespace app
