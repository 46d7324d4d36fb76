// The one evaluation path: results arrive in job order on the calling thread, equal whatever the
// thread count, with a bounded number waiting, and a failing sink stops the work cleanly.
#include "evaluation/evaluator.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>

namespace {

std::vector<sim::EvalJob> Jobs(int count) {
    std::vector<sim::EvalJob> jobs;
    for (int k = 0; k < count; ++k) {
        sim::SimParams params;
        params.iterations = 50 + 37 * (k % 5);  // uneven work, so jobs finish out of order
        jobs.push_back({sim::SineShape{1 + 0.2 * k, 0.5, 2.6}, sim::ModelKind::Thesis, sim::ThesisDef{sim::MeshDef{12, 8}, params}});
    }
    return jobs;
}

}  // namespace

TEST(Evaluator, ResultsArriveInJobOrderOnTheCallingThreadWhateverTheThreads) {
    const auto jobs = Jobs(40);
    std::vector<std::uint64_t> hashes[2];
    int slot = 0;
    for (int threads : {1, 3}) {
        const auto caller = std::this_thread::get_id();
        size_t expected = 0;
        app::MakeLocalEvaluator(threads)->Evaluate(jobs, [&](size_t index, sim::SimResult&& r) {
            EXPECT_EQ(index, expected++);
            EXPECT_EQ(std::this_thread::get_id(), caller);
            hashes[slot].push_back(sim::PositionsHash(r.final));
        });
        EXPECT_EQ(expected, jobs.size());
        ++slot;
    }
    EXPECT_EQ(hashes[0], hashes[1]);
}

TEST(Evaluator, AtMostAWindowOfResultsWaits) {
    const auto jobs = Jobs(30);
    size_t delivered = 0;
    // A slow consumer: the workers must wait for it rather than pile results up.
    app::EvaluateInOrder(jobs, 0, jobs.size(), 3, 4, [&](size_t index, sim::SimResult&&) {
        EXPECT_EQ(index, delivered++);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    });
    EXPECT_EQ(delivered, jobs.size());
}

TEST(Evaluator, AFailingSinkStopsTheWork) {
    const auto jobs = Jobs(50);
    size_t seen = 0;
    EXPECT_THROW(app::MakeLocalEvaluator(2)->Evaluate(jobs,
                                                      [&](size_t index, sim::SimResult&&) {
                                                          ++seen;
                                                          if (index == 4) throw std::runtime_error("disk full");
                                                      }),
                 std::runtime_error);
    EXPECT_EQ(seen, 5u);
}
