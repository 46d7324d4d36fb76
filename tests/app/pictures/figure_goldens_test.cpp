// Visual regression of the report's figures of numbers and its contact sheet: a fitness landscape as
// a line (with the thesis's point), a heat map (diverging, with the thesis's marks), an evolution
// plot (range, interquartile band, the thesis's reference line) and a contact sheet on a sweep's
// axes. Fixed data, so only layout and drawing can change them. UPDATE_GOLDENS=1 rewrites them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "experiments/experiment.h"
#include "pictures/figures.h"
#include "pictures/plots.h"
#include "render/image.h"
#include "render/plot.h"
#include "sim/batch.h"
#include "sim/solid.h"

namespace fs = std::filesystem;

namespace {

std::vector<std::uint8_t> ReadBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Plots are flat drawings: a mark is a handful of pixels in one place, so the goldens also bound the
// differing pixels per tile (a lost zero line or failure cross fails; noise spread thin does not).
const render::ImageTolerance kPlotTolerance{24, 0.003, 12};

void ExpectMatchesGolden(const std::string& name, const render::Image& actual) {
    ASSERT_FALSE(actual.Empty());
    ASSERT_FALSE(render::IsUniform(actual)) << name << " is blank";
    const fs::path golden = fs::path(ACTUATOR_GOLDEN_DIR) / (name + ".png");
    const auto bytes = render::EncodePng(actual, 9);
    const char* update = std::getenv("UPDATE_GOLDENS");
    if (update && std::string(update) == "1") {
        std::ofstream(golden, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        return;
    }
    render::Image expected;
    std::string error;
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing; run UPDATE_GOLDENS=1 ctest -L visual to create it";
    ASSERT_TRUE(render::DecodePng(ReadBytes(golden), &expected, &error)) << error;
    const auto comparison = render::CompareImages(expected, actual, kPlotTolerance);
    if (!comparison.matches) {
        const fs::path out = fs::path(ACTUATOR_VISUAL_OUT_DIR);
        fs::create_directories(out);
        std::ofstream(out / (name + ".actual.png"), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        ADD_FAILURE() << name << ": " << comparison.Summary() << "\n  actual: " << (out / (name + ".actual.png")).string()
                      << "\n  accept the new picture with: UPDATE_GOLDENS=1 ctest -L visual";
    }
}

app::Experiment Sweep(const std::string& axes, const std::string& points) {
    return app::ParseExperiment(R"({"model": {"name": "thesis"}, "id": "G", "title": "golden", "sim": {"iterations": 2000},
        "sweep": {"shape": {"family": "abs-sine", "phase": [0, "pi"]}, "axes": )" + axes + R"(},
        "thesis_result": {"points": )" + points + "}}", "golden.json");
}

TEST(FigureGoldens, LandscapeLine) {
    const app::Experiment e = Sweep(R"([{"parameter": "amplitude", "from": 1, "to": 10, "points": 19}])", R"([{"amplitude": 4.1, "fitness": 0.75}])");
    std::vector<double> fitness;
    for (double a : e.sweep.axes[0].values) fitness.push_back(0.6 - 0.05 * (a - 3.7) * (a - 3.7));
    fitness[15] = NAN;  // a failed point leaves a gap
    ExpectMatchesGolden("plot_landscape_line", app::LandscapeImage(app::PlotContextOf(e), fitness, 5, "best: amplitude 3.5,  fitness 0.598"));
}

TEST(FigureGoldens, LandscapeHeatmapDivergesAboutZeroAndMarksTheThesisPoints) {
    const app::Experiment e = Sweep(R"([{"parameter": "amplitude", "from": 1, "to": 10, "points": 10}, {"parameter": "cycles", "values": [2, 3, 4, 5, 6, 7, 8]}])",
                                    R"([{"amplitude": 4, "cycles": 4, "fitness": 0.97}, {"amplitude": 10, "cycles": 8, "fitness": 3.61}])");
    std::vector<double> fitness;
    for (double a : e.sweep.axes[0].values)
        for (double n : e.sweep.axes[1].values) fitness.push_back(0.4 * (n - 3.5) * std::sqrt(a) - 0.3);
    ExpectMatchesGolden("plot_landscape_heatmap", app::LandscapeImage(app::PlotContextOf(e), fitness, static_cast<int>(fitness.size()) - 1, "best: amplitude 10, cycles 8"));
}

// Failed designs are grey cells, and the picture says so under its colour bar, best or none.
TEST(FigureGoldens, LandscapeHeatmapSaysWhatItsGreyCellsAre) {
    const app::Experiment e = Sweep(R"([{"parameter": "amplitude", "from": 1, "to": 6, "points": 6}, {"parameter": "cycles", "values": [2, 3, 4, 5, 6, 7]}])", "[]");
    std::vector<double> fitness;
    for (double a : e.sweep.axes[0].values)
        for (double n : e.sweep.axes[1].values) fitness.push_back(a > 3.5 && n > 4.5 ? NAN : 0.1 * a * n);
    ExpectMatchesGolden("plot_landscape_heatmap_failed", app::LandscapeImage(app::PlotContextOf(e), fitness, 32, "best: amplitude 6, cycles 4"));
}

// Contractions that are all negative (part 3's shell searches): 0 is on the axis, drawn as a line,
// so the sign reads at a glance. Without the line the picture must not match: the per-tile bound sees
// a one-pixel line that the 0.3 % bound on the whole picture does not.
render::Image NegativeCurves(bool zeroLine) {
    std::string error;
    auto plots = render::PlotRenderer::Create(1200, 800, &error);
    EXPECT_TRUE(plots) << error;
    if (!plots) return {};
    render::LinePlot plot;
    plot.xLabel = "evaluations";
    plot.yLabel = "best so far: contraction, %";
    plot.zeroLine = zeroLine;
    render::LineSeries a{"first (median)", {}, {}, {0.10f, 0.55f, 0.20f}}, b{"second (median)", {}, {}, {0.13f, 0.35f, 0.75f}};
    for (int i = 0; i <= 24; ++i) {
        a.x.push_back(5 * i);
        a.y.push_back(-0.12 + 0.1 * (1 - std::exp(-i / 6.0)));
        b.x.push_back(5 * i);
        b.y.push_back(-0.17 * (1 - std::exp(-i / 3.0)));  // from 0: the range is the same with or without the line
    }
    plot.series = {a, b};
    return plots->RenderLines("All below zero: best so far against evaluations", {plot});
}

TEST(FigureGoldens, CurvesBelowZeroShowTheZeroLine) {
    const render::Image withLine = NegativeCurves(true), without = NegativeCurves(false);
    ExpectMatchesGolden("plot_below_zero", withLine);
    const auto plain = render::CompareImages(withLine, without, render::ImageTolerance{});
    const auto tiled = render::CompareImages(withLine, without, kPlotTolerance);
    EXPECT_TRUE(tiled.matches == false) << "a lost zero line must fail the goldens: " << tiled.Summary();
    EXPECT_TRUE(plain.differingFraction < 0.01) << "the line is a small part of the picture: " << plain.Summary();
}

// Logbooks of `count` GA runs of `generations` that rise towards 3, each with the thesis's best beside it.
std::vector<app::RunCurve> RisingRuns(int count, int generations = 20) {
    std::vector<app::RunCurve> runs;
    for (int r = 0; r < count; ++r) {
        app::RunCurve curve{"run " + std::to_string(r + 1), {}};
        for (int g = 0; g <= generations; ++g) {
            sim::LogbookRow row;
            row.generation = g;
            row.evaluations = 10;
            row.best = 1 + 2 * (1 - std::exp(-g / (5.0 + r)));
            row.worst = -1 + 0.05 * g;
            row.median = row.best - 0.6;
            row.q1 = row.median - 0.4;
            row.q3 = row.median + 0.3;
            row.mean = row.median - 0.1;
            curve.logbook.push_back(row);
        }
        curve.reference = 1.1 + 0.05 * r;
        curve.referenceLabel = "thesis's best";
        runs.push_back(curve);
    }
    return runs;
}

TEST(FigureGoldens, EvolutionWithRangeQuartilesAndTheThesisLine) {
    const app::Experiment e = app::ParseExperiment(R"({"model": {"name": "thesis"}, "id": "G", "title": "golden GA", "sim": {"iterations": 2000},
        "evolve": {"runs": 2, "genome": {"kind": "bspline"}}})", "golden.json");
    const std::vector<app::RunCurve> runs = RisingRuns(2);
    ExpectMatchesGolden("plot_evolution", app::EvolutionImage(app::PlotContextOf(e), runs));
}

// A quick run's two generations: the axis counts generations, 0, 1, 2, never 0.2 of one.
TEST(FigureGoldens, EvolutionOfTwoGenerationsHasWholeTicks) {
    const app::Experiment e = app::ParseExperiment(R"({"model": {"name": "thesis"}, "id": "G", "title": "quick GA", "sim": {"iterations": 2000},
        "evolve": {"runs": 1, "genome": {"kind": "bspline"}}})", "golden.json");
    ExpectMatchesGolden("plot_evolution_two_generations", app::EvolutionImage(app::PlotContextOf(e), RisingRuns(1, 2)));
}

