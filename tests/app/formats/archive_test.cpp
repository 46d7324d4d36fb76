// Evaluation archives: exact round trips, a file cut off at any byte read up to its last whole
// record, a damaged record told apart from a cut-off one, resume truncation, version-1 archives,
// and garbage refused rather than crashed on.
#include "formats/archive.h"

#include <capnp/message.h>
#include <capnp/serialize-packed.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <kj/io.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "support/errors.h"
#include "formats/schema_convert.h"
#include "process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

class Archive : public ::testing::Test {
protected:
    Archive() : folder_(::testing::UnitTest::GetInstance()->current_test_info()->name()), path_(folder_ / "evaluations.capnp") {}

    static app::ArchiveRecord Sample(int k) {
        app::ArchiveRecord a;
        a.job.Thesis().mesh = sim::MeshDef{12, 6};
        a.job.Thesis().params = sim::DefaultSimParams();
        a.job.Thesis().params.iterations = 300 + k;
        a.job.Thesis().params.load = k % 2 ? sim::Load::Stretch : sim::Load::Inflate;
        a.job.Thesis().params.precision = k == 1 ? sim::Precision::Double : sim::Precision::Float;
        const sim::Genome genome{{1.0 + k, 2, 3, 4, 5}, {8, 0, 4, 4}};
        a.job.shape = k == 2 ? sim::Shape(sim::SineShape{4.1, 0.5, std::numbers::pi - 0.5}) : sim::Shape(sim::BSplineShape{sim::SplineRegion::Middle, genome});
        a.result = sim::Evaluate(a.job.shape, a.job.Thesis().mesh, a.job.Thesis().params);
        a.experiment = "test";
        a.run = k;
        a.generation = 10 + k;
        a.role = k == 2 ? app::Role::Figure : app::Role::Individual;
        a.label = "sample " + std::to_string(k);
        return a;
    }
    std::string Bytes() const { return testing_support::Slurp(path_); }
    void Put(const std::string& bytes) const { std::ofstream(path_, std::ios::binary | std::ios::trunc) << bytes; }

    testing_support::TempFolder folder_;
    std::string path_;
};

}  // namespace

TEST_F(Archive, RoundTripKeepsEveryFieldAndMeshesExactly) {
    {
        app::ArchiveWriter writer(path_);
        for (int k = 0; k < 3; ++k) {
            auto sample = Sample(k);
            EXPECT_EQ(writer.Append(sample), static_cast<std::uint64_t>(k));
        }
        EXPECT_EQ(writer.Count(), 3u);
    }
    const auto contents = app::ReadArchive(path_, true);
    EXPECT_FALSE(contents.scan.tornTail || contents.scan.corrupt) << contents.scan.problem;
    ASSERT_EQ(contents.records.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        const auto expected = Sample(k);
        const auto& got = contents.records[k];
        EXPECT_EQ(got.id, static_cast<std::uint64_t>(k));
        EXPECT_EQ(got.experiment, expected.experiment);
        EXPECT_EQ(got.run, expected.run);
        EXPECT_EQ(got.generation, expected.generation);
        EXPECT_EQ(got.role, expected.role);
        EXPECT_EQ(got.label, expected.label);
        EXPECT_EQ(got.job.shape, expected.job.shape);
        EXPECT_EQ(got.job.Thesis().params.iterations, expected.job.Thesis().params.iterations);
        EXPECT_EQ(got.job.Thesis().params.load, expected.job.Thesis().params.load);
        EXPECT_EQ(got.job.Thesis().params.precision, expected.job.Thesis().params.precision);
        EXPECT_EQ(got.job.Thesis().mesh.resolution, 12);
        EXPECT_EQ(got.result.fitness, expected.result.fitness);  // doubles exactly
        EXPECT_EQ(got.result.status, expected.result.status);
        EXPECT_EQ(got.result.iterationsRun, expected.result.iterationsRun);
        // Float-solver meshes travel as float32, double-solver meshes as float64: both exact.
        EXPECT_EQ(got.result.final.x, expected.result.final.x);
        EXPECT_EQ(got.result.final.z, expected.result.final.z);
        EXPECT_EQ(got.result.initial.y, expected.result.initial.y);
    }
    // Appending later continues the numbering.
    app::ArchiveWriter again(path_);
    auto sample = Sample(0);
    EXPECT_EQ(again.Append(sample), 3u);
    EXPECT_EQ(app::ReadArchiveRecord(path_, 3).label, "sample 0");
    EXPECT_THAT([&] {
        try {
            app::ReadArchiveRecord(path_, 9);
        } catch (const app::UsageError& e) {
            return std::string(e.what());
        }
        return std::string();
    }(), HasSubstr("holds evaluations 0 to 3"));
}

