#include "algorithms.h"

#include <fmt/format.h>
#include <stdexcept>

namespace sim {
namespace {

double P(const OptimizerDef& def, const char* name) { return ParameterValue(def, name); }

}  // namespace

const std::vector<AlgorithmRow>& AlgorithmRows() {
    // pagmo 2.18's own defaults, except where noted.
    static const std::vector<AlgorithmRow> rows{
        {Algorithm::Cmaes, false, 5,
         {{"sigma0", 0.3, 1e-6, 1, false, "initial step size sigma0 (pagmo: 0.5)"},
          {"cc", -1, -1, 1, false, "backward time horizon for the evolution path (-1: automatic)"},
          {"cs", -1, -1, 1, false, "makes partly up for the small variance loss in case the indicator is zero (-1: automatic)"},
          {"c1", -1, -1, 1, false, "learning rate for the rank-one update of the covariance matrix (-1: automatic)"},
          {"cmu", -1, -1, 1, false, "learning rate for the rank-mu update of the covariance matrix (-1: automatic)"}}},
        {Algorithm::Xnes, false, 5,
         {{"sigma0", 0.3, 1e-6, 1, false, "initial step size sigma0 (pagmo: automatic)"},
          {"eta_mu", -1, -1, 1, false, "learning rate for the mean (-1: automatic)"},
          {"eta_sigma", -1, -1, 1, false, "learning rate for the step size (-1: automatic)"},
          {"eta_b", -1, -1, 1, false, "learning rate for the covariance (-1: automatic)"}}},
        {Algorithm::De, false, 5,
         {{"F", 0.8, 0, 1, false, "weight coefficient of the difference vectors"},
          {"CR", 0.9, 0, 1, false, "crossover probability"},
          {"variant", 2, 1, 10, true, "mutation variant (pagmo's numbering; 2: rand/1/exp)"}}},
        {Algorithm::Sade, false, 7,
         {{"variant", 2, 1, 18, true, "mutation variant (pagmo's numbering; 2: rand/1/exp)"},
          {"variant_adptv", 1, 1, 2, true, "self-adaptation: 1 jDE, 2 iDE"}}},
        {Algorithm::Pso, false, 2,
         {{"omega", 0.7298, 0, 1, false, "inertia weight (or constriction factor)"},
          {"eta1", 2.05, 0, 4, false, "social component"},
          {"eta2", 2.05, 0, 4, false, "cognitive component"},
          {"max_vel", 0.5, 1e-6, 1, false, "largest velocity, as a fraction of each gene's range"},
          {"variant", 5, 1, 6, true, "algorithm variant (pagmo's numbering; 5: canonical with constriction)"},
          {"neighb_type", 2, 1, 4, true, "swarm topology: 1 gbest, 2 lbest, 3 Von Neumann, 4 adaptive random"},
          {"neighb_param", 4, 1, 1000, true, "topology parameter (lbest: neighbours)"}},
         [](const OptimizerDef& d) -> std::string {
             // The ring (lbest) takes neighb_param / 2 neighbours on each side: none below 2, and it
             // reads past the swarm when they are more than the swarm.
             if (P(d, "neighb_type") != 2 || (P(d, "neighb_param") >= 2 && P(d, "neighb_param") <= d.population)) return "";
             return fmt::format("pso's ring topology (neighb_type 2) needs neighb_param from 2 to the population ({}), got {:g}", d.population,
                                P(d, "neighb_param"));
         }},
        {Algorithm::Nsga2, true, 8,
         {{"cr", 0.95, 0, 0.999999, false, "crossover probability"},
          {"eta_c", 10, 1, 100, false, "distribution index of the crossover"},
          {"m", 0.01, 0, 1, false, "mutation probability"},
          {"eta_m", 50, 1, 100, false, "distribution index of the mutation"}},
         [](const OptimizerDef& d) -> std::string {
             if (d.population % 4 == 0) return "";
             return fmt::format("nsga2 needs a population that is a multiple of 4 (got {}; try {})", d.population, (d.population + 3) / 4 * 4);
         }},
        {Algorithm::Moead, true, 4,
         {{"neighbours", 10, 2, 10000, true, "size of each weight's neighbourhood (pagmo: 20); smaller than the population"},
          {"CR", 1, 0, 1, false, "crossover parameter of the DE operator"},
          {"F", 0.5, 0, 1, false, "scale factor of the DE operator"},
          {"eta_m", 20, 0, 100, false, "distribution index of the polynomial mutation"},
          {"realb", 0.9, 0, 1, false, "chance that the mating pool is the neighbourhood"},
          {"limit", 2, 1, 10000, true, "most parents replaced by one child"}},
         [](const OptimizerDef& d) -> std::string {
             if (P(d, "neighbours") < d.population) return "";
             return fmt::format("moead's neighbours ({:g}) must be smaller than the population ({})", P(d, "neighbours"), d.population);
         }},
        // pagmo's simple genetic algorithm: tournament selection, exponential crossover, polynomial
        // mutation, pure elitism (pagmo's defaults for the three operators).
        {Algorithm::Sga, false, 2,
         {{"cr", 0.9, 0, 1, false, "crossover probability"},
          {"m", 0.02, 0, 1, false, "mutation probability per gene"},
          {"param_m", 1, 1, 100, false, "distribution index of the polynomial mutation (small: wide steps)"},
          {"param_s", 2, 1, 1000, true, "tournament size; at most the population"}},
         [](const OptimizerDef& d) -> std::string {
             if (P(d, "param_s") <= d.population) return "";
             return fmt::format("sga's tournament (param_s {}) is larger than the population ({})", P(d, "param_s"), d.population);
         }},
    };
    return rows;
}

const AlgorithmRow& AlgorithmRowOf(Algorithm id) {
    for (const AlgorithmRow& row : AlgorithmRows())
        if (row.id == id) return row;
    throw std::logic_error("an algorithm without a row");
}

}  // namespace sim
