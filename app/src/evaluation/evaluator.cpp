#include "evaluation/evaluator.h"

#include <atomic>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

namespace app {
namespace {

class LocalEvaluator final : public Evaluator {
public:
    explicit LocalEvaluator(int threads) : threads_(threads > 0 ? threads : sim::HardwareThreads()) {}
    void Evaluate(const std::vector<sim::EvalJob>& jobs, const ResultSink& sink) override {
        EvaluateInOrder(jobs, 0, jobs.size(), threads_, 4 * static_cast<size_t>(threads_), sink);
    }
    std::string Describe() const override { return std::to_string(threads_) + (threads_ == 1 ? " thread" : " threads"); }

private:
    int threads_;
};

}  // namespace

std::vector<sim::SimResult> Evaluator::EvaluateAll(const std::vector<sim::EvalJob>& jobs) {
    std::vector<sim::SimResult> results(jobs.size());
    Evaluate(jobs, [&](size_t index, sim::SimResult&& result) { results[index] = std::move(result); });
    return results;
}

std::unique_ptr<Evaluator> MakeLocalEvaluator(int threads) { return std::make_unique<LocalEvaluator>(threads); }

void EvaluateInOrder(const std::vector<sim::EvalJob>& jobs, size_t begin, size_t end, int threads, size_t window, const ResultSink& done) {
    if (begin >= end) return;
    threads = std::max(1, std::min<int>(threads, static_cast<int>(end - begin)));
    window = std::max<size_t>(window, static_cast<size_t>(threads));
    std::mutex mutex;
    std::condition_variable changed;
    std::map<size_t, sim::SimResult> ready;  // finished, waiting for an earlier job
    size_t next = begin;                      // next job to start
    size_t delivered = begin;                 // next job to hand to `done`
    bool stop = false;

    auto worker = [&] {
        for (;;) {
            size_t j;
            {
                std::unique_lock lock(mutex);
                // Do not run ahead of the consumer by more than the window: memory stays bounded.
                changed.wait(lock, [&] { return stop || next >= end || next < delivered + window; });
                if (stop || next >= end) return;
                j = next++;
            }
            sim::SimResult result = sim::Evaluate(jobs[j]);
            {
                std::lock_guard lock(mutex);
                ready.emplace(j, std::move(result));
            }
            changed.notify_all();
        }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);

    std::exception_ptr failure;
    while (delivered < end) {
        sim::SimResult result;
        {
            std::unique_lock lock(mutex);
            changed.wait(lock, [&] { return ready.count(delivered) != 0; });
            result = std::move(ready.at(delivered));
            ready.erase(delivered);
        }
        const size_t index = delivered;
        try {
            done(index, std::move(result));
        } catch (...) {
            failure = std::current_exception();
        }
        {
            std::lock_guard lock(mutex);
            ++delivered;
            if (failure) stop = true;
        }
        changed.notify_all();
        if (failure) break;
    }
    for (auto& thread : pool) thread.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace app
