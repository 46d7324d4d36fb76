#!/usr/bin/env python3
"""An Optuna study over the shell model: which braided sine contracts most at 3 kPa?

The design is a sine-profiled tube (Ecoflex 00-30, R = 5 mm, L = 150 mm, wall 1 mm) with a braid;
Optuna's TPE sampler chooses the amplitude (1 to 2 tube radii) and the braid's angle to the axis
(15 to 75 deg). actuator.optuna.Objective evaluates each trial, stores every output as a user
attribute, and reports a design that fails (a limit point, a wall stretched past its limit, a
self-intersection) as infeasible through Optuna's constraints, so the sampler learns to avoid it
instead of crashing or being rewarded.

    /usr/bin/python3 examples/optuna_study.py [--trials 40] [--seed 1] [--quick] [--json study.json]
"""
import argparse
import json
import math
import os
import sys
import warnings

import optuna

import actuator


def design(trial):
    amplitude = trial.suggest_float("amplitude", 1.0, 2.0)
    angle = trial.suggest_float("braid_angle_deg", 15.0, 75.0)
    return actuator.sine(amplitude), {"fibres": actuator.Fibres(fibres="braid", fibre_angle_deg=angle)}


def settings(quick):
    """The model's settings for every trial: the default mesh, or a coarse one for a quick look."""
    geometry = actuator.Geometry(ring_vertices=12, rings=16) if quick else actuator.Geometry()
    return {"model": "shell", "geometry": geometry, "load": actuator.Load(pressure_kpa=3, steps=2)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trials", type=int, default=40, help="trials to run (default 40)")
    parser.add_argument("--seed", type=int, default=1, help="the sampler's seed (default 1): the same seed, the same study")
    parser.add_argument("--quick", action="store_true", help="a coarse 12 x 16 mesh (seconds, not minutes)")
    parser.add_argument("--json", help="also write the study (every trial, the best) as JSON to this new file")
    args = parser.parse_args()
    if args.trials < 1:
        parser.error("--trials: at least 1")
    if args.json and os.path.exists(args.json):
        parser.error(f"--json: {args.json} exists; give another file")
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    warnings.filterwarnings("ignore", category=optuna.exceptions.ExperimentalWarning)  # constraints_func is "experimental" in Optuna 3.1

    objective = actuator.optuna.Objective(design, **settings(args.quick))
    sampler = optuna.samplers.TPESampler(seed=args.seed, constraints_func=actuator.optuna.constraints)
    study = optuna.create_study(direction="maximize", sampler=sampler)
    study.optimize(objective, n_trials=args.trials)

    # The best feasible trial (Optuna's best_trial may be an infeasible one's failed_value otherwise).
    feasible = [t for t in study.trials if t.user_attrs["status"] == "ok"]
    failed = [t for t in study.trials if t.user_attrs["status"] != "ok"]
    for t in study.trials:
        print(f"  trial {t.number:3d}: A = {t.params['amplitude']:.3f}, braid ±{t.params['braid_angle_deg']:.1f} deg -> "
              f"{t.user_attrs['status']}" + (f", contraction {t.value:+.3f} %" if t.user_attrs["status"] == "ok" else ""))
    if not feasible:
        print("no design converged", file=sys.stderr)
        return 1
    best = max(feasible, key=lambda t: t.value)
    print(f"best: trial {best.number}, A = {best.params['amplitude']:.4f}, braid ±{best.params['braid_angle_deg']:.2f} deg, "
          f"contraction {best.value:.4f} % at 3 kPa, max stretch {best.user_attrs['max_stretch']:.3f}; "
          f"{len(feasible)} ok, {len(failed)} failed ({', '.join(sorted({t.user_attrs['status'] for t in failed})) or 'none'})")
    if args.json:
        trials = [{"number": t.number, "params": t.params, "value": t.value if math.isfinite(t.value) else None, "attrs": t.user_attrs}
                  for t in study.trials]
        with open(args.json, "x") as f:
            json.dump({"best": {"number": best.number, "params": best.params, "value": best.value}, "trials": trials}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
