// The experiment runner and results folders in process: every kind runs through the one evaluator
// into one archive; a resume under an edited experiment is refused; a folder is owned by one run.
#include "experiments/experiment_runner.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "formats/archive.h"
#include "support/errors.h"
#include "formats/files.h"
#include "process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

class Runner : public ::testing::Test {
protected:
    Runner() : folder_(::testing::UnitTest::GetInstance()->current_test_info()->name()) {}

    app::ExperimentOutcome RunIn(const std::string& text, const std::string& name, bool resume = false, std::vector<app::Override> overrides = {}) {
        const app::Experiment e = app::ParseExperiment(text, name + ".json", overrides);
        app::ResultsFolder results(folder_.Path() / name, resume ? app::FolderMode::Resume : app::FolderMode::Fresh, "test");
        app::RunOptions options;
        options.evaluator = evaluator_.get();
        options.resume = resume;
        options.progress = false;
        options.folder = &results;
        return app::RunExperiment(e, results.Dir(), options);
    }

    testing_support::TempFolder folder_;
    std::unique_ptr<app::Evaluator> evaluator_ = app::MakeLocalEvaluator(2);
};

const char* kSweep = R"({"model": {"name": "thesis"}, "id": "s", "sim": {"iterations": 500}, "render": {"figures": false, "thumbnails": false},
    "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1, 2, 3]}]},
    "thesis_result": {"points": [{"amplitude": 2.5, "fitness": 0.3}]}})";
const char* kList = R"({"model": {"name": "thesis"}, "id": "l", "sim": {"iterations": 500, "load": "stretch"}, "render": {"figures": false, "thumbnails": false},
    "evaluate": {"shapes": [{"family": "cylinder", "thesis_fitness": -1}, {"family": "sine", "amplitude": 2, "phase": [0.5, 2.6]}]}})";
const char* kGa = R"({"model": {"name": "thesis"}, "id": "g", "sim": {"iterations": 300}, "render": {"figures": false, "thumbnails": false},
    "evolve": {"population": 4, "generations": 2, "genome": {"kind": "bspline", "length": [4, 6]}}})";

}  // namespace

TEST_F(Runner, EveryKindRecordsEveryEvaluationUnderOneId) {
    const auto sweep = RunIn(kSweep, "sweep");
    EXPECT_EQ(sweep.simulations, 4);  // three grid points and the thesis's table point
    const auto records = app::ReadArchive((folder_.Path() / "sweep" / "evaluations.capnp").string(), false).records;
    ASSERT_EQ(records.size(), 4u);
    EXPECT_EQ(records[3].role, app::Role::ThesisPoint);
    EXPECT_EQ(std::get<sim::SineShape>(records[3].job.shape).amplitude, 2.5);
    const auto point = std::find_if(sweep.rows.begin(), sweep.rows.end(), [](const app::ComparisonRow& row) { return row.quantity == "fitness at amplitude 2.5"; });
    ASSERT_NE(point, sweep.rows.end());
    EXPECT_EQ(point->thesis, 0.3);

    const auto list = RunIn(kList, "list");
    EXPECT_EQ(list.simulations, 2);
    EXPECT_EQ(list.rows[0].thesis, -1);
    EXPECT_LT(list.rows[0].ours, 0);  // a stretched cylinder lengthens

    const auto ga = RunIn(kGa, "ga");
    const auto gaRecords = app::ReadArchive((folder_.Path() / "ga" / "evaluations.capnp").string(), false).records;
    EXPECT_EQ(static_cast<long long>(gaRecords.size()), ga.simulations);
    for (size_t k = 0; k < gaRecords.size(); ++k) EXPECT_EQ(gaRecords[k].role, app::Role::Individual) << k;
}

TEST_F(Runner, AResumeUnderAnEditedExperimentIsRefusedNamingTheChange) {
    RunIn(kSweep, "sweep");
    try {
        RunIn(kSweep, "sweep", true, {{"sim.iterations", "600"}});
        ADD_FAILURE() << "accepted";
    } catch (const app::UsageError& error) {
        EXPECT_THAT(error.what(), HasSubstr("sim.iterations: '500' -> '600'"));
    }
    // Unchanged, it resumes (and, being finished, only redoes its final steps).
    EXPECT_EQ(RunIn(kSweep, "sweep", true).simulations, 1);  // the thesis point after the grid
}

TEST_F(Runner, AFolderIsOwnedByOneRunAndNeverMixed) {
    const fs::path dir = folder_.Path() / "owned";
    {
        app::ResultsFolder first(dir, app::FolderMode::Fresh, "test");
        // A second run into the same folder while the first holds it is refused, naming the holder.
        try {
            app::ResultsFolder second(dir, app::FolderMode::Overwrite, "test");
            ADD_FAILURE() << "a second run took the folder";
        } catch (const app::UsageError& error) {
            EXPECT_THAT(error.what(), HasSubstr("in use by pid " + std::to_string(getpid())));
        }
        app::WriteFileAtomically((dir / "result.txt").string(), "one");
    }
    EXPECT_THROW(app::ResultsFolder(dir, app::FolderMode::Fresh, "test"), app::UsageError);
    EXPECT_THROW(app::ResultsFolder(folder_.Path() / "none", app::FolderMode::Resume, "test"), app::UsageError);
    // --overwrite: the old results survive a run that ends before its first result...
    { app::ResultsFolder replacing(dir, app::FolderMode::Overwrite, "test"); }
    EXPECT_EQ(testing_support::Slurp(dir / "result.txt"), "one");
    // ...and go once it has one.
    {
        app::ResultsFolder replacing(dir, app::FolderMode::Overwrite, "test");
        EXPECT_FALSE(fs::exists(dir / "result.txt"));
        replacing.FirstResultDone();
    }
    EXPECT_FALSE(fs::exists(dir / "result.txt"));
    for (const auto& e : fs::directory_iterator(folder_.Path())) EXPECT_THAT(e.path().filename().string(), ::testing::Not(HasSubstr("replaced")));
}

TEST_F(Runner, StaleTemporariesOfDeadProcessesAreRemoved) {
    const fs::path dir = folder_.Path() / "stale";
    fs::create_directories(dir);
    // A pid that cannot be alive (beyond pid_max), and our own, which is.
    testing_support::Slurp(dir);  // nothing
    std::ofstream(dir / ".act4194305-0.tmp") << "half";
    std::ofstream(dir / (".act" + std::to_string(getpid()) + "-0.tmp")) << "mine";
    app::RemoveStaleTemporaries(dir);
    EXPECT_FALSE(fs::exists(dir / ".act4194305-0.tmp"));
    EXPECT_TRUE(fs::exists(dir / (".act" + std::to_string(getpid()) + "-0.tmp")));
}