// A title that wraps on one run's narrow figure pushes the panel's label down, never under itself.
TEST(FigureGoldens, EvolutionUnderATitleThatWraps) {
    const app::Experiment e = app::ParseExperiment(R"({"model": {"name": "thesis"}, "id": "S5.4F", "sim": {"iterations": 2000},
        "title": "Four B-splines over the middle with fibre genes under the shell model", "evolve": {"runs": 1, "genome": {"kind": "bspline"}}})",
                                                   "golden.json");
    ExpectMatchesGolden("plot_evolution_wrapped_title", app::EvolutionImage(app::PlotContextOf(e), RisingRuns(1)));
}

TEST(FigureGoldens, ContactSheetOnTheSweepAxes) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Thesis);
    job.Thesis().params = sim::DefaultSimParams();
    job.Thesis().params.iterations = 1500;
    std::vector<sim::SimResult> results;
    const double amplitudes[] = {1, 2.5, 4};
    const int cycles[] = {2, 4};
    for (int n : cycles)
        for (double a : amplitudes) {
            job.shape = sim::AbsSineShape{a, 0, n * 3.141592653589793};
            results.push_back(sim::Evaluate(job));
        }
    std::vector<app::SheetEntry> entries;
    for (const auto& r : results) entries.push_back({&r, app::FitnessCaption(r)});
    app::SheetAxes axes{3, {"1", "2.5", "4"}, {"2", "4"}, "amplitude A", "cycles"};
    const fs::path path = fs::path(ACTUATOR_VISUAL_OUT_DIR) / "contact_sheet_golden_case.png";
    fs::create_directories(path.parent_path());
    std::unique_ptr<render::MeshRenderer> renderer;
    app::WriteContactSheet(path, "golden  -  contact sheet", entries, job, renderer, axes);
    render::Image image;
    std::string error;
    ASSERT_TRUE(render::DecodePng(ReadBytes(path), &image, &error)) << error;
    ExpectMatchesGolden("contact_sheet_axes", image);
}

