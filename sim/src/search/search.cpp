#include "sim/search.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

namespace sim {

void ChainGaLogbookRow(LogbookRow& row, const LogbookRow* before) {
    row.evaluationsSoFar = (before ? before->evaluationsSoFar : 0) + row.evaluations;
    row.bestSoFar = before && std::isfinite(before->bestSoFar) && !(row.best > before->bestSoFar) ? before->bestSoFar : row.best;
}

double SortedQuantile(const std::vector<double>& ascending, double q) {
    if (ascending.empty()) return std::nan("");
    const double at = q * static_cast<double>(ascending.size() - 1);
    const size_t low = static_cast<size_t>(std::floor(at));
    const size_t high = std::min(low + 1, ascending.size() - 1);
    return ascending[low] + (at - static_cast<double>(low)) * (ascending[high] - ascending[low]);
}


// ---------------------------------------------------------------------------------------------
// Sweeps
// ---------------------------------------------------------------------------------------------

double SweepParameterValue(const Shape& shape, SweepParameter parameter) {
    auto read = [&](const auto& sine) {
        switch (parameter) {
            case SweepParameter::Amplitude: return sine.amplitude;
            case SweepParameter::Cycles: return (sine.phaseEnd - sine.phaseStart) / std::numbers::pi;
            case SweepParameter::PhaseEnd: return sine.phaseEnd;
            case SweepParameter::PressureKpa:
            case SweepParameter::FibreAngleDeg: break;
        }
        return std::nan("");
    };
    if (const auto* s = std::get_if<SineShape>(&shape)) return read(*s);
    if (const auto* a = std::get_if<AbsSineShape>(&shape)) return read(*a);
    return std::nan("");
}

Shape WithSweepParameter(Shape shape, SweepParameter parameter, double value) {
    auto write = [&](auto& sine) {
        switch (parameter) {
            case SweepParameter::Amplitude: sine.amplitude = value; break;
            case SweepParameter::Cycles: sine.phaseEnd = sine.phaseStart + value * std::numbers::pi; break;
            case SweepParameter::PhaseEnd: sine.phaseEnd = value; break;
            case SweepParameter::PressureKpa:
            case SweepParameter::FibreAngleDeg: break;
        }
    };
    if (auto* s = std::get_if<SineShape>(&shape)) write(*s);
    else if (auto* a = std::get_if<AbsSineShape>(&shape)) write(*a);
    return shape;
}

std::vector<double> Linspace(double from, double to, int points) {
    std::vector<double> values;
    for (int k = 0; k < points; ++k) values.push_back(points == 1 ? from : from + (to - from) * k / (points - 1));
    return values;
}

std::vector<Shape> SweepShapes(const SweepDef& def) {
    std::vector<Shape> shapes{def.base};
    for (const SweepAxis& axis : def.axes) {
        std::vector<Shape> next;
        for (const Shape& shape : shapes)
            for (double value : axis.values) next.push_back(WithSweepParameter(shape, axis.parameter, value));
        shapes = std::move(next);
    }
    return shapes;
}

// ---------------------------------------------------------------------------------------------
// Genetic algorithm
// ---------------------------------------------------------------------------------------------
namespace {

// Families a fibre layout has: a braid two, the others one.
int FibreFamilies(const GenomeDef& def) { return def.fibreSwitches ? 2 : 0; }

std::vector<double> RandomFibreGenes(const GenomeDef& def, Random& rng) {
    std::vector<double> genes;
    for (int k = 0; k < def.fibreAngles; ++k) genes.push_back(def.fibreAngleMin + (def.fibreAngleMax - def.fibreAngleMin) * rng.Uniform());
    for (int k = 0; k < FibreFamilies(def); ++k) genes.push_back(rng.Chance(0.5) ? 1.0 : 0.0);
    return genes;
}

Genome ShapeGenes(const Genome& genome, const GenomeDef& def) {
    if (!def.HasFibreGenes() || genome.empty()) return genome;
    return Genome(genome.begin(), genome.end() - 1);
}

Genome RandomShapeGenome(const GenomeDef& def, const MeshDef& mesh, Random& rng);

// Free-xy gene k (vertex k / 2's x or y offset) is searched unless the region is `middle` and the
// vertex is clamped: the thesis's Table 3.3 gives the free-xy range as rows {2, h-2}, so the clamped
// turns keep the plain cylinder's radius, as the middle B-splines do.
bool FreeXYGeneMoves(const GenomeDef& def, const MeshDef& mesh, size_t k) {
    return def.region != SplineRegion::Middle || !IsClamped(mesh, static_cast<int>(k / 2));
}

Genome RandomGenome(const GenomeDef& def, const MeshDef& mesh, Random& rng) {
    Genome genome = RandomShapeGenome(def, mesh, rng);
    if (def.HasFibreGenes()) genome.push_back(RandomFibreGenes(def, rng));
    return genome;
}

Genome RandomShapeGenome(const GenomeDef& def, const MeshDef& mesh, Random& rng) {
    Genome genome;
    if (def.kind == GenomeKind::FreeXY) {
        std::vector<double> offsets(2 * static_cast<size_t>(VertexCount(mesh)), 0.0);
        for (size_t k = 0; k < offsets.size(); ++k)
            if (FreeXYGeneMoves(def, mesh, k)) offsets[k] = -def.initRange + 2 * def.initRange * rng.Uniform();
        genome.push_back(std::move(offsets));
        return genome;
    }
    for (int s = 0; s < def.splines; ++s) {
        std::vector<double> spline(static_cast<size_t>(rng.Integer(def.lengthMin, def.lengthMax)));
        for (double& c : spline) c = def.ControlValue(rng.Integer(0, def.ControlLevels()));
        genome.push_back(std::move(spline));
    }
    return genome;
}

// The thesis's mutation (section 3.2.5). B-splines: each gene is reset to a random integer with
// probability INDPB; then, with probability INDPB each, a spline grows by one random gene (if below
// its maximum length) and shrinks by its last gene (if above its minimum). Free-xy: each gene moves
// by Gaussian noise with probability INDPB, clamped to the bounds.
void Mutate(Genome& genome, const GaDef& def, const MeshDef& mesh, Random& rng) {
    const GenomeDef& g = def.genome;
    const size_t shapeLists = g.HasFibreGenes() ? genome.size() - 1 : genome.size();
    for (size_t list = 0; list < shapeLists; ++list) {
        auto& genes = genome[list];
        if (g.kind == GenomeKind::FreeXY) {
            for (size_t k = 0; k < genes.size(); ++k)
                if (FreeXYGeneMoves(g, mesh, k) && rng.Chance(def.indpb)) genes[k] = std::clamp(genes[k] + g.sigma * rng.Normal(), -g.bound, g.bound);
            continue;
        }
        for (double& c : genes)
            if (rng.Chance(def.indpb)) c = g.ControlValue(rng.Integer(0, g.ControlLevels()));
        if (rng.Chance(def.indpb) && static_cast<int>(genes.size()) < g.lengthMax)
            genes.push_back(g.ControlValue(rng.Integer(0, g.ControlLevels())));
        if (rng.Chance(def.indpb) && static_cast<int>(genes.size()) > g.lengthMin) genes.pop_back();
    }
    // Fibre genes: angles by clamped Gaussian steps, switches flipped, each with probability INDPB.
    if (g.HasFibreGenes()) {
        auto& genes = genome.back();
        for (size_t k = 0; k < genes.size(); ++k) {
            if (!rng.Chance(def.indpb)) continue;
            if (static_cast<int>(k) < g.fibreAngles) genes[k] = std::clamp(genes[k] + g.fibreSigmaDeg * rng.Normal(), g.fibreAngleMin, g.fibreAngleMax);
            else genes[k] = genes[k] > 0.5 ? 0.0 : 1.0;
        }
    }
}

// DEAP's cxTwoPoint on each pair of gene lists (over the shorter length).
void CrossTwoPoint(Genome& a, Genome& b, Random& rng) {
    for (size_t k = 0; k < a.size() && k < b.size(); ++k) {
        const long long size = static_cast<long long>(std::min(a[k].size(), b[k].size()));
        if (size < 2) continue;
        long long first = rng.Integer(1, size);
        long long second = rng.Integer(1, size - 1);
        if (second >= first) ++second;
        else std::swap(first, second);
        std::swap_ranges(a[k].begin() + first, a[k].begin() + second, b[k].begin() + first);
    }
}

// Tournament of k aspirants drawn with replacement from the valid individuals; the first best wins
// (DEAP's selTournament). Failed individuals never enter.
const Individual& Tournament(const std::vector<const Individual*>& valid, int k, Random& rng) {
    const Individual* best = nullptr;
    for (int draw = 0; draw < k; ++draw) {
        const Individual* aspirant = valid[static_cast<size_t>(rng.Integer(0, static_cast<long long>(valid.size()) - 1))];
        if (!best || aspirant->fitness > best->fitness) best = aspirant;
    }
    return *best;
}

void Evaluate(std::vector<Individual>& population, const GenomeEvaluator& evaluate, int* evaluations) {
    std::vector<Individual*> pending;
    std::vector<const Genome*> genomes;
    for (auto& individual : population)
        if (!individual.evaluated) {
            pending.push_back(&individual);
            genomes.push_back(&individual.genome);
        }
    *evaluations = static_cast<int>(pending.size());
    if (pending.empty()) return;
    const auto results = evaluate(genomes);
    for (size_t j = 0; j < pending.size(); ++j) {
        pending[j]->evaluated = true;
        pending[j]->fitness = results[j].first;
        pending[j]->status = results[j].second;
    }
}

// Valid individuals, best first; ties keep population order.
std::vector<const Individual*> RankValid(const std::vector<Individual>& population) {
    std::vector<const Individual*> valid;
    for (const auto& individual : population)
        if (individual.Valid()) valid.push_back(&individual);
    std::stable_sort(valid.begin(), valid.end(), [](const Individual* a, const Individual* b) { return a->fitness > b->fitness; });
    return valid;
}

void Record(GaState& state, int evaluations) {
    LogbookRow row;
    row.generation = state.generation;
    row.evaluations = evaluations;
    const auto ranked = RankValid(state.population);
    row.invalid = static_cast<int>(state.population.size() - ranked.size());
    if (!ranked.empty()) {
        row.best = ranked.front()->fitness;
        row.worst = ranked.back()->fitness;
        double sum = 0;
        for (const auto* individual : ranked) sum += individual->fitness;
        row.mean = sum / ranked.size();
        double squares = 0;
        for (const auto* individual : ranked) squares += (individual->fitness - row.mean) * (individual->fitness - row.mean);
        row.stddev = std::sqrt(squares / ranked.size());
        std::vector<double> ascending;
        for (auto it = ranked.rbegin(); it != ranked.rend(); ++it) ascending.push_back((*it)->fitness);
        row.q1 = SortedQuantile(ascending, 0.25);
        row.median = SortedQuantile(ascending, 0.5);
        row.q3 = SortedQuantile(ascending, 0.75);
        state.bestPerGeneration.push_back(*ranked.front());
    } else {
        row.best = row.worst = row.mean = row.stddev = std::nan("");
        state.bestPerGeneration.push_back(state.population.front());
    }
    ChainGaLogbookRow(row, state.logbook.empty() ? nullptr : &state.logbook.back());
    state.logbook.push_back(row);
    for (const auto* individual : ranked) {
        const bool known = std::any_of(state.hallOfFame.begin(), state.hallOfFame.end(),
                                       [&](const Individual& h) { return h.genome == individual->genome; });
        if (known) continue;
        state.hallOfFame.push_back(*individual);
    }
    std::stable_sort(state.hallOfFame.begin(), state.hallOfFame.end(),
                     [](const Individual& a, const Individual& b) { return a.fitness > b.fitness; });
    if (state.hallOfFame.size() > kHallOfFameSize) state.hallOfFame.resize(kHallOfFameSize);
}

}  // namespace

bool GenomeDef::OnControlGrid(double c) const {
    if (!(c >= controlMin - 1e-9 * controlStep && c <= controlMax + 1e-9 * controlStep)) return false;
    const double level = (c - controlMin) / controlStep;
    return c == ControlValue(std::llround(level));
}

std::string ControlGridError(const GenomeDef& g) {
    if (!std::isfinite(g.controlMin) || !std::isfinite(g.controlMax)) return "the control point range must be finite";
    if (g.controlMin > g.controlMax) return "the control point range is reversed (give the low end first)";
    if (!(g.controlStep > 0) || !std::isfinite(g.controlStep)) return "the control step must be positive";
    const double levels = (g.controlMax - g.controlMin) / g.controlStep;
    if (levels > 1e6) return "the control grid has more than a million points (a larger step)";
    if (std::fabs(levels - std::round(levels)) > 1e-9 * std::max(1.0, levels))
        return "the control step must divide the control range (max - min a whole number of steps)";
    return "";
}

std::string GaDefError(const GaDef& d, const MeshDef& mesh) {
    if (d.population < 2) return "population must be at least 2";
    if (d.generations < 0) return "generations must not be negative";
    if (d.tournament < 1) return "tournament size must be at least 1";
    if (d.elite < 0 || d.elite >= d.population) return "elite must be at least 0 and smaller than the population";
    for (double p : {d.mutpb, d.indpb, d.cxpb})
        if (!(p >= 0 && p <= 1)) return "probabilities (mutpb, indpb, cxpb) must be between 0 and 1";
    const GenomeDef& g = d.genome;
    if (g.kind == GenomeKind::BSpline) {
        if (g.splines != 1 && g.splines != 2 && g.splines != 4) return "splines must be 1, 2 or 4";
        if (std::string e = ControlGridError(g); !e.empty()) return e;
        if (g.lengthMin < 4) return "a spline needs at least 4 control points (length min >= 4)";
        if (g.lengthMin > g.lengthMax) return "length range is empty (min > max)";
        if (g.splines > mesh.resolution) return "more splines than vertices per turn";
    } else {
        if (!(g.initRange >= 0) || !(g.sigma >= 0) || !(g.bound > 0) || !std::isfinite(g.initRange + g.sigma + g.bound))
            return "free-xy init_range and sigma must be >= 0 and bound > 0";
    }
    if (g.fibreAngles < 0 || g.fibreAngles > 64) return "fibre angle genes must number 0 to 64";
    if (!(g.fibreAngleMin >= -90 && g.fibreAngleMax <= 90 && g.fibreAngleMin <= g.fibreAngleMax)) return "the fibre angle range must lie within -90 to 90 degrees, low end first";
    if (!(g.fibreSigmaDeg >= 0) || !std::isfinite(g.fibreSigmaDeg)) return "the fibre angle mutation's sigma must be >= 0 degrees";
    return "";
}

Shape ShapeOfGenome(const Genome& whole, const GenomeDef& def, const MeshDef& mesh) {
    const Genome genome = ShapeGenes(whole, def);
    if (def.kind == GenomeKind::FreeXY) {
        FreeXYShape s;
        const auto& offsets = genome.at(0);
        const size_t n = static_cast<size_t>(VertexCount(mesh));
        s.dx.resize(n);
        s.dy.resize(n);
        for (size_t i = 0; i < n; ++i) {
            s.dx[i] = offsets[2 * i];
            s.dy[i] = offsets[2 * i + 1];
        }
        return s;
    }
    return BSplineShape{def.region, genome};
}

FibreDef FibresOfGenome(const Genome& genome, const GenomeDef& def, FibreDef base) {
    if (!def.HasFibreGenes() || genome.empty()) return base;
    const auto& genes = genome.back();
    if (def.fibreAngles == 1 && !genes.empty()) base.angleDeg = genes[0];
    if (def.fibreAngles > 1) {
        base.bands.clear();
        for (int k = 0; k < def.fibreAngles && k < static_cast<int>(genes.size()); ++k)
            base.bands.push_back({double(k) / def.fibreAngles, k + 1 == def.fibreAngles ? 1.0 : double(k + 1) / def.fibreAngles, genes[static_cast<size_t>(k)]});
        base.sectorAnglesDeg.clear();
    }
    if (def.fibreSwitches && static_cast<int>(genes.size()) >= def.fibreAngles + 2) {
        base.plus = genes[static_cast<size_t>(def.fibreAngles)] > 0.5;
        base.minus = genes[static_cast<size_t>(def.fibreAngles) + 1] > 0.5;
    }
    return base;
}

Genome GenomeOfDesign(const Shape& shape, const FibreDef& fibres, const GenomeDef& def) {
    Genome genome = GenomeOfShape(shape);
    if (!def.HasFibreGenes()) return genome;
    std::vector<double> genes;
    if (def.fibreAngles == 1) genes.push_back(fibres.angleDeg);
    for (int k = 0; def.fibreAngles > 1 && k < def.fibreAngles; ++k)
        genes.push_back(k < static_cast<int>(fibres.bands.size()) ? fibres.bands[static_cast<size_t>(k)].angleDeg : fibres.angleDeg);
    if (def.fibreSwitches) {
        genes.push_back(fibres.plus ? 1.0 : 0.0);
        genes.push_back(fibres.minus ? 1.0 : 0.0);
    }
    genome.push_back(genes);
    return genome;
}

Genome GenomeOfShape(const Shape& shape) {
    if (const auto* b = std::get_if<BSplineShape>(&shape)) return b->splines;
    if (const auto* f = std::get_if<FreeXYShape>(&shape)) {
        std::vector<double> offsets(2 * f->dx.size());
        for (size_t i = 0; i < f->dx.size() && i < f->dy.size(); ++i) {
            offsets[2 * i] = f->dx[i];
            offsets[2 * i + 1] = f->dy[i];
        }
        return {offsets};
    }
    return {};
}

GaState StartEvolution(const GaDef& def, const MeshDef& mesh, std::uint64_t seed, const GenomeEvaluator& evaluate) {
    GaState state;
    state.rng = Random(seed);
    for (int i = 0; i < def.population; ++i) state.population.push_back(Individual{RandomGenome(def.genome, mesh, state.rng)});
    int evaluations = 0;
    Evaluate(state.population, evaluate, &evaluations);
    Record(state, evaluations);
    return state;
}

bool EvolveOneGeneration(const GaDef& def, const MeshDef& mesh, GaState& state, const GenomeEvaluator& evaluate) {
    const auto ranked = RankValid(state.population);
    if (ranked.empty()) return false;

    std::vector<Individual> next;
    for (int e = 0; e < def.elite && e < static_cast<int>(ranked.size()); ++e) next.push_back(*ranked[e]);
    std::vector<Individual> offspring;
    while (static_cast<int>(next.size() + offspring.size()) < def.population)
        offspring.push_back(Tournament(ranked, def.tournament, state.rng));

    // DEAP's varAnd: crossover on consecutive pairs, then mutation; changed individuals lose their fitness.
    for (size_t i = 1; i < offspring.size(); i += 2) {
        if (state.rng.Chance(def.cxpb)) {
            CrossTwoPoint(offspring[i - 1].genome, offspring[i].genome, state.rng);
            offspring[i - 1].evaluated = offspring[i].evaluated = false;
        }
    }
    for (auto& individual : offspring) {
        if (state.rng.Chance(def.mutpb)) {
            Mutate(individual.genome, def, mesh, state.rng);
            individual.evaluated = false;
        }
    }
    int evaluations = 0;
    Evaluate(offspring, evaluate, &evaluations);
    next.insert(next.end(), offspring.begin(), offspring.end());
    state.population = std::move(next);
    ++state.generation;
    Record(state, evaluations);
    return true;
}

std::string GenomeText(const Genome& genome) {
    std::string text;
    char buffer[32];
    for (size_t k = 0; k < genome.size(); ++k) {
        if (k) text += ';';
        for (size_t j = 0; j < genome[k].size(); ++j) {
            if (j) text += ',';
            text.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, genome[k][j]).ptr);
        }
    }
    return text;
}

std::string GaStopReason(const GaDef& def, const GaState& state) {
    if (state.generation >= def.generations) return "generations";
    const StopDef& s = def.stop;
    if (state.logbook.empty()) return "";
    if (s.evaluations > 0 && state.logbook.back().evaluationsSoFar >= s.evaluations) return "evaluations";
    // Elitism keeps the best: a generation's best is the run's best so far.
    const double best = state.logbook.back().best;
    if (std::isfinite(s.target) && best >= s.target) return "target";
    if (s.stagnation > 0 && state.logbook.size() > static_cast<size_t>(s.stagnation) &&
        !(best > state.logbook[state.logbook.size() - 1 - static_cast<size_t>(s.stagnation)].best))
        return "stagnation";
    return "";
}

}  // namespace sim
