// [SECTION] Server
// [SECTION] Worker pool
#include "remote.h"

#include <capnp/ez-rpc.h>
#include <kj/async-io.h>
#include <kj/async.h>
#include <kj/timer.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <iostream>
#include <thread>

#include "cli_options.h"
#include "schema_convert.h"

namespace app {

// ---------------------------------------------------------------------------------------------
// [SECTION] Server
// ---------------------------------------------------------------------------------------------
namespace {

capnp::ReaderOptions Limits() {
    capnp::ReaderOptions options;
    options.traversalLimitInWords = kServerMaxWords;
    options.nestingLimit = 32;
    return options;
}

// Checks one request against the server's bounds; the message names what is wrong.
sim::EvalJob CheckedJob(schema::EvalRequest::Reader request, unsigned index) {
    const std::string which = "request " + std::to_string(index) + ": ";
    sim::EvalJob job;
    const auto size = request.getMeshSize();
    const std::uint64_t vertices = std::uint64_t(size.getResolution()) * size.getTurns();
    if (size.getResolution() < sim::kMinResolution || size.getTurns() < sim::kMinTurns || vertices > kServerMaxVertices)
        throw std::runtime_error(which + "mesh size out of bounds (at least 3 x 5, at most " + std::to_string(kServerMaxVertices) + " vertices)");
    job.mesh = sim::MeshDef{static_cast<int>(size.getResolution()), static_cast<int>(size.getTurns())};
    job.params = GetParams(request.getParams());
    if (request.getParams().getIterations() > kServerMaxIterations)
        throw std::runtime_error(which + "more than " + std::to_string(kServerMaxIterations) + " iterations");
    const sim::SimParams& p = job.params;
    for (double v : {p.springConstant, p.pressureScale, p.pullForce, p.stepScale})
        if (!std::isfinite(v) || v < 0) throw std::runtime_error(which + "model constants must be finite and not negative");
    if (!(p.divergenceLimit > 0)) throw std::runtime_error(which + "divergence limit must be positive");
    job.shape = GetShape(request.getShape());
    if (const std::string error = sim::ShapeError(job.shape, job.mesh); !error.empty()) throw std::runtime_error(which + error);
    return job;
}

class EvaluatorImpl final : public schema::Evaluator::Server {
public:
    explicit EvaluatorImpl(int threads) : threads_(threads) {}

    kj::Promise<void> evaluate(EvaluateContext context) override {
        std::vector<sim::EvalJob> jobs;
        try {
            const auto requests = context.getParams().getRequests();
            if (requests.size() > kServerMaxRequests)
                throw std::runtime_error("more than " + std::to_string(kServerMaxRequests) + " shapes in one call");
            for (unsigned k = 0; k < requests.size(); ++k) jobs.push_back(CheckedJob(requests[k], k));
        } catch (const std::exception& error) {
            KJ_FAIL_REQUIRE("bad evaluation request", error.what());
        }
        // The batch runs on its own threads; the event loop keeps serving other clients meanwhile.
        auto paf = kj::newPromiseAndCrossThreadFulfiller<std::vector<sim::SimResult>>();
        // shared_ptr: kj::Own's destructor may throw, which std::thread's callable must not.
        auto fulfiller = std::make_shared<kj::Own<kj::CrossThreadPromiseFulfiller<std::vector<sim::SimResult>>>>(kj::mv(paf.fulfiller));
        std::thread([jobs = std::move(jobs), fulfiller, threads = threads_]() mutable {
            (*fulfiller)->fulfill(sim::EvaluateBatch(jobs, threads));
        }).detach();
        return paf.promise.then([context](std::vector<sim::SimResult> results) mutable {
            auto responses = context.getResults().initResponses(static_cast<unsigned>(results.size()));
            for (unsigned k = 0; k < results.size(); ++k) {
                auto r = responses[k].initResult();
                r.setStatus(ToSchema(results[k].status));
                r.setFitness(results[k].fitness);
                r.setContractionPercent(results[k].contractionPercent);
                r.setIterationsRun(static_cast<std::uint32_t>(results[k].iterationsRun));
                r.setElapsedMs(results[k].elapsedMs);
                SetExactMesh(responses[k].initInitial(), results[k].initial);
                SetExactMesh(responses[k].initFinal(), results[k].final);
            }
        });
    }