// `characterize`'s force-contraction chart: one line per pressure with the free stroke marked, and
// the ideal muscle's lines dashed beside them (fixed data: a muscle a little weaker than the ideal).
TEST(FigureGoldens, CharacteristicCurvesWithTheIdealMuscleDashed) {
    const double pi = 3.141592653589793, radiusMm = 5, alpha = 30 * pi / 180;
    const std::vector<double> pressures{5, 10, 20};
    std::vector<std::vector<double>> contraction, force, ideal;
    for (double p : pressures) {
        const double stroke = 0.93 * (1 - 1 / (std::sqrt(3.0) * std::cos(alpha)));  // a little short of the ideal free stroke, 1/3
        std::vector<double> eps, modelled, theory;
        for (int k = 0; k < 6; ++k) {
            const double e = stroke * k / 5;
            const double ideal = pi * radiusMm * radiusMm * p * 1e-3 * (3 * (1 - e) * (1 - e) / std::pow(std::tan(alpha), 2) - 1 / std::pow(std::sin(alpha), 2));
            eps.push_back(100 * e);
            theory.push_back(ideal);
            modelled.push_back(k == 5 ? 0 : 0.9 * ideal * (1 - e / stroke * 0.3));
        }
        contraction.push_back(eps);
        force.push_back(modelled);
        ideal.push_back(theory);
    }
    sim::SimResult isometric, freeStroke;
    for (double p : {0.0, 5.0, 10.0, 15.0, 20.0}) {
        isometric.shell.curvePressureKpa.push_back(p);
        isometric.shell.curveForceN.push_back(0.4 * p);
        freeStroke.shell.curvePressureKpa.push_back(p);
        freeStroke.shell.curveContractionPercent.push_back(20 * (1 - std::exp(-p / 6)));
    }
    const app::CharacteristicImages images =
        app::CharacteristicCurveImages("golden braid at 30 deg", pressures, contraction, force, ideal, isometric, freeStroke);
    ExpectMatchesGolden("characteristic_force_contraction", images.forceContraction);
}

// The exported solids as `render --solid` draws them: a short sine tube cut along its axis, and its
// mold pulled apart.
sim::PartSolids GoldenSolids() {
    sim::PartDef part;
    part.radiusMm = 8;
    part.lengthMm = 40;
    part.thicknessMm = 1.5;
    part.angularSamples = 48;
    part.axialSamples = 25;
    sim::PartSolids solids;
    EXPECT_EQ(sim::BuildPartSolids(sim::SineShape{1.3, 0.5, 3.141592653589793 - 0.5}, part, {}, &solids), "");
    return solids;
}

TEST(FigureGoldens, SolidCutaway) {
    ExpectMatchesGolden("solid_cutaway", app::MakeRenderer(480, 360)->Render(app::CutawayScene(GoldenSolids(), "golden cut-away")));
}

TEST(FigureGoldens, SolidMoldExploded) {
    ExpectMatchesGolden("solid_mold", app::MakeRenderer(640, 400)->Render(app::ExplodedMoldScene(GoldenSolids(), "golden mold")));
}

}  // namespace
