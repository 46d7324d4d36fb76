#!/usr/bin/env python3
"""DEAP's own eaSimple over actuator.evaluate, on the thesis's problem 4.1.

The problem: a sine radius (phase 0.5 to pi-0.5) whose amplitude A, 1 to 10 mesh units, is the one
gene; fitness is the thesis model's contraction after 10,000 iterations of inflation (docs/models/thesis.md).
The workbench's 30-point sweep (assets/experiments/4.1_amplitude_sweep.json) is best at its grid
point A = 3.48 (fitness 0.597); the C++ genetic algorithm (pagmo's sga, assets/experiments/
optimizers/O4.1_ga_thesis.json) finds A = 3.64 (0.5983) between grid points, and so does this
script. The thesis reports A = 4.1 (0.75).

DEAP evaluates through toolbox.map. actuator.evaluate releases the GIL, so a thread pool's map runs
the simulations on every core; any map works (a process pool's, a Dask client's via
actuator.evaluate_many(..., map=client)).

    /usr/bin/python3 examples/deap_ga.py [--seed 1] [--population 12] [--generations 8] [--threads 2] [--json FILE]
"""
import argparse
import concurrent.futures
import json
import math
import os
import random
import sys

import actuator
from deap import algorithms, base, creator, tools

AMPLITUDE = (1.0, 10.0)  # mesh units, as the 4.1 sweep
PHASE = (0.5, math.pi - 0.5)
PARAMS = actuator.ThesisParams(iterations=10000)


def fitness(individual):
    """The thesis model's fitness of the sine with amplitude individual[0] (mesh units); a failed
    simulation (a status, never an exception) scores below every design."""
    result = actuator.evaluate(actuator.sine(individual[0], PHASE), model="thesis", params=PARAMS)
    return (result.fitness if result.status == "ok" else -1e9,)


def clamp(individual):
    individual[0] = min(max(individual[0], AMPLITUDE[0]), AMPLITUDE[1])
    return individual


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=1, help="Python's random seed (default 1)")
    parser.add_argument("--population", type=int, default=12, help="individuals (default 12)")
    parser.add_argument("--generations", type=int, default=8, help="generations (default 8)")
    parser.add_argument("--threads", type=int, default=os.cpu_count(), help="simulations at once (default: one per core)")
    parser.add_argument("--json", help="write the best design and the logbook to this new file")
    args = parser.parse_args()
    if args.population < 2 or args.generations < 0 or args.threads < 1:
        parser.error("--population must be 2 or more, --generations 0 or more, --threads 1 or more")
    if args.json and os.path.exists(args.json):
        parser.error(f"--json: {args.json} exists; choose a new file")

    random.seed(args.seed)
    creator.create("FitnessMax", base.Fitness, weights=(1.0,))
    creator.create("Individual", list, fitness=creator.FitnessMax)
    toolbox = base.Toolbox()
    toolbox.register("amplitude", random.uniform, *AMPLITUDE)
    toolbox.register("individual", tools.initRepeat, creator.Individual, toolbox.amplitude, n=1)
    toolbox.register("population", tools.initRepeat, list, toolbox.individual)
    toolbox.register("evaluate", fitness)
    toolbox.register("mate", lambda a, b: tuple(map(clamp, tools.cxBlend(a, b, alpha=0.3))))
    toolbox.register("mutate", lambda a: (clamp(tools.mutGaussian(a, mu=0.0, sigma=0.5, indpb=1.0)[0]),))
    toolbox.register("select", tools.selTournament, tournsize=3)

    stats = tools.Statistics(lambda ind: ind.fitness.values[0])
    stats.register("max", max)
    stats.register("mean", lambda v: sum(v) / len(v))
    hall = tools.HallOfFame(1)
    with concurrent.futures.ThreadPoolExecutor(args.threads) as pool:
        toolbox.register("map", pool.map)
        population = toolbox.population(n=args.population)
        population, logbook = algorithms.eaSimple(population, toolbox, cxpb=0.5, mutpb=0.3, ngen=args.generations, stats=stats,
                                                  halloffame=hall, verbose=False)
    best = hall[0]
    evaluations = sum(row["nevals"] for row in logbook)
    print(f"DEAP eaSimple, {args.population} x {args.generations} generations, {evaluations} simulations on {args.threads} threads")
    for row in logbook:
        print(f"  generation {row['gen']:2d}: {row['nevals']:2d} simulations, best {row['max']:.4f}, mean {row['mean']:.4f}")
    print(f"best: A = {best[0]:.3f} mesh units, fitness {best.fitness.values[0]:.4f} mesh units "
          f"(C++ GA: A = 3.64, 0.5983; thesis: A = 4.1, 0.75)")
    if args.json:
        record = {"amplitude": best[0], "fitness": best.fitness.values[0], "simulations": evaluations,
                  "logbook": [{"generation": r["gen"], "simulations": r["nevals"], "best": r["max"], "mean": r["mean"]} for r in logbook]}
        with open(args.json, "x") as f:
            json.dump(record, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
