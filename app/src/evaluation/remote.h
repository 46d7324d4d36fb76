// Evaluation spread over machines: `actuator serve` runs an evaluation server (Cap'n Proto RPC,
// interface Evaluator in app/schema/actuator.capnp); a worker pool is an Evaluator that sends parts
// of a batch to servers, and with "local" to this machine's cores, and gives back results identical
// to a local run. It asks each server its limits (info) and splits batches into calls within them.
// A worker that fails, drops its connection or passes the timeout loses its shapes to the others.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "evaluation/evaluator.h"

namespace app {

// What a server accepts in one call, at most. A call's reply holds two float64 meshes per shape.
struct ServerLimits {
    std::uint32_t maxVertices = 65536;
    std::uint32_t maxIterations = 1'000'000;
    std::uint32_t maxRequests = 4096;                  // shapes in one call
    // The sum of the call's work (see Work): one shell job of the largest mesh at the default budget
    // (4 load steps, 200 Newton iterations a step), about half an hour of one core at worst.
    std::uint64_t maxWork = 65536ull * 4 * 200 * 10000;
    std::uint64_t maxReplyWords = 12ull << 20;         // 96 MiB, under the 128 MiB message limit
};
constexpr std::uint64_t kMessageWords = 16ull << 20;  // 128 MiB: Cap'n Proto's traversal limit per message

struct ServeOptions {
    std::string listen = "127.0.0.1:7300";  // ADDRESS:PORT; port 0 picks a free one
    int threads = 0;                        // 0: all cores
};

// Serves until the process is killed. Prints "listening on ADDRESS:PORT" on stdout once bound.
void Serve(const ServeOptions& options);

struct WorkerPoolOptions {
    std::vector<std::string> workers;  // "host:port" or "local"
    int localThreads = 0;              // threads for "local"; 0: all cores
    double timeoutSeconds = 300;       // a call that takes longer counts as a hung worker
};
constexpr double kMaxWorkerTimeoutSeconds = 7 * 24 * 3600.0;

std::unique_ptr<Evaluator> MakeWorkerPool(const WorkerPoolOptions& options);

// "a:1,b:2,local" -> list. Throws UsageError on an empty entry, a missing or bad port, spaces.
std::vector<std::string> ParseWorkerList(const std::string& text);
// "ADDRESS:PORT" or a bare port, for serve --listen. Throws UsageError.
std::string ParseListenAddress(const std::string& text);

// The server's words for a reply of these jobs, and their work (vertices x iterations).
std::uint64_t ReplyWords(const sim::EvalJob& job);
std::uint64_t Work(const sim::EvalJob& job);

}  // namespace app
