// Evaluation archives: exact round trips, reading a file cut off at any byte, and refusing garbage.
#include "archive.h"
#include "cli_options.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <numbers>

namespace fs = std::filesystem;

namespace {

class Archive : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("actuator_archive_" + std::to_string(getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        path_ = (dir_ / "evaluations.capnp").string();
    }
    void TearDown() override { fs::remove_all(dir_); }

    static app::ArchivedEvaluation Sample(int k) {
        const sim::MeshDef mesh{12, 6};
        sim::SimParams params = sim::DefaultSimParams();
        params.iterations = 300 + k;
        params.load = k % 2 ? sim::Load::Stretch : sim::Load::Inflate;
        const sim::Genome genome{{1.0 + k, 2, 3, 4, 5}, {8, 0, 4, 4}};
        const sim::Shape shape = k == 2 ? sim::Shape(sim::SineShape{4.1, 0.5, std::numbers::pi - 0.5}) : sim::Shape(sim::BSplineShape{sim::SplineRegion::Middle, genome});
        const auto result = sim::Evaluate(shape, mesh, params);
        app::ArchivedEvaluation a;
        a.experiment = "test";
        a.run = k;
        a.generation = 10 + k;
        a.label = "sample " + std::to_string(k);
        a.shape = shape;
        a.params = params;
        a.mesh = mesh;
        app::SetResult(a, result);
        return a;
    }

    fs::path dir_;
    std::string path_;
};

}  // namespace

TEST_F(Archive, RoundTripKeepsEveryField) {
    {
        app::ArchiveWriter writer(path_);
        for (int k = 0; k < 3; ++k) writer.Append(Sample(k));
        EXPECT_EQ(writer.Count(), 3u);
    }
    const auto contents = app::ReadArchive(path_);
    EXPECT_FALSE(contents.truncated) << contents.problem;
    ASSERT_EQ(contents.evaluations.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        const auto expected = Sample(k);
        const auto& got = contents.evaluations[k];
        EXPECT_EQ(got.index, static_cast<std::uint64_t>(k));
        EXPECT_EQ(got.experiment, expected.experiment);
        EXPECT_EQ(got.run, expected.run);
        EXPECT_EQ(got.generation, expected.generation);
        EXPECT_EQ(got.label, expected.label);
        EXPECT_EQ(sim::ShapeName(got.shape), sim::ShapeName(expected.shape));
        EXPECT_EQ(got.params.iterations, expected.params.iterations);
        EXPECT_EQ(got.params.load, expected.params.load);
        EXPECT_EQ(got.params.springConstant, expected.params.springConstant);
        EXPECT_EQ(got.mesh.resolution, 12);
        EXPECT_EQ(got.fitness, expected.fitness);  // doubles exactly
        EXPECT_EQ(got.status, expected.status);
        EXPECT_EQ(got.iterationsRun, expected.iterationsRun);
        ASSERT_EQ(got.final.Size(), 72);
        for (int i = 0; i < 72; ++i) {  // meshes as float32
            EXPECT_EQ(got.final.z[i], static_cast<double>(static_cast<float>(expected.final.z[i])));
            EXPECT_EQ(got.initial.x[i], static_cast<double>(static_cast<float>(expected.initial.x[i])));
        }
        if (k == 2) {
            const auto& sine = std::get<sim::SineShape>(got.shape);
            EXPECT_EQ(sine.amplitude, 4.1);
        } else {
            EXPECT_EQ(std::get<sim::BSplineShape>(got.shape).splines, std::get<sim::BSplineShape>(expected.shape).splines);
        }
    }
    // Appending later continues the numbering.
    app::ArchiveWriter again(path_);
    again.Append(Sample(0));
    EXPECT_EQ(app::ReadArchive(path_).evaluations.back().index, 3u);
}

TEST_F(Archive, ACutOffArchiveReadsUpToItsLastCompleteEvaluation) {
    std::vector<std::uintmax_t> ends;
    {
        app::ArchiveWriter writer(path_);
        for (int k = 0; k < 3; ++k) {
            writer.Append(Sample(k));
            ends.push_back(fs::file_size(path_));
        }
    }
    std::ifstream in(path_, std::ios::binary);
    const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Cut the file at many places inside the last two messages: what is complete is read, the rest is
    // reported as truncated, and nothing crashes.
    for (std::uintmax_t cut = ends[0] - 5; cut < whole.size(); cut += 97) {
        std::ofstream(path_, std::ios::binary | std::ios::trunc).write(whole.data(), static_cast<std::streamsize>(cut));
        const auto contents = app::ReadArchive(path_, false);
        const size_t complete = cut >= ends[1] ? 2 : cut >= ends[0] ? 1 : 0;
        EXPECT_EQ(contents.evaluations.size(), complete) << "cut at " << cut;
        EXPECT_TRUE(contents.truncated) << "cut at " << cut;
    }
}

TEST_F(Archive, GarbageIsReportedNotCrashedOn) {
    std::string garbage;
    for (int i = 0; i < 5000; ++i) garbage += static_cast<char>((i * 7919 + 13) & 0xff);
    std::ofstream(path_, std::ios::binary) << garbage;
    const auto contents = app::ReadArchive(path_);
    EXPECT_TRUE(contents.truncated);
    EXPECT_TRUE(contents.evaluations.empty());
    EXPECT_FALSE(contents.problem.empty());
    EXPECT_THROW(app::ReadArchive((dir_ / "missing.capnp").string()), app::UsageError);
}
