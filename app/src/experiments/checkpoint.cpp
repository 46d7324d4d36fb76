#include "formats/json_out.h"
#include "experiments/checkpoint.h"

#include <cmath>

#include "formats/csv.h"
#include "formats/table.h"
#include "support/errors.h"

namespace app {
namespace {

using Json = nlohmann::ordered_json;
constexpr int kCheckpointVersion = 2;

Json NumberOrNull(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }
double NumberOrNaN(const Json& value) { return value.is_null() ? std::nan("") : value.get<double>(); }

Json IndividualJson(const sim::Individual& individual) {
    return Json{{"genome", individual.genome}, {"evaluated", individual.evaluated}, {"fitness", NumberOrNull(individual.fitness)},
                {"status", sim::Name(individual.status)}};
}

// A genome this experiment's GA could have made: the right number of gene lists, lengths and
// values within the bounds, a buildable shape.
void CheckGenome(const sim::Genome& whole, const Experiment& e) {
    const sim::GenomeDef& g = e.ga.genome;
    sim::Genome genome = whole;
    if (g.HasFibreGenes()) {
        // The last list: the angles in their range, then 0/1 switches.
        if (genome.empty()) throw std::runtime_error("a genome has no fibre genes");
        const auto& fibres = genome.back();
        if (static_cast<int>(fibres.size()) != g.fibreAngles + (g.fibreSwitches ? 2 : 0)) throw std::runtime_error("a genome has the wrong number of fibre genes");
        for (size_t k = 0; k < fibres.size(); ++k)
            if (static_cast<int>(k) < g.fibreAngles ? !(fibres[k] >= g.fibreAngleMin && fibres[k] <= g.fibreAngleMax) : (fibres[k] != 0 && fibres[k] != 1))
                throw std::runtime_error("a fibre gene is outside its range");
        genome.pop_back();
    }
    if (g.kind == sim::GenomeKind::BSpline) {
        if (static_cast<int>(genome.size()) != g.splines) throw std::runtime_error("a genome has " + std::to_string(genome.size()) + " splines, the experiment " + std::to_string(g.splines));
        for (const auto& spline : genome) {
            if (static_cast<int>(spline.size()) < g.lengthMin || static_cast<int>(spline.size()) > g.lengthMax)
                throw std::runtime_error("a spline has " + std::to_string(spline.size()) + " control points, outside " + std::to_string(g.lengthMin) +
                                         " to " + std::to_string(g.lengthMax));
            for (double c : spline)
                if (!g.OnControlGrid(c)) throw std::runtime_error("a control point is outside the control range");
        }
    } else {
        if (genome.size() != 1 || genome[0].size() != 2 * static_cast<size_t>(sim::VertexCount(DesignMesh(e))))
            throw std::runtime_error("a free-xy genome has the wrong number of offsets");
        for (double v : genome[0])
            if (!(std::fabs(v) <= std::max(g.bound, g.initRange))) throw std::runtime_error("a free-xy offset is outside the bound");
    }
    if (const std::string error = sim::JobError(JobOfGenome(e, whole)); !error.empty()) throw std::runtime_error(error);
}

sim::Individual IndividualFrom(const Json& j, const Experiment& e) {
    sim::Individual individual;
    individual.genome = j.at("genome").get<sim::Genome>();
    individual.evaluated = j.at("evaluated").get<bool>();
    individual.fitness = NumberOrNaN(j.at("fitness"));
    const auto status = sim::FromName<sim::Status>(j.at("status").get<std::string>());
    if (!status) throw std::runtime_error("unknown status " + j.at("status").dump());
    individual.status = *status;
    if (individual.evaluated && individual.status == sim::Status::Ok && !std::isfinite(individual.fitness))
        throw std::runtime_error("a valid individual has no fitness");
    CheckGenome(individual.genome, e);
    return individual;
}

}  // namespace

std::string FormatCheckpoint(const RunCheckpoint& c) {
    Json j;
    j["version"] = kCheckpointVersion;
    j["experiment_hash"] = c.experimentHash;
    j["seed"] = c.seed;
    j["generation"] = c.state.generation;
    j["stop_reason"] = c.state.stopReason;
    j["archive_count"] = c.archiveCount;
    j["rng"] = c.state.rng.State();
    j["population"] = Json::array();
    for (const auto& individual : c.state.population) j["population"].push_back(IndividualJson(individual));
    j["logbook"] = Json::array();
    for (const auto& row : c.state.logbook)
        j["logbook"].push_back(Json{{"generation", row.generation}, {"evaluations", row.evaluations}, {"best", NumberOrNull(row.best)},
                                    {"worst", NumberOrNull(row.worst)}, {"mean", NumberOrNull(row.mean)}, {"std", NumberOrNull(row.stddev)},
                                    {"invalid", row.invalid}, {"q1", NumberOrNull(row.q1)}, {"median", NumberOrNull(row.median)}, {"q3", NumberOrNull(row.q3)}});
    j["best_per_generation"] = Json::array();
    for (const auto& individual : c.state.bestPerGeneration) j["best_per_generation"].push_back(IndividualJson(individual));
    j["hall_of_fame"] = Json::array();
    for (const auto& individual : c.state.hallOfFame) j["hall_of_fame"].push_back(IndividualJson(individual));
    j["experiment"] = c.experiment;
    return j.dump() + "\n";
}

RunCheckpoint ParseCheckpoint(const std::string& text, const std::string& path, const Experiment& e) {
    Json j;
    try {
        j = ParseJson(text, path);
    } catch (const Json::exception&) {
        throw UsageError(path + ": not a checkpoint (not valid JSON); remove it to restart this run, or --overwrite");
    }
    RunCheckpoint c;
    try {
        if (j.at("version").get<int>() != kCheckpointVersion) throw std::runtime_error("written by another version");
        c.experimentHash = j.at("experiment_hash").get<std::string>();
        c.experiment = j.at("experiment");
    } catch (const std::exception& error) {
        throw UsageError(path + ": not a usable checkpoint (" + error.what() + ")");
    }
    if (c.experimentHash != ExperimentHash(e)) {
        const std::string changed = ExperimentDifference(c.experiment, e.document);
        throw UsageError("--resume: the experiment changed since this run started (" + (changed.empty() ? std::string("its text differs") : changed) +
                         "); put it back, or start afresh with --overwrite");
    }
    try {
        c.seed = j.at("seed").get<std::uint64_t>();
        c.state.generation = j.at("generation").get<int>();
        // Checkpoints written before stop criteria existed have no reason: the run had not ended.
        if (j.contains("stop_reason")) c.state.stopReason = j.at("stop_reason").get<std::string>();
        if (c.state.stopReason.size() > 64) throw std::runtime_error("the stop reason is too long");
        c.archiveCount = j.at("archive_count").get<std::uint64_t>();
        const auto rng = j.at("rng").get<std::array<std::uint64_t, 4>>();
        if (rng == std::array<std::uint64_t, 4>{}) throw std::runtime_error("the generator's state is all zero (xoshiro256** would repeat zeros forever)");
        c.state.rng.SetState(rng);
        for (const auto& individual : j.at("population")) c.state.population.push_back(IndividualFrom(individual, e));
        for (const auto& row : j.at("logbook")) {
            sim::LogbookRow r;
            r.generation = row.at("generation").get<int>();
            r.evaluations = row.at("evaluations").get<int>();
            r.best = NumberOrNaN(row.at("best"));
            r.worst = NumberOrNaN(row.at("worst"));
            r.mean = NumberOrNaN(row.at("mean"));
            r.stddev = NumberOrNaN(row.at("std"));
            r.invalid = row.at("invalid").get<int>();
            r.q1 = NumberOrNaN(row.at("q1"));
            r.median = NumberOrNaN(row.at("median"));
            r.q3 = NumberOrNaN(row.at("q3"));
            sim::ChainGaLogbookRow(r, c.state.logbook.empty() ? nullptr : &c.state.logbook.back());
            c.state.logbook.push_back(r);
        }
        for (const auto& individual : j.at("best_per_generation")) c.state.bestPerGeneration.push_back(IndividualFrom(individual, e));
        for (const auto& individual : j.at("hall_of_fame")) c.state.hallOfFame.push_back(IndividualFrom(individual, e));
        if (static_cast<int>(c.state.population.size()) != e.ga.population)
            throw std::runtime_error("the population has " + std::to_string(c.state.population.size()) + " individuals, the experiment " +
                                     std::to_string(e.ga.population));
        if (c.state.generation < 0 || c.state.generation > e.ga.generations) throw std::runtime_error("generation out of range");
        if (c.state.logbook.size() != static_cast<size_t>(c.state.generation + 1) || c.state.bestPerGeneration.size() != c.state.logbook.size())
            throw std::runtime_error("the logbook does not match the generation");
        if (c.state.hallOfFame.size() > sim::kHallOfFameSize) throw std::runtime_error("the hall of fame is too long");
        for (const auto& individual : c.state.population)
            if (!individual.evaluated) throw std::runtime_error("an individual was never evaluated");
    } catch (const std::exception& error) {
        throw UsageError(path + ": not a usable checkpoint (" + error.what() + "); remove it to restart this run, or --overwrite");
    }
    return c;
}

std::string LogbookCsv(const sim::GaState& state) {
    Table table(std::vector<std::string>{"generation", "evaluations", "best", "worst", "mean", "std", "q1", "median", "q3", "invalid", "stopped_by"});
    for (size_t k = 0; k < state.logbook.size(); ++k) {
        const auto& r = state.logbook[k];
        table.AddRow({std::to_string(r.generation), std::to_string(r.evaluations), CsvNumber(r.best), CsvNumber(r.worst), CsvNumber(r.mean),
                       CsvNumber(r.stddev), CsvNumber(r.q1), CsvNumber(r.median), CsvNumber(r.q3), std::to_string(r.invalid), k + 1 == state.logbook.size() ? state.stopReason : ""});
    }
    return table.Csv();
}

std::string BestPerGenerationCsv(const sim::GaState& state) {
    Table table(std::vector<std::string>{"generation", "fitness", "status", "genome"});
    for (size_t g = 0; g < state.bestPerGeneration.size(); ++g) {
        const auto& b = state.bestPerGeneration[g];
        table.AddRow({std::to_string(g), CsvNumber(b.Valid() ? b.fitness : NAN), sim::Name(b.status), sim::GenomeText(b.genome)});
    }
    return table.Csv();
}

std::string HallOfFameCsv(const sim::GaState& state) {
    Table table(std::vector<std::string>{"rank", "fitness", "genome"});
    for (size_t k = 0; k < state.hallOfFame.size(); ++k)
        table.AddRow({std::to_string(k + 1), CsvNumber(state.hallOfFame[k].fitness), sim::GenomeText(state.hallOfFame[k].genome)});
    return table.Csv();
}

namespace {
constexpr int kOptimizerCheckpointVersion = 1;
}  // namespace

std::string FormatOptimizerCheckpoint(const OptimizerCheckpoint& c, const Experiment& e) {
    const Json j{{"kind", "optimizer checkpoint"},    {"version", kOptimizerCheckpointVersion}, {"algorithm", sim::Name(e.optimizer.algorithm)},
                 {"seed", c.seed},                    {"generation", c.generation},             {"archive_count", c.archiveCount},
                 {"stop_reason", c.stopReason},       {"seconds", c.seconds},                   {"experiment_hash", ExperimentHash(e)},
                 {"experiment", e.document}};
    return j.dump(2) + "\n";
}

OptimizerCheckpoint ParseOptimizerCheckpoint(const std::string& text, const std::string& path, const Experiment& e) {
    try {
        const Json j = ParseJson(text, path);
        if (j.at("kind") != "optimizer checkpoint" || j.at("version") != kOptimizerCheckpointVersion)
            throw std::runtime_error("not an optimizer checkpoint of this version");
        if (j.at("experiment_hash").get<std::string>() != ExperimentHash(e)) {
            const std::string what = ExperimentDifference(j.at("experiment"), e.document);
            throw UsageError(path + ": made with another experiment (" + (what.empty() ? "it was edited" : what) +
                             "); resume needs the experiment the run started with");
        }
        OptimizerCheckpoint c;
        c.seed = j.at("seed").get<std::uint64_t>();
        c.generation = j.at("generation").get<int>();
        c.archiveCount = j.at("archive_count").get<std::uint64_t>();
        c.stopReason = j.at("stop_reason").get<std::string>();
        c.seconds = j.at("seconds").get<double>();
        if (c.generation < 0 || c.generation > 1000000 || !(c.seconds >= 0)) throw std::runtime_error("values out of range");
        return c;
    } catch (const UsageError&) {
        throw;
    } catch (const std::exception& error) {
        throw UsageError(path + ": not a usable optimizer checkpoint (" + error.what() + "); remove the folder or use --overwrite");
    }
}

}  // namespace app
