// The thesis's numbers as the experiment files hold them, re-read from the thesis's text: each table
// row's genome and fitness against the row as the text extraction prints it (digits in order, the
// length column equal to the genes), the stretch tests' genomes equal to the tables they come from,
// and the report checker (thesis_report_check.h) shown to catch what it is meant to catch.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/errors.h"
#include "experiments/experiment.h"
#include "app/report/thesis_report_check.h"

namespace fs = std::filesystem;
using ::testing::IsEmpty;

namespace {

app::Experiment Load(const std::string& name) { return app::LoadExperiment((fs::path(ACTUATOR_ASSETS_DIR) / "experiments" / name).string(), {}); }

std::string Squeezed(const std::string& text) {
    std::string out;
    for (char c : text)
        if (!std::isspace(static_cast<unsigned char>(c)) && c != '[' && c != ']') out += c;
    return out;
}

std::string Digits(const app::LabelledShape& design) {
    std::string out;
    for (const auto& spline : std::get<sim::BSplineShape>(design.shape).splines)
        for (double c : spline) out += fmt::format("{:g}", c);
    return out;
}

// The thesis's text beside the checkout (../shared/source), when this machine has it.
std::string ThesisText() {
    for (fs::path dir = fs::path(ACTUATOR_ASSETS_DIR).parent_path(); !dir.empty() && dir != dir.root_path(); dir = dir.parent_path()) {
        const fs::path file = dir.parent_path() / "shared" / "source" / "thesis-2019-soft-pneumatic-actuators.txt";
        std::ifstream in(file);
        if (in) return std::string(std::istreambuf_iterator<char>(in), {});
        if (dir.parent_path() == dir) break;
    }
    return "";
}

const char* kGaFiles[] = {"5.1_bspline_entire.json", "5.2_bspline_middle.json", "5.3_two_bsplines_middle.json", "5.4_four_bsplines_middle.json"};

TEST(ThesisData, EveryGenomeMatchesItsTableRowDigitForDigit) {
    int specimens = 0;
    for (const char* name : kGaFiles) {
        const app::Experiment e = Load(name);
        ASSERT_EQ(e.thesisResult.specimens.size(), e.thesisResult.runBest.size()) << name << ": a genome for every run the table lists";
        for (const auto& s : e.thesisResult.specimens) {
            ++specimens;
            EXPECT_EQ(app::ControlPointCount(s.design.shape), static_cast<size_t>(s.length)) << s.design.label << ": the table's length column";
            EXPECT_EQ(s.design.thesisFitness, e.thesisResult.runBest.at(s.run - 1)) << s.design.label;
            // Run number, fitness, genes and length, in the order the extraction prints them.
            EXPECT_EQ(Squeezed(s.design.source), fmt::format("{}{:g}{}{}", s.run, s.design.thesisFitness, Digits(s.design), s.length)) << s.design.label;
        }
    }
    EXPECT_EQ(specimens, 1 + 3 + 3 + 3);
}

TEST(ThesisData, TableFiveSixIsReadAsOnePointZeroSevenAndTheLengthsComeOutAsPrinted) {
    const app::Experiment e = Load("5.3_two_bsplines_middle.json");
    EXPECT_EQ(e.thesisResult.runBest, (std::vector<double>{1.07, 1.07, 1.09}));
    std::vector<int> lengths;
    for (const auto& s : e.thesisResult.specimens) lengths.push_back(s.length);
    EXPECT_EQ(lengths, (std::vector<int>{17, 24, 32}));
}

TEST(ThesisData, EveryNumberIsInTheThesisTextWhereItsSourceSaysWhenTheTextIsAtHand) {
    std::vector<std::string> sources;
    std::vector<double> values;
    for (const auto& entry : fs::directory_iterator(fs::path(ACTUATOR_ASSETS_DIR) / "experiments")) {
        if (entry.path().extension() != ".json") continue;
        const app::Experiment e = app::LoadExperiment(entry.path().string(), {});
        for (const auto& s : e.thesisResult.specimens) sources.push_back(s.design.source), values.push_back(s.design.thesisFitness);
        for (const auto& p : e.thesisResult.points) sources.push_back(p.source), values.push_back(p.fitness);
        for (const auto& s : e.shapes) sources.push_back(s.source), values.push_back(s.thesisFitness);
    }
    ASSERT_GE(sources.size(), 10u + 5 + 7);
    for (size_t k = 0; k < sources.size(); ++k) {
        EXPECT_FALSE(sources[k].empty()) << "a thesis number without the row it was read from: " << values[k];
        EXPECT_NE(Squeezed(sources[k]).find(Squeezed(fmt::format("{:g}", values[k]))), std::string::npos) << sources[k] << " does not print " << values[k];
    }
    const std::string thesis = Squeezed(ThesisText());
    if (thesis.empty()) GTEST_SKIP() << "the thesis's text (../shared/source/) is not beside this checkout";
    for (const auto& source : sources) EXPECT_NE(thesis.find(Squeezed(source)), std::string::npos) << "not in the thesis's text: " << source;
}

TEST(ThesisData, TheStretchTestsUseTheBestGenomeOfEachTable) {
    const app::Experiment stretch = Load("6.2_stretch_bsplines.json");
    ASSERT_EQ(stretch.shapes.size(), 4u);
    const std::pair<const char*, int> from[] = {{"5.1_bspline_entire.json", 1}, {"5.2_bspline_middle.json", 3}, {"5.3_two_bsplines_middle.json", 3},
                                               {"5.4_four_bsplines_middle.json", 1}};
    for (size_t k = 0; k < 4; ++k) {
        const app::Experiment table = Load(from[k].first);
        const auto& specimen = table.thesisResult.specimens.at(static_cast<size_t>(from[k].second - 1));
        // The best run of each table is the one stretched (Table 6.2's four rows).
        for (double other : table.thesisResult.runBest) EXPECT_LE(other, specimen.design.thesisFitness) << from[k].first;
        EXPECT_EQ(stretch.shapes[k].shape, specimen.design.shape) << stretch.shapes[k].label << " against " << specimen.design.label;
    }
}

TEST(ThesisData, AGenomeWhoseLengthDisagreesWithItsTableIsRefused) {
    const std::string file = (fs::temp_directory_path() / "thesis_length_test.json").string();
    std::ofstream(file) << R"({"model": {"name": "thesis"}, "id": "x", "evolve": {"genome": {"kind": "bspline"}},
        "thesis_result": {"run_best": [1.0], "specimens": [{"run": 1, "thesis_fitness": 1.0, "length": 5, "family": "bspline", "control_points": [[1, 2, 3, 4]]}]}})";
    try {
        app::LoadExperiment(file, {});
        ADD_FAILURE() << "accepted";
    } catch (const app::UsageError& error) {
        EXPECT_THAT(error.what(), ::testing::HasSubstr("4 control points, but the table's length column says 5"));
    }
    fs::remove(file);
}

