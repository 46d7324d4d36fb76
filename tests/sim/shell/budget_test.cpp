// The per-evaluation Newton budget (SolverDef::newtonBudget): counted, not timed, so an evaluation
// ends the same way on every machine and at every thread count; a design that needs more is the
// status budget-exceeded, a failed design to every optimizer.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/batch.h"
#include "sim/model.h"
#include "sim/optimize.h"

namespace {

// A short braided sine bulb with its isobaric test: every stage that spends Newton iterations runs
// (the load path, the stability check, the blocking force, the held strokes).
sim::EvalJob BraidedBulb(int budget) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Membrane);
    job.shape = sim::SineShape{1.5, 0.5, std::numbers::pi - 0.5};
    sim::ShellDef& def = job.Shell();
    def.geometry.lengthMm = 40;
    def.geometry.ringVertices = 24;
    def.geometry.rings = 12;
    def.load.pressureKpa = 1;
    def.load.steps = 2;
    def.load.isobaricPoints = 3;
    def.fibres.layout = sim::FibreLayout::Braid;
    def.fibres.angleDeg = 35;
    def.solver.newtonBudget = budget;
    return job;
}

TEST(NewtonBudget, ADesignWithinItIsUntouchedAndOneIterationLessFailsIt) {
    const sim::SimResult free = sim::Evaluate(BraidedBulb(0));  // no budget
    ASSERT_EQ(free.status, sim::Status::Ok);
    const int needed = free.shell.newtonIterations;
    ASSERT_GT(needed, 10);

    const sim::SimResult exact = sim::Evaluate(BraidedBulb(needed));
    EXPECT_EQ(exact.status, sim::Status::Ok);
    EXPECT_EQ(exact.shell.newtonIterations, needed);
    EXPECT_EQ(exact.contractionPercent, free.contractionPercent) << "a budget that holds changes nothing";
    EXPECT_EQ(exact.shell.blockingForceN, free.shell.blockingForceN);
    EXPECT_EQ(exact.shell.isobaricForceN, free.shell.isobaricForceN);

    // Short by one, by a held stroke's worth, or spent inside the load path: each is a failed design
    // that never spends more than its budget.
    for (int budget : {needed - 1, needed / 2, 3}) {
        const sim::SimResult r = sim::Evaluate(BraidedBulb(budget));
        EXPECT_EQ(r.status, sim::Status::BudgetExceeded) << budget;
        EXPECT_LE(r.shell.newtonIterations, budget);
        EXPECT_TRUE(std::isnan(r.fitness) && std::isnan(r.contractionPercent)) << "a failed design reads as no number";
        EXPECT_TRUE(std::isnan(sim::ObjectiveValue(sim::ObjectiveKind::Contraction, r, nullptr)));
        EXPECT_STREQ(sim::Name(r.status), "budget-exceeded");
    }
}

TEST(NewtonBudget, TheVerdictIsTheSameWhateverTheThreads) {
    std::vector<sim::EvalJob> jobs;
    for (int budget : {0, 5, 12, 20, 40, 80}) jobs.push_back(BraidedBulb(budget));
    const std::vector<sim::SimResult> one = sim::EvaluateBatch(jobs, 1), two = sim::EvaluateBatch(jobs, 2);
    ASSERT_EQ(one.size(), two.size());
    for (size_t k = 0; k < one.size(); ++k) {
        EXPECT_EQ(one[k].status, two[k].status) << k;
        EXPECT_EQ(one[k].shell.newtonIterations, two[k].shell.newtonIterations) << k;
    }
}

TEST(NewtonBudget, ANegativeBudgetIsRefused) {
    sim::ShellDef def = sim::DefaultShellDef();
    def.solver.newtonBudget = -1;
    EXPECT_NE(sim::ShellDefError(def).find("budget"), std::string::npos);
}

}  // namespace
