#include "sim/batch.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>

namespace sim {

int HardwareThreads() { return std::max(1u, std::thread::hardware_concurrency()); }

std::vector<SimResult> EvaluateBatch(const std::vector<EvalJob>& jobs, int threads, const BatchProgress& onDone) {
    const int total = static_cast<int>(jobs.size());
    std::vector<SimResult> results(jobs.size());
    if (threads <= 0) threads = HardwareThreads();
    threads = std::max(1, std::min(threads, total));

    // Workers take the next job index; each result lands in its job's slot, so the output does not
    // depend on which thread ran what or in which order jobs finished.
    std::atomic<int> next{0};
    std::mutex progressMutex;
    int done = 0;
    auto worker = [&] {
        for (int j = next++; j < total; j = next++) {
            results[j] = Evaluate(jobs[j]);
            if (onDone) {
                std::lock_guard lock(progressMutex);
                onDone(++done, total, results[j]);
            }
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& thread : pool) thread.join();
    return results;
}

}  // namespace sim
