// [SECTION] Addresses
// [SECTION] Server
// [SECTION] Worker pool
#include "evaluation/remote.h"

#include <capnp/ez-rpc.h>
#include <kj/async-io.h>
#include <kj/async.h>
#include <kj/timer.h>
#include <malloc.h>

#include <atomic>
#include <cctype>
#include <condition_variable>
#include <cmath>
#include <deque>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>

#include "support/errors.h"
#include "sim/fields.h"
#include "support/number_expression.h"
#include "formats/schema_convert.h"
#include "sim/model.h"

namespace app {

namespace {

// Vertices of a job's meshes.
std::uint64_t Vertices(const sim::EvalJob& job) { return static_cast<std::uint64_t>(std::max(0, sim::ModelOf(job).vertices(job))); }

}  // namespace

std::uint64_t ReplyWords(const sim::EvalJob& job) {
    const std::uint64_t curve = 3ull * static_cast<std::uint64_t>(sim::ModelOf(job).curvePoints(job));
    return 6ull * Vertices(job) + curve + 96;
}
std::uint64_t Work(const sim::EvalJob& job) { return sim::ModelOf(job).work(job); }  // the model's own estimate

// ---------------------------------------------------------------------------------------------
// [SECTION] Addresses
// ---------------------------------------------------------------------------------------------
namespace {

// HOST:PORT with no spaces, a host, and a port in [minPort, 65535].
std::string CheckedAddress(const std::string& item, const std::string& what, int minPort) {
    for (char c : item)
        if (std::isspace(static_cast<unsigned char>(c))) throw UsageError(what + ": " + Quote(item) + " contains a space");
    const size_t colon = item.rfind(':');
    if (colon == std::string::npos) throw UsageError(what + ": " + Quote(item) + " needs a port (host:port)");
    if (colon == 0) throw UsageError(what + ": " + Quote(item) + " needs a host before the port");
    ParseInteger(item.substr(colon + 1), what + " port", minPort, 65535);
    return item;
}

}  // namespace

std::vector<std::string> ParseWorkerList(const std::string& text) {
    std::vector<std::string> workers;
    size_t start = 0;
    for (;;) {
        const size_t comma = text.find(',', start);
        const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (item.empty()) throw UsageError("--workers: empty entry in " + Quote(text) + " (expected host:port,host:port or local)");
        workers.push_back(item == "local" ? item : CheckedAddress(item, "--workers", 1));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return workers;
}

std::string ParseListenAddress(const std::string& text) {
    if (!text.empty() && text.find(':') == std::string::npos) {
        ParseInteger(text, "--listen port", 0, 65535);
        return "127.0.0.1:" + text;  // a bare port
    }
    return CheckedAddress(text, "--listen", 0);
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Server
// ---------------------------------------------------------------------------------------------
namespace {

capnp::ReaderOptions MessageLimits() {
    capnp::ReaderOptions options;
    options.traversalLimitInWords = kMessageWords;
    options.nestingLimit = 32;
    return options;
}

// Checks one request against the server's bounds; the message names what is wrong.
sim::EvalJob CheckedJob(schema::EvalRequest::Reader request, unsigned index, const ServerLimits& limits) {
    const std::string which = "request " + std::to_string(index) + ": ";
    if (request.getModel() == schema::ModelKind::THESIS) {
        const auto size = request.getMeshSize();
        const std::uint64_t vertices = std::uint64_t(size.getResolution()) * size.getTurns();
        if (size.getResolution() < sim::kMinResolution || size.getTurns() < sim::kMinTurns || vertices > limits.maxVertices)
            throw std::runtime_error(which + "mesh size out of bounds (at least 3 x 5, at most " + std::to_string(limits.maxVertices) + " vertices)");
        if (request.getParams().getIterations() > limits.maxIterations)
            throw std::runtime_error(which + "more than " + std::to_string(limits.maxIterations) + " iterations");
    }
    sim::EvalJob job = GetJob(request);
    // The ranges the command line accepts, then the model's own checks (ShellDefError bounds the
    // ring mesh before anything is built from it).
    if (const std::string error = JobFieldsError(job); !error.empty()) throw std::runtime_error(which + error);
    if (const std::string error = sim::JobError(job); !error.empty()) throw std::runtime_error(which + error);
    if (Vertices(job) > limits.maxVertices) throw std::runtime_error(which + "more than " + std::to_string(limits.maxVertices) + " vertices");
    return job;
}

// The server's calls, run one at a time on every thread in the order they came: memory is that of
// one call's jobs, however many clients there are. Waiting calls hold only their requests, and at
// most kMaxWaitingCalls wait. A call whose client has gone (disconnected, or the call cancelled) is
// dropped before it starts, or stops after the shapes in hand.
class CallQueue {
public:
    static constexpr size_t kMaxWaitingCalls = 64;

    explicit CallQueue(int threads) : threads_(threads), runner_([this] { Run(); }) {}
    ~CallQueue() {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        changed_.notify_all();
        runner_.join();
    }

    // The call's results, in job order. Throws when too many calls wait already.
    kj::Promise<std::vector<sim::SimResult>> Submit(std::vector<sim::EvalJob> jobs) {
        auto paf = kj::newPromiseAndCrossThreadFulfiller<std::vector<sim::SimResult>>();
        auto dropped = std::make_shared<std::atomic<bool>>(false);
        {
            std::lock_guard lock(mutex_);
            if (waiting_.size() >= kMaxWaitingCalls)
                throw std::runtime_error("the server is busy: " + std::to_string(kMaxWaitingCalls) + " calls wait already; try again later");
            waiting_.push_back(Call{std::move(jobs), dropped, kj::mv(paf.fulfiller)});
        }
        changed_.notify_all();
        // The promise is destroyed when the call ends: answered, or cancelled because its client went.
        return paf.promise.attach(kj::defer([dropped] { dropped->store(true); }));
    }

private:
    struct Call {
        std::vector<sim::EvalJob> jobs;
        std::shared_ptr<std::atomic<bool>> dropped;
        kj::Own<kj::CrossThreadPromiseFulfiller<std::vector<sim::SimResult>>> fulfiller;
    };
    struct Dropped {};

    void Run() {
        for (;;) {
            Call call;
            {
                std::unique_lock lock(mutex_);
                changed_.wait(lock, [&] { return stopping_ || !waiting_.empty(); });
                if (stopping_) return;
                call = std::move(waiting_.front());
                waiting_.pop_front();
            }
            std::vector<sim::SimResult> results(call.jobs.size());
            size_t done = 0;
            try {
                if (*call.dropped) throw Dropped{};
                EvaluateInOrder(call.jobs, 0, call.jobs.size(), threads_, 4 * static_cast<size_t>(threads_), [&](size_t k, sim::SimResult&& r) {
                    results[k] = std::move(r);
                    ++done;
                    if (*call.dropped) throw Dropped{};
                });
            } catch (const Dropped&) {
                std::cout << "a call was dropped by its client: " << call.jobs.size() - done << " of " << call.jobs.size() << " shapes not evaluated"
                          << std::endl;
                continue;  // its fulfiller goes unanswered: nobody waits for it
            }
            call.fulfiller->fulfill(std::move(results));
            malloc_trim(0);  // give the call's memory back: a server idles small
        }
    }

    int threads_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Call> waiting_;
    bool stopping_ = false;
    std::thread runner_;  // last: it starts once the rest is built
};

class EvaluatorImpl final : public schema::Evaluator::Server {
public:
    explicit EvaluatorImpl(int threads) : threads_(threads > 0 ? threads : sim::HardwareThreads()), calls_(threads_) {}

    kj::Promise<void> evaluate(EvaluateContext context) override {
        // A client that cancels its call or disconnects cancels the work (Cap'n Proto 0.9 keeps
        // running a call to its end unless it says it may be cancelled).
        context.allowCancellation();
        std::vector<sim::EvalJob> jobs;
        try {
            const auto requests = context.getParams().getRequests();
            if (requests.size() > limits_.maxRequests)
                throw std::runtime_error("more than " + std::to_string(limits_.maxRequests) + " shapes in one call");
            std::uint64_t work = 0, words = 0;
            for (unsigned k = 0; k < requests.size(); ++k) {
                jobs.push_back(CheckedJob(requests[k], k, limits_));
                work += Work(jobs.back());
                words += ReplyWords(jobs.back());
            }
            // Bounded by work and by the reply, one shape or many: a call inside the other limits
            // could still need many gigabytes (4,096 shapes of 65,536 vertices) or hours.
            if (work > limits_.maxWork)
                throw std::runtime_error("the call asks for " + std::to_string(work) + " units of work, more than " + std::to_string(limits_.maxWork) +
                                         "; split it or lower its budget (see info)");
            if (words > limits_.maxReplyWords)
                throw std::runtime_error("the reply would take " + std::to_string(words * 8 >> 20) + " MiB, more than " +
                                         std::to_string(limits_.maxReplyWords * 8 >> 20) + "; split it (see info)");
        } catch (const std::exception& error) {
            KJ_FAIL_REQUIRE("bad evaluation request", error.what());
        }
        std::vector<sim::ModelKind> models;
        for (const auto& job : jobs) models.push_back(job.model);
        kj::Promise<std::vector<sim::SimResult>> results = nullptr;
        try {
            results = calls_.Submit(std::move(jobs));
        } catch (const std::exception& error) {
            return KJ_EXCEPTION(OVERLOADED, error.what());
        }
        return results.then([context, models = std::move(models)](std::vector<sim::SimResult> results) mutable {
            auto responses = context.getResults().initResponses(static_cast<unsigned>(results.size()));
            for (unsigned k = 0; k < results.size(); ++k) {
                SetResponse(responses[k], results[k], models[k]);
                results[k] = sim::SimResult{};
            }
        });
    }

    kj::Promise<void> info(InfoContext context) override {
        auto r = context.getResults();
        r.setThreads(static_cast<std::uint32_t>(threads_));
        r.setMaxVertices(limits_.maxVertices);
        r.setMaxIterations(limits_.maxIterations);
        r.setMaxRequests(limits_.maxRequests);
        r.setMaxWork(limits_.maxWork);
        r.setMaxReplyWords(limits_.maxReplyWords);
        return kj::READY_NOW;
    }

private:
    int threads_;
    ServerLimits limits_;
    CallQueue calls_;
};

}  // namespace

void Serve(const ServeOptions& options) {
    const std::string address = ParseListenAddress(options.listen);
    capnp::EzRpcServer server(kj::heap<EvaluatorImpl>(options.threads), address, 0, MessageLimits());
    auto& waitScope = server.getWaitScope();
    const unsigned port = server.getPort().wait(waitScope);
    std::cout << "listening on " << address.substr(0, address.rfind(':')) << ":" << port << " ("
              << (options.threads > 0 ? options.threads : sim::HardwareThreads()) << " threads)" << std::endl;
    kj::NEVER_DONE.wait(waitScope);
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Worker pool
// ---------------------------------------------------------------------------------------------
namespace {

struct Worker {
    std::string address;
    bool local = false;
    bool alive = true;
    bool busy = false;
    bool limitsKnown = false;
    ServerLimits limits;
    kj::Own<capnp::EzRpcClient> client;
    kj::Maybe<schema::Evaluator::Client> evaluator;
};

class WorkerPool final : public Evaluator {
public:
    explicit WorkerPool(const WorkerPoolOptions& options) : options_(options) {
        for (const auto& address : options.workers) {
            Worker w;
            w.address = address;
            w.local = address == "local";
            if (w.local) {
                w.limitsKnown = true;
                w.limits.maxRequests = 1u << 30;
                w.limits.maxWork = ~0ull;
                w.limits.maxReplyWords = ~0ull;
            } else {
                // Connects in the background; a bad address or a dead server shows up as a failed call.
                w.client = kj::heap<capnp::EzRpcClient>(address, 0, MessageLimits());
                w.evaluator = w.client->getMain<schema::Evaluator>();
                waitScope_ = w.client->getWaitScope();
                timer_ = w.client->getIoProvider().getTimer();
            }
            workers_.push_back(kj::mv(w));
        }
        if (workers_.size() == 1 && workers_[0].local) {
            // Only "local": no event loop is needed, but one keeps the code below single.
            localOnly_ = true;
        }
    }

    // kj's owners may throw from their destructors; a pool ending must not.
    ~WorkerPool() noexcept override {}

    std::string Describe() const override {
        std::string text;
        for (const auto& w : workers_) text += (text.empty() ? "" : ", ") + w.address;
        return "workers " + text;
    }

    void Evaluate(const std::vector<sim::EvalJob>& jobs, const ResultSink& sink) override {
        if (localOnly_) {
            const int threads = options_.localThreads > 0 ? options_.localThreads : sim::HardwareThreads();
            EvaluateInOrder(jobs, 0, jobs.size(), threads, 4 * static_cast<size_t>(threads), sink);
            return;
        }
        jobs_ = &jobs;
        pending_.clear();
        for (size_t j = 0; j < jobs.size(); ++j) pending_.push_back(j);
        ready_.clear();
        size_t delivered = 0;
        running_ = 0;
        kj::Vector<kj::Promise<void>> calls;
        while (delivered < jobs.size()) {
            for (auto& w : workers_) {
                if (!w.alive || w.busy || pending_.empty()) continue;
                if (!w.limitsKnown) calls.add(AskLimits(w));
                else calls.add(Dispatch(w));
            }
            if (running_ == 0) {
                if (std::none_of(workers_.begin(), workers_.end(), [](const Worker& w) { return w.alive; }))
                    throw WorkersGone("every worker is gone (" + std::to_string(jobs.size() - delivered) + " shapes left unevaluated)");
                continue;  // a worker just learned its limits: dispatch to it
            }
            auto paf = kj::newPromiseAndFulfiller<void>();
            wake_ = kj::mv(paf.fulfiller);
            paf.promise.wait(WaitScope());
            while (ready_.count(delivered)) {
                sim::SimResult result = std::move(ready_.at(delivered));
                ready_.erase(delivered);
                sink(delivered, std::move(result));
                ++delivered;
            }
        }
        jobs_ = nullptr;
    }

private:
    kj::WaitScope& WaitScope() { return KJ_ASSERT_NONNULL(waitScope_); }

    void Wake() {
        if (wake_ && wake_->isWaiting()) wake_->fulfill();
    }

    kj::Promise<void> WithTimeout(kj::Promise<void> promise) {
        const auto delay = static_cast<std::int64_t>(std::min(options_.timeoutSeconds, kMaxWorkerTimeoutSeconds) * 1000) * kj::MILLISECONDS;
        return promise.exclusiveJoin(KJ_ASSERT_NONNULL(timer_).afterDelay(delay).then([]() -> kj::Promise<void> {
            return KJ_EXCEPTION(DISCONNECTED, "no answer within the worker timeout");
        }));
    }

    void Lost(Worker& w, const std::string& why, const std::vector<size_t>& indices) {
        w.alive = false;
        w.busy = false;
        std::cerr << "worker " << w.address << " failed (" << why << ")";
        if (!indices.empty()) std::cerr << "; its " << indices.size() << " shapes go to the other workers";
        std::cerr << "\n";
        for (auto it = indices.rbegin(); it != indices.rend(); ++it) pending_.push_front(*it);
    }

    kj::Promise<void> AskLimits(Worker& w) {
        w.busy = true;
        ++running_;
        auto request = KJ_ASSERT_NONNULL(w.evaluator).infoRequest();
        auto call = request.send().then([&w](capnp::Response<schema::Evaluator::InfoResults> info) {
            w.limits.maxVertices = info.getMaxVertices();
            w.limits.maxIterations = info.getMaxIterations();
            w.limits.maxRequests = std::max(1u, info.getMaxRequests());
            // Older servers leave these at 0: bound them by the message size alone.
            w.limits.maxWork = info.getMaxWork() ? info.getMaxWork() : ~0ull;
            w.limits.maxReplyWords = info.getMaxReplyWords() ? info.getMaxReplyWords() : kMessageWords * 3 / 4;
            w.limitsKnown = true;
        });
        return WithTimeout(kj::mv(call))
            .then([this, &w]() {
                    w.busy = false;
                    --running_;
                    Wake();
                },
                  [this, &w](kj::Exception&& e) {
                      --running_;
                      Lost(w, e.getDescription().cStr(), {});
                      Wake();
                  })
            .eagerlyEvaluate(nullptr);
    }

    // The next part of the batch for this worker: within its limits, and small enough that every
    // live worker gets several parts (so a slow or dying worker holds back little).
    std::vector<size_t> TakeChunk(const Worker& w) {
        const size_t alive = std::max<size_t>(1, std::count_if(workers_.begin(), workers_.end(), [](const Worker& x) { return x.alive; }));
        const size_t balance = std::max<size_t>(1, (jobs_->size() + 3 * alive - 1) / (3 * alive));
        std::vector<size_t> chunk;
        std::uint64_t work = 0, words = 0;
        while (!pending_.empty() && chunk.size() < std::min<size_t>(balance, w.limits.maxRequests)) {
            const sim::EvalJob& job = (*jobs_)[pending_.front()];
            const std::uint64_t jobWork = Work(job), jobWords = ReplyWords(job);
            if (!chunk.empty() && (work + jobWork > w.limits.maxWork || words + jobWords > w.limits.maxReplyWords)) break;
            work += jobWork;
            words += jobWords;
            chunk.push_back(pending_.front());
            pending_.pop_front();
        }
        return chunk;
    }

    kj::Promise<void> Dispatch(Worker& w) {
        std::vector<size_t> chunk = TakeChunk(w);
        w.busy = true;
        ++running_;
        if (w.local) return RunLocally(w, std::move(chunk));
        const sim::EvalJob& first = (*jobs_)[chunk.front()];
        if (Vertices(first) > w.limits.maxVertices ||
            (first.model == sim::ModelKind::Thesis && static_cast<std::uint64_t>(first.Thesis().params.iterations) > w.limits.maxIterations) ||
            Work(first) > w.limits.maxWork ||
            ReplyWords(first) > w.limits.maxReplyWords) {
            --running_;
            Lost(w, "a shape is larger than it accepts", chunk);
            return kj::READY_NOW;
        }
        auto request = KJ_ASSERT_NONNULL(w.evaluator).evaluateRequest();
        auto list = request.initRequests(static_cast<unsigned>(chunk.size()));
        for (unsigned k = 0; k < chunk.size(); ++k) SetJob(list[k], (*jobs_)[chunk[k]]);
        auto shared = std::make_shared<std::vector<size_t>>(std::move(chunk));
        auto call = request.send().then([this, shared](capnp::Response<schema::Evaluator::EvaluateResults> response) {
            const auto responses = response.getResponses();
            if (responses.size() != shared->size()) KJ_FAIL_REQUIRE("answered a different number of shapes");
            std::vector<sim::SimResult> results(responses.size());
            for (unsigned k = 0; k < responses.size(); ++k) results[k] = GetResponse(responses[k]);
            for (unsigned k = 0; k < results.size(); ++k) ready_.emplace((*shared)[k], std::move(results[k]));
        });
        return WithTimeout(kj::mv(call))
            .then([this, &w]() {
                    w.busy = false;
                    --running_;
                    Wake();
                },
                  [this, &w, shared](kj::Exception&& e) {
                      --running_;
                      Lost(w, e.getDescription().cStr(), *shared);
                      Wake();
                  })
            .eagerlyEvaluate(nullptr);
    }

    // This machine's part runs on its own threads while the servers work; the event loop hears of
    // it through a cross-thread promise.
    kj::Promise<void> RunLocally(Worker& w, std::vector<size_t> chunk) {
        std::vector<sim::EvalJob> jobs;
        for (size_t j : chunk) jobs.push_back((*jobs_)[j]);
        auto paf = kj::newPromiseAndCrossThreadFulfiller<std::vector<sim::SimResult>>();
        auto fulfiller = std::make_shared<kj::Own<kj::CrossThreadPromiseFulfiller<std::vector<sim::SimResult>>>>(kj::mv(paf.fulfiller));
        const int threads = options_.localThreads > 0 ? options_.localThreads : sim::HardwareThreads();
        std::thread([jobs = std::move(jobs), fulfiller, threads]() mutable {
            std::vector<sim::SimResult> results(jobs.size());
            EvaluateInOrder(jobs, 0, jobs.size(), threads, 4 * static_cast<size_t>(threads),
                            [&](size_t k, sim::SimResult&& r) { results[k] = std::move(r); });
            (*fulfiller)->fulfill(std::move(results));
        }).detach();
        return paf.promise
            .then([this, &w, chunk = std::move(chunk)](std::vector<sim::SimResult> results) {
                for (size_t k = 0; k < results.size(); ++k) ready_.emplace(chunk[k], std::move(results[k]));
                w.busy = false;
                --running_;
                Wake();
            })
            .eagerlyEvaluate(nullptr);
    }

    WorkerPoolOptions options_;
    std::vector<Worker> workers_;
    bool localOnly_ = false;
    kj::Maybe<kj::WaitScope&> waitScope_;
    kj::Maybe<kj::Timer&> timer_;
    const std::vector<sim::EvalJob>* jobs_ = nullptr;
    std::deque<size_t> pending_;
    std::map<size_t, sim::SimResult> ready_;
    int running_ = 0;
    kj::Own<kj::PromiseFulfiller<void>> wake_;
};

}  // namespace

std::unique_ptr<Evaluator> MakeWorkerPool(const WorkerPoolOptions& options) { return std::make_unique<WorkerPool>(options); }

}  // namespace app
