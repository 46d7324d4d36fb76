#!/usr/bin/env python3
"""A contraction-pressure curve with Matplotlib, notebook style: why fibres decide whether a tube
contracts.

A plain silicone tube (Ecoflex 00-30, R = 5 mm, L = 150 mm, wall 1 mm) lengthens when inflated.
Braided fibres change that: like a McKibben muscle, a braid closer to the axis than the "magic
angle" arctan(sqrt 2) = 54.7 deg shortens the tube, and one further from it lengthens it. Each curve is
one evaluation of the shell model (docs/models/shell.md): equilibrium at every load step, up to 1.2 kPa (below the plain tube's pressure maximum, about 2.4 kPa).

    /usr/bin/python3 examples/contraction_pressure.py [--out contraction_pressure.png] [--threads 2]
"""
import argparse
import concurrent.futures
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files, no display
import matplotlib.pyplot as plt

import actuator

# %% The designs: the plain tube, and braids at angles to the axis around the magic angle.
MAGIC_DEG = math.degrees(math.atan(math.sqrt(2.0)))
BRAIDS_DEG = [20.0, 35.0, MAGIC_DEG, 70.0]
LOAD = actuator.Load(pressure_kpa=1.2, steps=8)


def curves(threads):
    """{label: (pressure kPa list, contraction % list)}, the plain tube first."""
    fibres = [actuator.Fibres(fibres="none")] + [actuator.Fibres(fibres="braid", fibre_angle_deg=a) for a in BRAIDS_DEG]
    labels = ["plain tube"] + [f"braid ±{a:.1f}°" for a in BRAIDS_DEG]
    # actuator.evaluate releases the GIL while it solves: a thread pool runs the designs side by side.
    with concurrent.futures.ThreadPoolExecutor(threads) as pool:
        results = list(pool.map(lambda f: actuator.evaluate(actuator.cylinder(), model="shell", load=LOAD, fibres=f), fibres))
    out = {}
    for label, r in zip(labels, results):
        if r.status != "ok":
            print(f"{label}: {r.status}", file=sys.stderr)
            continue
        # The curve starts at rest: 0 kPa, 0 %.
        pressure = [0.0] + list(r.shell["curve_pressure_kpa"])
        contraction = [0.0] + list(r.shell["curve_contraction_percent"])
        out[label] = (pressure, contraction)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="contraction_pressure.png", help="the PNG to write, a new file (default contraction_pressure.png)")
    parser.add_argument("--threads", type=int, default=os.cpu_count(), help="designs solved at once (default: one per core)")
    args = parser.parse_args()
    if args.threads < 1:
        parser.error("--threads must be 1 or more")
    if os.path.exists(args.out):
        parser.error(f"--out: {args.out} exists; choose a new file")

    # %% Evaluate and print the numbers behind the picture.
    data = curves(args.threads)
    for label, (pressure, contraction) in data.items():
        print(f"{label:>14}: contraction at {pressure[-1]:.1f} kPa = {contraction[-1]:+.2f} %")

    # %% Plot: contraction (positive = shorter) against pressure.
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    for label, (pressure, contraction) in data.items():
        style = dict(color="0.4", linestyle="--") if label == "plain tube" else {}
        ax.plot(pressure, contraction, marker="o", markersize=3, label=label, **style)
    ax.axhline(0, color="0.7", linewidth=0.8)
    ax.set_xlabel("pressure (kPa)")
    ax.set_ylabel("contraction (%)  — positive = shorter")
    ax.set_title("Shell model: a braid at under 54.7° to the axis contracts, over it lengthens\n"
                 "Ecoflex 00-30, R 5 mm, L 150 mm, wall 1 mm", fontsize=10)
    ax.legend(fontsize=8, loc="best")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out + ".part.png")
    os.replace(args.out + ".part.png", args.out)  # whole or not at all
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
