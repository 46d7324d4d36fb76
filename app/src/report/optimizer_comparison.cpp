#include "report/optimizer_comparison.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

#include "formats/csv.h"
#include "support/errors.h"
#include "experiments/experiment_runner.h"
#include "formats/files.h"
#include "formats/json_out.h"
#include "pictures/figures.h"
#include "pictures/plots.h"
#include "formats/table.h"
#include "render/plot.h"

namespace app {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

sim::ObjectiveKind FitnessOf(const Experiment& e) {
    if (e.kind == ExperimentKind::Optimize) return e.optimizer.objectives[0].kind;
    return sim::ModelOf(e.model).physical ? sim::ObjectiveKind::Contraction : sim::ObjectiveKind::ThesisFitness;  // the GA's fitness
}

std::string Label(const Experiment& e) {
    const std::string algorithm = e.kind == ExperimentKind::Evolve ? "thesis GA" : sim::Name(e.optimizer.algorithm);
    return e.id.empty() ? algorithm : e.id + " (" + algorithm + ")";
}

std::string Folder(const Experiment& e) { return e.id.empty() ? fs::path(e.path).stem().string() : e.id; }

// The run's best so far against the evaluations it had made, from its logbook, read by column name.
// An optimizer's logbook counts evaluations cumulatively and has a best-so-far column; the GA's counts
// each generation's evaluations, and its best so far is the running best of the generations' bests
// (the GA maximises its fitness).
std::vector<std::pair<double, double>> CurveOf(const Experiment& e, const fs::path& runDir) {
    const Table logbook = Table::Read((runDir / "logbook.csv").string());
    std::vector<std::pair<double, double>> curve;
    double evaluations = 0, best = NAN;
    for (size_t k = 0; k < logbook.Rows(); ++k) {
        if (e.kind == ExperimentKind::Evolve) {
            evaluations += logbook.Number(k, "evaluations");
            const double b = logbook.Number(k, "best");
            if (std::isfinite(b) && !(b <= best)) best = b;
        } else {
            evaluations = logbook.Number(k, "evaluations");
            best = logbook.Number(k, "best_so_far");
        }
        curve.push_back({evaluations, best});
    }
    return curve;
}

// The curve's value at x evaluations: the best so far of the last generation that had used no more.
double ValueAt(const std::vector<std::pair<double, double>>& curve, double x) {
    double value = NAN;
    for (const auto& [evaluations, best] : curve)
        if (evaluations <= x) value = best;
    return value;
}

double Quantile(std::vector<double> values, double q) {
    std::sort(values.begin(), values.end());
    const double at = q * static_cast<double>(values.size() - 1);
    const size_t low = static_cast<size_t>(std::floor(at));
    const size_t high = std::min(values.size() - 1, low + 1);
    return values[low] + (at - static_cast<double>(low)) * (values[high] - values[low]);
}

// The space a contender searches, in words: two contenders on one problem describe it alike. The
// GA's splines vary in length between bounds; the optimizers' are fixed (a GA whose bounds are equal
// searches the same space as they do).
std::string DesignSpace(const Experiment& e) {
    const bool ga = e.kind == ExperimentKind::Evolve;
    const sim::GenomeDef& g = ga ? e.ga.genome : e.optimizer.genome.genes;
    std::string space;
    if (ga ? g.kind == sim::GenomeKind::BSpline : e.optimizer.genome.family == sim::VectorFamily::BSpline) {
        const int low = ga ? g.lengthMin : e.optimizer.genome.controlPoints, high = ga ? g.lengthMax : e.optimizer.genome.controlPoints;
        space = fmt::format("{} B-spline(s) over the {}, {} control points in [{}, {}]", g.splines, sim::Name(g.region),
                            low == high ? std::to_string(low) : fmt::format("{} to {}", low, high), g.controlMin, g.controlMax);
    } else if (ga ? g.kind == sim::GenomeKind::FreeXY : e.optimizer.genome.family == sim::VectorFamily::FreeXY) {
        space = fmt::format("free-xy offsets over the {} within {}", sim::Name(g.region), g.bound);
    } else {
        const auto& v = e.optimizer.genome;
        space = fmt::format("{} with A in [{}, {}], phase from [{}, {}] to [{}, {}]", sim::Name(v.family), v.amplitude[0], v.amplitude[1],
                            v.phaseStart[0], v.phaseStart[1], v.phaseEnd[0], v.phaseEnd[1]);
    }
    if (g.fibreAngles > 0) space += fmt::format(", {} fibre angle gene(s) in [{}, {}] deg", g.fibreAngles, g.fibreAngleMin, g.fibreAngleMax);
    if (g.fibreSwitches) space += ", fibre switches";
    return space;
}

}  // namespace

