#include "checkpoint.h"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_options.h"

namespace app {
namespace {

using nlohmann::json;
constexpr int kCheckpointVersion = 1;

json NumberOrNull(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }
double NumberOrNaN(const json& value) { return value.is_null() ? std::nan("") : value.get<double>(); }

sim::Status StatusFromName(const std::string& name) {
    if (name == "ok") return sim::Status::Ok;
    if (name == "nan") return sim::Status::NaN;
    if (name == "diverged") return sim::Status::Diverged;
    throw std::runtime_error("unknown status '" + name + "'");
}

json IndividualJson(const sim::Individual& individual) {
    return json{{"genome", individual.genome}, {"evaluated", individual.evaluated},
                {"fitness", NumberOrNull(individual.fitness)}, {"status", sim::StatusName(individual.status)}};
}

sim::Individual IndividualFrom(const json& j) {
    sim::Individual individual;
    individual.genome = j.at("genome").get<sim::Genome>();
    individual.evaluated = j.at("evaluated").get<bool>();
    individual.fitness = NumberOrNaN(j.at("fitness"));
    individual.status = StatusFromName(j.at("status").get<std::string>());
    return individual;
}

std::string Number(double value) {
    if (!std::isfinite(value)) return "nan";
    char buffer[32];
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

}  // namespace

std::string FormatCheckpoint(const RunCheckpoint& c) {
    json j;
    j["version"] = kCheckpointVersion;
    j["seed"] = c.seed;
    j["generation"] = c.state.generation;
    j["rng"] = c.state.rng.State();
    for (const auto& individual : c.state.population) j["population"].push_back(IndividualJson(individual));
    for (const auto& row : c.state.logbook)
        j["logbook"].push_back(json{{"generation", row.generation}, {"evaluations", row.evaluations}, {"best", NumberOrNull(row.best)},
                                    {"worst", NumberOrNull(row.worst)}, {"mean", NumberOrNull(row.mean)},
                                    {"std", NumberOrNull(row.stddev)}, {"invalid", row.invalid}});
    for (const auto& individual : c.state.bestPerGeneration) j["best_per_generation"].push_back(IndividualJson(individual));
    j["hall_of_fame"] = json::array();
    for (const auto& individual : c.state.hallOfFame) j["hall_of_fame"].push_back(IndividualJson(individual));
    return j.dump() + "\n";
}

RunCheckpoint ParseCheckpoint(const std::string& text, const std::string& path) {
    try {
        const json j = json::parse(text);
        if (j.at("version").get<int>() != kCheckpointVersion) throw std::runtime_error("written by another version");
        RunCheckpoint c;
        c.seed = j.at("seed").get<std::uint64_t>();
        c.state.generation = j.at("generation").get<int>();
        c.state.rng.SetState(j.at("rng").get<std::array<std::uint64_t, 4>>());
        for (const auto& individual : j.at("population")) c.state.population.push_back(IndividualFrom(individual));
        for (const auto& row : j.at("logbook"))
            c.state.logbook.push_back(sim::LogbookRow{row.at("generation").get<int>(), row.at("evaluations").get<int>(),
                                                      NumberOrNaN(row.at("best")), NumberOrNaN(row.at("worst")),
                                                      NumberOrNaN(row.at("mean")), NumberOrNaN(row.at("std")), row.at("invalid").get<int>()});
        for (const auto& individual : j.at("best_per_generation")) c.state.bestPerGeneration.push_back(IndividualFrom(individual));
        for (const auto& individual : j.at("hall_of_fame")) c.state.hallOfFame.push_back(IndividualFrom(individual));
        if (c.state.population.empty() || c.state.logbook.size() != static_cast<size_t>(c.state.generation + 1))
            throw std::runtime_error("inconsistent contents");
        return c;
    } catch (const std::exception& error) {
        throw UsageError(path + ": not a usable checkpoint (" + error.what() + ")");
    }
}

std::string LogbookCsv(const sim::GaState& state) {
    std::string csv = "generation,evaluations,best,worst,mean,std,invalid\n";
    for (const auto& r : state.logbook)
        csv += std::to_string(r.generation) + "," + std::to_string(r.evaluations) + "," + Number(r.best) + "," + Number(r.worst) + "," +
               Number(r.mean) + "," + Number(r.stddev) + "," + std::to_string(r.invalid) + "\n";
    return csv;
}

std::string BestPerGenerationCsv(const sim::GaState& state) {
    std::string csv = "generation,fitness,status,genome\n";
    for (size_t g = 0; g < state.bestPerGeneration.size(); ++g) {
        const auto& b = state.bestPerGeneration[g];
        csv += std::to_string(g) + "," + Number(b.Valid() ? b.fitness : std::nan("")) + "," + sim::StatusName(b.status) + ",\"" +
               sim::GenomeText(b.genome) + "\"\n";
    }
    return csv;
}

std::string HallOfFameCsv(const sim::GaState& state) {
    std::string csv = "rank,fitness,genome\n";
    for (size_t k = 0; k < state.hallOfFame.size(); ++k)
        csv += std::to_string(k + 1) + "," + Number(state.hallOfFame[k].fitness) + ",\"" + sim::GenomeText(state.hallOfFame[k].genome) + "\"\n";
    return csv;
}

}  // namespace app
