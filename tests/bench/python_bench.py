#!/usr/bin/env python3
"""The Python module's speed against the C++ it wraps (issue 15's targets), figures for the notes.

1. One evaluate() call with no relaxation (iterations 0), against the same call in C++
   (wire_bench's BM_EvaluateZeroIterations): what the binding adds per call.
2. 1,000 thesis-model designs (sine, A = 1 to 10, 10,000 iterations) on N threads: evaluate_many,
   evaluate_many through a process pool's map, and the command line's sweep of the same designs.

    PYTHONPATH=build/python /usr/bin/python3 tests/bench/python_bench.py --build build [--designs 1000] [--threads 2] [--rounds 3]
"""
import argparse
import concurrent.futures
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import actuator


def per_call_us(calls, repeats=5):
    shape = actuator.sine(4.1, (0.5, math.pi - 0.5))
    params = actuator.ThesisParams(iterations=0)
    best = math.inf
    for _ in range(repeats):
        t = time.perf_counter()
        for _ in range(calls):
            actuator.evaluate(shape, params=params)
        best = min(best, (time.perf_counter() - t) / calls * 1e6)
    return best


def cpp_call_us(build):
    out = subprocess.run([os.path.join(build, "tests", "wire_bench"), "--benchmark_filter=EvaluateZeroIterations", "--benchmark_format=json",
                          "--benchmark_repetitions=5"], check=True, capture_output=True, text=True).stdout
    # The fastest repetition, as per_call_us takes the fastest of its repeats.
    return min(r["real_time"] for r in json.loads(out)["benchmarks"] if r.get("run_type") == "iteration")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default="build", help="the build folder (default build)")
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--rounds", type=int, default=3, help="interleaved rounds, compared by medians (default 3)")
    args = parser.parse_args()

    py_us, cpp_us = per_call_us(2000), cpp_call_us(args.build)
    print(f"one evaluate() with 0 iterations: Python {py_us:.1f} us, C++ {cpp_us:.1f} us, the binding adds {py_us - cpp_us:.1f} us per call")

    # The three ways, interleaved over `rounds` rounds and compared by their medians: this shared
    # machine's speed drifts by several percent over a minute.
    amplitudes = np.linspace(1, 10, args.designs)
    shapes = [actuator.sine(float(a), (0.5, math.pi - 0.5)) for a in amplitudes]
    sweep = {"id": "bench", "sim": {"iterations": 10000},
             "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]},
                       "axes": [{"parameter": "amplitude", "from": 1, "to": 10, "points": args.designs}]},
             "render": {"figures": False, "thumbnails": False}}
    times = {"cli": [], "many": [], "map": []}
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ProcessPoolExecutor(args.threads) as pool:
        path = os.path.join(tmp, "sweep.json")
        with open(path, "w") as f:
            json.dump(sweep, f)
        list(pool.map(abs, range(args.threads)))  # start the workers before the clock
        reference = None
        for k in range(args.rounds):
            t = time.perf_counter()
            subprocess.run([os.path.join(args.build, "app", "actuator"), "sweep", path, "--out", os.path.join(tmp, f"out{k}"), "--threads",
                            str(args.threads)], check=True, capture_output=True)
            times["cli"].append(time.perf_counter() - t)
            t = time.perf_counter()
            local = actuator.evaluate_many(shapes, threads=args.threads)
            times["many"].append(time.perf_counter() - t)
            t = time.perf_counter()
            mapped = actuator.evaluate_many(shapes, map=pool.map)
            times["map"].append(time.perf_counter() - t)
            assert [r.fitness.hex() for r in mapped] == [r.fitness.hex() for r in local]
            print(f"  round {k + 1}: sweep {times['cli'][-1]:.2f} s, evaluate_many {times['many'][-1]:.2f} s, "
                  f"through a process pool {times['map'][-1]:.2f} s", flush=True)

    n = args.designs
    cli, many, mapped = (statistics.median(times[k]) for k in ("cli", "many", "map"))
    print(f"{n} thesis designs on {args.threads} threads (10,000 iterations each), medians of {args.rounds} rounds:")
    print(f"  actuator sweep (C++, archive included):   {cli:6.2f} s  {n / cli:6.1f} designs/s")
    print(f"  evaluate_many(threads={args.threads}):               {many:6.2f} s  {n / many:6.1f} designs/s  ({(many / cli - 1) * 100:+.1f} % time)")
    print(f"  evaluate_many(map=process pool map):     {mapped:6.2f} s  {n / mapped:6.1f} designs/s  ({(mapped / cli - 1) * 100:+.1f} % time)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