TEST(ThesisReportCheck, CatchesAFalseRelationAWrongVerdictAMissingItemAndWrongCounts) {
    const std::string header = "2 claims of the thesis's tables, figures and analyses: **1 reproduced, 0 explained differences, 1 unexplained**; and 1 settings tables followed\n\n"
                               "| thesis | claim | thesis value | ours | difference | tolerance | verdict | reason (computed from this run) |\n"
                               "|---|---|---:|---:|---:|---:|---|---|\n";
    const std::string good = header + "| [Figure 4.1](#a) | x | 0.75 | 0.74 | -0.01 | 0.0375 | reproduced |  |\n"
                                      "| [Table 4.4](#a), Figure 4.6 | y | 1.74 | 1.999 ([figure](a/x.png), [Figure 4.6](a/y.png)) | +0.26 | 0.087 | unexplained | 1.999 differs from 1.74 by more than 0.087 |\n"
                                      "| [Table 4.1](#a) | settings | - | as printed | - | - | followed |  |\n";
    const auto problems = testing_support::ThesisReportProblems(good);
    // Only the items this small table lacks: a figure listed beside a table's claim has its row.
    for (const auto& p : problems) EXPECT_THAT(p, ::testing::EndsWith("has no row"));
    EXPECT_EQ(problems.size(), 33u - 4);
    auto count = [](const std::string& report, const std::string& what) {
        int n = 0;
        for (const auto& p : testing_support::ThesisReportProblems(report)) n += p.find(what) != std::string::npos;
        return n;
    };
    std::string lie = good;
    lie.replace(lie.find("differs from 1.74 by more than"), 30, "is within 0.5 of 1.74 and yes");
    EXPECT_EQ(count(lie, "false:"), 0) << "1.999 is within 0.5 of 1.74 is true";
    lie = good;
    lie.replace(lie.find("1.999 differs from 1.74 by more than 0.087"), 42, "1.999 is within 0.087 of 1.74");
    EXPECT_EQ(count(lie, "false: '1.999 is within 0.087 of 1.74'"), 1);
    std::string wrongVerdict = good;
    wrongVerdict.replace(wrongVerdict.find("| 0.74 |"), 8, "| 0.60 |");
    EXPECT_EQ(count(wrongVerdict, "'reproduced', yet"), 1);
    std::string wrongCount = good;
    wrongCount.replace(wrongCount.find("**1 reproduced"), 14, "**2 reproduced");
    EXPECT_EQ(count(wrongCount, "summary's counts"), 1);
    std::string settingsReproduced = good;
    settingsReproduced.replace(settingsReproduced.find("| followed |"), 12, "| reproduced |");
    EXPECT_EQ(count(settingsReproduced, "a settings table judged 'reproduced'"), 1);
    EXPECT_EQ(count(settingsReproduced, "summary's counts"), 1);
    std::string noVerdict = good;
    noVerdict.replace(noVerdict.find("| reproduced |"), 14, "|  |");
    EXPECT_EQ(count(noVerdict, "no verdict"), 1);
}

}  // namespace
