#include "sim/batch.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>

namespace sim {

double SweepValue(const EvalJob& job, SweepParameter parameter) {
    if (parameter == SweepParameter::PressureKpa) return job.model == ModelKind::Thesis ? NAN : job.Shell().load.pressureKpa;
    if (parameter == SweepParameter::FibreAngleDeg) return job.model == ModelKind::Thesis ? NAN : job.Shell().fibres.angleDeg;
    return SweepParameterValue(job.shape, parameter);
}

EvalJob WithSweepValue(EvalJob job, SweepParameter parameter, double value) {
    if (parameter == SweepParameter::PressureKpa) job.Shell().load.pressureKpa = value;
    else if (parameter == SweepParameter::FibreAngleDeg) job.Shell().fibres.angleDeg = value;
    else job.shape = WithSweepParameter(job.shape, parameter, value);
    return job;
}

std::vector<EvalJob> SweepJobs(const SweepDef& def, const EvalJob& base) {
    std::vector<EvalJob> jobs{base};
    jobs.front().shape = def.base;
    for (const SweepAxis& axis : def.axes) {
        std::vector<EvalJob> next;
        for (const EvalJob& job : jobs)
            for (double value : axis.values) next.push_back(WithSweepValue(job, axis.parameter, value));
        jobs = std::move(next);
    }
    return jobs;
}

int HardwareThreads() { return std::max(1u, std::thread::hardware_concurrency()); }

void ParallelFor(int count, int threads, const std::function<void(int)>& task) {
    if (threads <= 0) threads = HardwareThreads();
    threads = std::max(1, std::min(threads, count));
    // Workers take the next index until none is left.
    std::atomic<int> next{0};
    auto worker = [&] {
        for (int i = next++; i < count; i = next++) task(i);
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& thread : pool) thread.join();
}

std::vector<SimResult> EvaluateBatch(const std::vector<EvalJob>& jobs, int threads, const BatchProgress& onDone) {
    const int total = static_cast<int>(jobs.size());
    std::vector<SimResult> results(jobs.size());
    // Each result lands in its job's slot, so the output does not depend on which thread ran what or
    // in which order jobs finished.
    std::mutex progressMutex;
    int done = 0;
    ParallelFor(total, threads, [&](int j) {
        results[j] = Evaluate(jobs[j]);
        if (onDone) {
            std::lock_guard lock(progressMutex);
            onDone(++done, total, results[j]);
        }
    });
    return results;
}

}  // namespace sim