void CheckContenders(const std::vector<Experiment>& contenders) {
    if (contenders.size() < 2) throw UsageError("compare needs two or more experiment files (each an 'evolve' or 'optimizer' experiment)");
    const Experiment& first = contenders.front();
    for (const Experiment& e : contenders) {
        if (e.kind != ExperimentKind::Evolve && e.kind != ExperimentKind::Optimize)
            throw UsageError(e.path + ": describes no genetic algorithm or optimizer; compare runs 'evolve' and 'optimizer' experiments");
        if (e.kind == ExperimentKind::Optimize && e.optimizer.objectives.size() != 1)
            throw UsageError(e.path + ": has " + std::to_string(e.optimizer.objectives.size()) +
                             " objectives; compare draws one objective's best against evaluations");
        if (e.model != first.model)
            throw UsageError(e.path + ": uses the " + sim::Name(e.model) + " model, " + first.path + " the " + sim::Name(first.model) +
                             " model; compare runs one problem");
        // One problem: the same model settings (what a design is evaluated with) and the same space of designs.
        const Json model = ModelJson(JobOf(e, sim::CylinderShape{})), firstModel = ModelJson(JobOf(first, sim::CylinderShape{}));
        if (model != firstModel)
            throw UsageError(e.path + ": evaluates designs with other model settings than " + first.path + " (" +
                             ExperimentDifference(firstModel, model) + "); compare runs one problem");
        if (DesignSpace(e) != DesignSpace(first))
            throw UsageError(e.path + ": searches " + DesignSpace(e) + ", " + first.path + " " + DesignSpace(first) + "; compare runs one problem");
        if (FitnessOf(e) != FitnessOf(first))
            throw UsageError(e.path + ": is judged by " + sim::Name(FitnessOf(e)) + ", " + first.path + " by " + sim::Name(FitnessOf(first)) +
                             "; compare runs one problem");
        if (const std::string why = FolderNameError(Folder(e)); !why.empty())
            throw UsageError(e.path + ": its id " + why + "; compare runs each contender in a folder named by its id");
        for (const Experiment& other : contenders)
            if (&other != &e && Folder(other) == Folder(e)) throw UsageError(e.path + " and " + other.path + " have the same id " + Quote(Folder(e)));
    }
}

Experiment ContenderRun(const Experiment& contender, int seed, long long budget) {
    // Through the document, so that each run's experiment.json re-reads as what ran (a resume).
    Json document = contender.document;
    const char* block = contender.kind == ExperimentKind::Evolve ? "evolve" : "optimizer";
    document["seed"] = seed;
    document[block]["runs"] = 1;
    // The budget alone ends the run (a generation count large enough never to be reached first).
    document[block]["generations"] = 100000;
    document[block]["stop"] = Json{{"evaluations", budget}};
    document["render"]["thumbnails"] = false;
    Experiment e = ParseExperiment(document.dump(), contender.path);
    e.id = contender.id;
    return e;
}

