#include "sim/batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {
std::vector<sim::EvalJob> AmplitudeSweep(int points) {
    std::vector<sim::EvalJob> jobs;
    for (int k = 0; k < points; ++k) {
        const double amplitude = 1.0 + 9.0 * k / (points - 1);
        jobs.push_back({sim::SineShape{amplitude, 0.5, std::numbers::pi - 0.5}, sim::ModelKind::Thesis, sim::ThesisDef{}});
    }
    return jobs;
}
}  // namespace

TEST(Batch, ResultsDoNotDependOnThreadCount) {
    auto jobs = AmplitudeSweep(6);
    jobs.push_back({sim::AbsSineShape{4, 0, 4 * std::numbers::pi}, sim::ModelKind::Thesis, sim::ThesisDef{}});
    const auto one = sim::EvaluateBatch(jobs, 1);
    for (int threads : {2, 3, 8}) {
        const auto many = sim::EvaluateBatch(jobs, threads);
        ASSERT_EQ(many.size(), one.size());
        for (size_t j = 0; j < jobs.size(); ++j) {
            EXPECT_EQ(sim::PositionsHash(many[j].final), sim::PositionsHash(one[j].final)) << "job " << j << ", " << threads << " threads";
            EXPECT_EQ(many[j].fitness, one[j].fitness);
        }
    }
}

TEST(Batch, ReportsProgressForEveryJob) {
    const auto jobs = AmplitudeSweep(4);
    int calls = 0, last = 0;
    sim::EvaluateBatch(jobs, 2, [&](int done, int total, const sim::SimResult& finished) {
        EXPECT_EQ(finished.final.Size(), 900);
        ++calls;
        EXPECT_EQ(total, 4);
        EXPECT_EQ(done, last + 1);
        last = done;
    });
    EXPECT_EQ(calls, 4);
}

TEST(ThesisValues, Figure41AmplitudeSweepPeaksBetween3And5AndTurnsNegative) {
    // Thesis 4.1: A in [1, 10], 30 points, phase [0.5, pi - 0.5].
    const auto jobs = AmplitudeSweep(30);
    const auto results = sim::EvaluateBatch(jobs, 0);
    size_t best = 0;
    for (size_t j = 0; j < results.size(); ++j) {
        ASSERT_EQ(results[j].status, sim::Status::Ok) << "A=" << std::get<sim::SineShape>(jobs[j].shape).amplitude;
        if (results[j].fitness > results[best].fitness) best = j;
    }
    const double bestAmplitude = std::get<sim::SineShape>(jobs[best].shape).amplitude;
    EXPECT_GE(bestAmplitude, 3.0);
    EXPECT_LE(bestAmplitude, 5.0);
    EXPECT_NEAR(results[best].fitness, 0.59, 0.02);
    for (size_t j = 0; j < results.size(); ++j) {
        const double amplitude = std::get<sim::SineShape>(jobs[j].shape).amplitude;
        if (amplitude >= 7.5) EXPECT_LT(results[j].fitness, 0.0) << "A=" << amplitude;
    }
}