TEST_F(Archive, ACutOffArchiveReadsUpToItsLastCompleteRecord) {
    std::vector<std::uintmax_t> ends;
    {
        app::ArchiveWriter writer(path_);
        for (int k = 0; k < 3; ++k) {
            auto sample = Sample(k);
            writer.Append(sample);
            ends.push_back(fs::file_size(path_));
        }
    }
    const std::string whole = Bytes();
    // Cut the file at many places: what is whole is read, the rest is a torn tail, nothing crashes.
    for (std::uintmax_t cut = 0; cut < whole.size(); cut += 37) {
        Put(whole.substr(0, cut));
        const auto contents = app::ReadArchive(path_, false);
        const size_t complete = cut >= ends[1] ? 2 : cut >= ends[0] ? 1 : 0;
        EXPECT_EQ(contents.records.size(), complete) << "cut at " << cut;
        EXPECT_EQ(contents.scan.tornTail, cut != 0 && cut != ends[0] && cut != ends[1]) << "cut at " << cut;
        EXPECT_FALSE(contents.scan.corrupt) << "cut at " << cut;
    }
}

TEST_F(Archive, ADamagedRecordIsToldApartFromACutOffOne) {
    {
        app::ArchiveWriter writer(path_);
        for (int k = 0; k < 3; ++k) {
            auto sample = Sample(k);
            writer.Append(sample);
        }
    }
    std::string bytes = Bytes();
    const size_t middle = bytes.size() / 2;
    bytes[middle] = static_cast<char>(bytes[middle] ^ 0x40);
    Put(bytes);
    const auto contents = app::ReadArchive(path_, false);
    EXPECT_TRUE(contents.scan.corrupt);
    EXPECT_FALSE(contents.scan.tornTail);
    EXPECT_THAT(contents.scan.problem, HasSubstr("checksum"));
    // A resume refuses to build on it.
    EXPECT_THROW(app::TruncateArchive(path_, 3), app::UsageError);
}

TEST_F(Archive, ResumeTruncationDropsATornTailAndRecordsPastTheCheckpoint) {
    {
        app::ArchiveWriter writer(path_);
        for (int k = 0; k < 3; ++k) {
            auto sample = Sample(k);
            writer.Append(sample);
        }
    }
    Put(Bytes() + std::string("\x40\x00\x00\x00\x12\x34", 6));  // a torn fourth record
    EXPECT_THROW(app::ArchiveWriter refused(path_), app::UsageError);  // never append after torn bytes
    app::TruncateArchive(path_, 2);
    {
        app::ArchiveWriter writer(path_);
        EXPECT_EQ(writer.Count(), 2u);
        auto sample = Sample(1);
        writer.Append(sample);
    }
    const auto contents = app::ReadArchive(path_, false);
    EXPECT_FALSE(contents.scan.tornTail || contents.scan.corrupt);
    ASSERT_EQ(contents.records.size(), 3u);
    EXPECT_EQ(contents.records[2].label, "sample 1");
    app::TruncateArchive(path_, 0);
    EXPECT_EQ(app::ArchiveWriter(path_).Count(), 0u);
}

TEST_F(Archive, VersionOneArchivesStillRead) {
    // Version 1: packed messages back to back, no header, no checksums.
    kj::VectorOutputStream bytes;
    for (int k = 0; k < 2; ++k) {
        capnp::MallocMessageBuilder message;
        auto e = message.initRoot<app::schema::Evaluation>();
        e.setIndex(static_cast<std::uint64_t>(k));
        e.setLabel("old " + std::to_string(k));
        app::SetJob(e, Sample(2).job);
        e.initResult().setFitness(0.5 + k);
        capnp::writePackedMessage(bytes, message);
    }
    Put(std::string(reinterpret_cast<const char*>(bytes.getArray().begin()), bytes.getArray().size()));
    const auto contents = app::ReadArchive(path_, false);
    EXPECT_EQ(contents.scan.version, 1);
    ASSERT_EQ(contents.records.size(), 2u);
    EXPECT_EQ(contents.records[1].label, "old 1");
    EXPECT_EQ(contents.records[1].result.fitness, 1.5);
    EXPECT_EQ(contents.records[1].role, app::Role::Grid);  // no role field then
}

TEST_F(Archive, GarbageIsRefusedNotCrashedOn) {
    std::string garbage;
    for (int i = 0; i < 5000; ++i) garbage += static_cast<char>((i * 7919 + 13) & 0xff);
    Put(garbage);
    EXPECT_THROW(app::ReadArchive(path_, true), app::UsageError);
    EXPECT_THROW(app::ReadArchive(folder_ / "missing.capnp", true), app::UsageError);
}