ComparisonResult CompareOptimizers(const std::vector<Experiment>& contenders, const ComparisonDef& def, const fs::path& dir, Evaluator& evaluator,
                                   ResultsFolder* folder, bool resume, bool progress) {
    CheckContenders(contenders);
    ComparisonResult result;
    const auto started = std::chrono::steady_clock::now();
    std::error_code ec;
    int done = 0;
    const int total = static_cast<int>(contenders.size()) * def.seeds;
    for (const Experiment& contender : contenders) {
        ContenderResult c;
        c.label = Label(contender);
        for (int seed = 1; seed <= def.seeds; ++seed) {
            const Experiment e = ContenderRun(contender, seed, def.budget);
            const fs::path sub = dir / Folder(contender) / ("seed_" + std::to_string(seed));
            ++done;
            if (!fs::exists(sub / "summary.json", ec)) {
                const bool again = resume && fs::exists(sub / "run.json", ec);
                fs::create_directories(sub, ec);
                if (!fs::is_directory(sub, ec)) throw UsageError("cannot create folder " + Quote(sub.string()));
                if (progress) std::cerr << "compare: " << done << "/" << total << " " << c.label << " seed " << seed << (again ? " (resumed)" : "") << "\n";
                RunOptions options;
                options.evaluator = &evaluator;
                options.resume = again;
                options.folder = folder;
                options.progress = progress;
                RunExperiment(e, sub, options);
            }
            c.curves.push_back(CurveOf(e, sub / "run_1"));
            c.finalBest.push_back(c.curves.back().empty() ? NAN : c.curves.back().back().second);
            c.evaluations.push_back(c.curves.back().empty() ? 0 : static_cast<long long>(c.curves.back().back().first));
        }
        result.contenders.push_back(std::move(c));
    }

    // The tables: every run's end, and every run's curve (what the figure draws).
    Table ends({"contender", "seed", "evaluations", "best"});
    Table curves({"contender", "seed", "evaluations", "best_so_far"});
    for (const auto& c : result.contenders)
        for (size_t s = 0; s < c.finalBest.size(); ++s) {
            ends.AddRow({c.label, std::to_string(s + 1), std::to_string(c.evaluations[s]), CsvNumber(c.finalBest[s])});
            for (const auto& [evaluations, best] : c.curves[s])
                curves.AddRow({c.label, std::to_string(s + 1), CsvNumber(evaluations), CsvNumber(best)});
        }
    WriteFileAtomically((dir / "comparison.csv").string(), ends.Csv());
    WriteFileAtomically((dir / "comparison_curves.csv").string(), curves.Csv());

    // The figure: at evaluations 0..budget, each contender's median best so far over its seeds, and
    // the range from the worst seed to the best shaded (where every seed has a value).
    const Experiment& first = contenders.front();
    const sim::ObjectiveKind fitness = FitnessOf(first);
    const render::Rgb colours[] = {{0.10f, 0.55f, 0.20f}, {0.13f, 0.35f, 0.75f}, {0.80f, 0.20f, 0.15f}, {0.55f, 0.25f, 0.65f}, {0.85f, 0.55f, 0.10f}};
    render::LinePlot plot;
    plot.xLabel = "evaluations";
    plot.yLabel = fmt::format("best so far: {}", sim::ObjectiveUnit(fitness));
    // Contraction's sign is the finding (+ shorter, - longer): 0 is always on the axis, drawn.
    plot.zeroLine = fitness == sim::ObjectiveKind::Contraction;
    std::string table = "| contender | runs | median best at the budget | worst run | best run |\n|---|---:|---:|---:|---:|\n";
    for (size_t k = 0; k < result.contenders.size(); ++k) {
        const auto& c = result.contenders[k];
        const render::Rgb colour = colours[k % 5];
        render::Band band{"", {}, {}, {}, colour};
        render::LineSeries median{c.label + " (median)", {}, {}, colour};
        const int steps = 100;
        for (int i = 0; i <= steps; ++i) {
            const double x = static_cast<double>(def.budget) * i / steps;
            std::vector<double> values;
            for (const auto& curve : c.curves) values.push_back(ValueAt(curve, x));
            const bool all = std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
            median.x.push_back(x);
            median.y.push_back(all ? Quantile(values, 0.5) : NAN);
            band.x.push_back(x);
            band.low.push_back(all ? *std::min_element(values.begin(), values.end()) : NAN);
            band.high.push_back(all ? *std::max_element(values.begin(), values.end()) : NAN);
        }
        if (k == 0) band.label = "range of the seeds";
        plot.bands.push_back(band);
        plot.series.push_back(median);
        std::vector<double> finals;
        for (double v : c.finalBest)
            if (std::isfinite(v)) finals.push_back(v);
        table += fmt::format("| {} | {} | {} | {} | {} |\n", c.label, c.finalBest.size(), finals.empty() ? "-" : fmt::format("{:.4g}", Quantile(finals, 0.5)),
                             finals.empty() ? "-" : fmt::format("{:.4g}", *std::min_element(finals.begin(), finals.end())),
                             finals.empty() ? "-" : fmt::format("{:.4g}", *std::max_element(finals.begin(), finals.end())));
    }
    if (first.render.figures) {
        std::string error;
        auto plots = render::PlotRenderer::Create(1200, 760, &error);
        if (!plots) throw UsageError("cannot render: " + error);
        WritePng((dir / "comparison.png").string(),
                 plots->RenderLines(fmt::format("One problem ({} model), {} seeds each, {} evaluations: best so far against evaluations", sim::Name(first.model),
                                                def.seeds, def.budget),
                                    {plot}),
                 6);
        result.figures.push_back("comparison.png");
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    result.markdown = fmt::format("Each contender ran {} times (seeds 1 to {}) to {} evaluations under the {} model; fitness: {}. Every run is a results "
                                  "folder of its own (`{}<id>/seed_<k>/`); numbers in [`comparison.csv`]({}comparison.csv).\n\n",
                                  def.seeds, def.seeds, def.budget, sim::Name(first.model), sim::ObjectiveUnit(fitness), def.linkPrefix, def.linkPrefix) +
                      table + "\n" + (result.figures.empty() ? "" : "![comparison](" + def.linkPrefix + "comparison.png)\n");
    return result;
}

}  // namespace app
