#!/usr/bin/env python3
"""The Python module's speed against the C++ it wraps (issue 15's targets), figures for the notes.

1. One evaluate() call with no relaxation (iterations 0), against the same call in C++
   (wire_bench's BM_EvaluateZeroIterations): what the binding adds per call.
2. 1,000 thesis-model designs (sine, A = 1 to 10, 10,000 iterations) on N threads: evaluate_many,
   evaluate_many through a process pool's map, and the command line's sweep of the same designs.

    PYTHONPATH=build/python /usr/bin/python3 tests/bench/python_bench.py --build build [--designs 1000] [--threads 2]
"""
import argparse
import concurrent.futures
import json
import math
import os
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
    args = parser.parse_args()

    py_us, cpp_us = per_call_us(2000), cpp_call_us(args.build)
    print(f"one evaluate() with 0 iterations: Python {py_us:.1f} us, C++ {cpp_us:.1f} us, the binding adds {py_us - cpp_us:.1f} us per call")

    amplitudes = np.linspace(1, 10, args.designs)
    shapes = [actuator.sine(float(a), (0.5, math.pi - 0.5)) for a in amplitudes]
    t = time.perf_counter()
    local = actuator.evaluate_many(shapes, threads=args.threads)
    t_many = time.perf_counter() - t
    with concurrent.futures.ProcessPoolExecutor(args.threads) as pool:
        list(pool.map(abs, range(args.threads)))  # start the workers before the clock
        t = time.perf_counter()
        mapped = actuator.evaluate_many(shapes, map=pool.map)
        t_map = time.perf_counter() - t
    assert [r.fitness.hex() for r in mapped] == [r.fitness.hex() for r in local]

    sweep = {"id": "bench", "sim": {"iterations": 10000},
             "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]},
                       "axes": [{"parameter": "amplitude", "from": 1, "to": 10, "points": args.designs}]},
             "render": {"figures": False, "thumbnails": False}}
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "sweep.json")
        with open(path, "w") as f:
            json.dump(sweep, f)
        t = time.perf_counter()
        subprocess.run([os.path.join(args.build, "app", "actuator"), "sweep", path, "--out", os.path.join(tmp, "out"), "--threads",
                        str(args.threads)], check=True, capture_output=True)
        t_cli = time.perf_counter() - t

    n = args.designs
    print(f"{n} thesis designs on {args.threads} threads (10,000 iterations each):")
    print(f"  actuator sweep (C++, archive included):   {t_cli:6.2f} s  {n / t_cli:6.1f} designs/s")
    print(f"  evaluate_many(threads={args.threads}):               {t_many:6.2f} s  {n / t_many:6.1f} designs/s  ({(t_many / t_cli - 1) * 100:+.1f} % time)")
    print(f"  evaluate_many(map=process pool map):     {t_map:6.2f} s  {n / t_map:6.1f} designs/s  ({(t_map / t_cli - 1) * 100:+.1f} % time)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