    kj::Promise<void> info(InfoContext context) override {
        auto r = context.getResults();
        r.setThreads(static_cast<std::uint32_t>(threads_ > 0 ? threads_ : sim::HardwareThreads()));
        r.setMaxVertices(kServerMaxVertices);
        r.setMaxIterations(kServerMaxIterations);
        r.setMaxRequests(kServerMaxRequests);
        return kj::READY_NOW;
    }

private:
    int threads_;
};

}  // namespace

void Serve(const ServeOptions& options) {
    std::string address = options.listen;
    if (address.find(':') == std::string::npos) address = "127.0.0.1:" + address;  // a bare port
    capnp::EzRpcServer server(kj::heap<EvaluatorImpl>(options.threads), address, 0, Limits());
    auto& waitScope = server.getWaitScope();
    const unsigned port = server.getPort().wait(waitScope);
    std::cout << "listening on " << address.substr(0, address.rfind(':')) << ":" << port << " ("
              << (options.threads > 0 ? options.threads : sim::HardwareThreads()) << " threads)" << std::endl;
    kj::NEVER_DONE.wait(waitScope);
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Worker pool
// ---------------------------------------------------------------------------------------------

std::vector<std::string> ParseWorkerList(const std::string& text) {
    std::vector<std::string> workers;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = text.find(',', start);
        const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (item.empty()) throw UsageError("--workers: empty entry in '" + text + "' (expected host:port,host:port or local)");
        if (item != "local" && item.find(':') == std::string::npos) throw UsageError("--workers: '" + item + "' needs a port (host:port)");
        workers.push_back(item);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return workers;
}

struct RemoteWorker {
    std::string address;
    bool local = false;
    bool alive = true;
    kj::Own<capnp::EzRpcClient> client;
    kj::Maybe<schema::Evaluator::Client> evaluator;
};

struct WorkerPool::State {
    WorkerPoolOptions options;
    std::vector<RemoteWorker> workers;
    kj::Maybe<kj::WaitScope&> waitScope;
    kj::Maybe<kj::Timer&> timer;
};

WorkerPool::WorkerPool(const WorkerPoolOptions& options) : state_(std::make_unique<State>()) {
    state_->options = options;
    for (const auto& address : options.workers) {
        RemoteWorker w;
        w.address = address;
        w.local = address == "local";
        if (!w.local) {
            // Connects in the background; a bad address or a dead server shows up as a failed call.
            w.client = kj::heap<capnp::EzRpcClient>(address, 0, Limits());
            w.evaluator = w.client->getMain<schema::Evaluator>();
            state_->waitScope = w.client->getWaitScope();
            state_->timer = w.client->getIoProvider().getTimer();
        }
        state_->workers.push_back(kj::mv(w));
    }
}

WorkerPool::~WorkerPool() = default;

std::vector<sim::SimResult> WorkerPool::Evaluate(const std::vector<sim::EvalJob>& jobs, const sim::BatchProgress& progress) {
    State& s = *state_;
    std::vector<sim::SimResult> results(jobs.size());
    std::deque<size_t> pending;
    for (size_t j = 0; j < jobs.size(); ++j) pending.push_back(j);
    int done = 0;
    const int total = static_cast<int>(jobs.size());
    auto finished = [&](size_t j, sim::SimResult result) {
        results[j] = std::move(result);
        if (progress) progress(++done, total, results[j]);
    };

    while (!pending.empty()) {
        std::vector<RemoteWorker*> alive;
        for (auto& w : s.workers)
            if (w.alive) alive.push_back(&w);
        if (alive.empty())
            throw WorkersGone("every worker is gone (" + std::to_string(pending.size()) + " shapes left unevaluated)");

        // Split what is left evenly over the live workers; each gets one call.
        const size_t share = (pending.size() + alive.size() - 1) / alive.size();
        struct Call {
            RemoteWorker* worker;
            std::vector<size_t> indices;
            kj::Maybe<kj::Promise<capnp::Response<schema::Evaluator::EvaluateResults>>> promise;
        };
        std::vector<std::unique_ptr<Call>> calls;
        std::vector<size_t> localIndices;
        for (RemoteWorker* w : alive) {
            std::vector<size_t> indices;
            while (!pending.empty() && indices.size() < share) {
                indices.push_back(pending.front());
                pending.pop_front();
            }
            if (indices.empty()) break;
            if (w->local) {
                localIndices = std::move(indices);
                continue;
            }
            auto request = KJ_ASSERT_NONNULL(w->evaluator).evaluateRequest();
            auto list = request.initRequests(static_cast<unsigned>(indices.size()));
            for (unsigned k = 0; k < indices.size(); ++k) {
                const sim::EvalJob& job = jobs[indices[k]];
                SetShape(list[k].initShape(), job.shape);
                SetParams(list[k].initParams(), job.params);
                list[k].initMeshSize().setResolution(static_cast<std::uint32_t>(job.mesh.resolution));
                list[k].getMeshSize().setTurns(static_cast<std::uint32_t>(job.mesh.turns));
            }
            auto timeout = KJ_ASSERT_NONNULL(s.timer).afterDelay(static_cast<std::int64_t>(s.options.timeoutSeconds * 1000) * kj::MILLISECONDS)
                               .then([]() -> capnp::Response<schema::Evaluator::EvaluateResults> {
                                   KJ_FAIL_REQUIRE("no answer within the worker timeout");
                               });
            calls.push_back(std::make_unique<Call>(Call{w, std::move(indices), request.send().exclusiveJoin(kj::mv(timeout))}));
        }

        // This machine's share runs on its own threads while the servers work.
        std::vector<sim::SimResult> localResults;
        std::thread localThread;
        if (!localIndices.empty()) {
            localThread = std::thread([&] {
                std::vector<sim::EvalJob> localJobs;
                for (size_t j : localIndices) localJobs.push_back(jobs[j]);
                localResults = sim::EvaluateBatch(localJobs, s.options.localThreads);
            });
        }
        for (auto& callPointer : calls) {
            Call& call = *callPointer;
            try {
                auto response = KJ_ASSERT_NONNULL(call.promise).wait(KJ_ASSERT_NONNULL(s.waitScope));
                const auto responses = response.getResponses();
                if (responses.size() != call.indices.size()) throw std::runtime_error("answered a different number of shapes");
                for (unsigned k = 0; k < responses.size(); ++k) {
                    sim::SimResult r;
                    r.status = FromSchema(responses[k].getResult().getStatus());
                    r.fitness = responses[k].getResult().getFitness();
                    r.contractionPercent = responses[k].getResult().getContractionPercent();
                    r.iterationsRun = static_cast<int>(responses[k].getResult().getIterationsRun());
                    r.elapsedMs = responses[k].getResult().getElapsedMs();
                    r.initial = GetExactMesh(responses[k].getInitial());
                    r.final = GetExactMesh(responses[k].getFinal());
                    finished(call.indices[k], std::move(r));
                }
            } catch (const kj::Exception& error) {
                call.worker->alive = false;
                std::cerr << "worker " << call.worker->address << " failed (" << error.getDescription().cStr() << "); its "
                          << call.indices.size() << " shapes go to the other workers\n";
                for (size_t j : call.indices) pending.push_back(j);
            } catch (const std::exception& error) {
                call.worker->alive = false;
                std::cerr << "worker " << call.worker->address << " failed (" << error.what() << "); its " << call.indices.size()
                          << " shapes go to the other workers\n";
                for (size_t j : call.indices) pending.push_back(j);
            }
        }
        if (localThread.joinable()) {
            localThread.join();
            for (size_t k = 0; k < localIndices.size(); ++k) finished(localIndices[k], std::move(localResults[k]));
        }
    }
    return results;
}

}  // namespace app
