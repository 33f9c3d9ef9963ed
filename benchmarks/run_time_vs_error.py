#!/usr/bin/python3
"""Run time against error: the vibrating bar for every shape function over four grid
levels. Writes results.csv (one row per run; wall time is the median of --repeats runs
on one thread) and pareto.png (error against wall time, log-log).

    python3 benchmarks/run_time_vs_error.py --build build --out output/run_time_vs_error
"""
import argparse
import csv
import json
import os
import statistics
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SHAPES = [("linear", ""), ("ugimp", ""), ("bspline", ""), ("lme", "1.8")]
LEVELS = ["0.05", "0.025", "0.0125", "0.00625"]


def run(binary, scene, out, settings):
    cmd = [binary, scene, "--threads", "1", "--set", "Output/Directory=" + out,
           "--set", "Output/Write particle files=false", "--set", "Output/Verbosity=0"]
    for s in settings:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="output/run_time_vs_error")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    binary = os.path.join(args.build, "lme-mpm")
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for shape, gamma in SHAPES:
        for h in LEVELS:
            settings = ["Shape functions/Type=" + shape, "Grid/Cell size=" + h]
            if gamma:
                settings.append("Shape functions/LME gamma=" + gamma)
            if shape == "ugimp":  # particle boxes must tile the body for GIMP
                settings.append("Body 1/Particle placement=uniform")
            walls = []
            for _ in range(args.repeats):
                s = run(binary, "prm/vibrating_bar.prm", os.path.join(args.out, "run"), settings)
                walls.append(s["wall_seconds"])
            cells = round(1.25 / float(h)) * round(0.1 / float(h))
            rows.append({"shape_function": shape, "gamma": gamma, "cells": cells,
                         "particles": int(s["particles"]), "steps": int(s["steps"]),
                         "wall_seconds": statistics.median(walls),
                         "error_displacement_l2": s["max_error_displacement_l2"],
                         "error_stress_l2": s["max_error_stress_l2"]})
            print(rows[-1], flush=True)
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key in zip(axes, ["error_displacement_l2", "error_stress_l2"]):
        for shape, gamma in SHAPES:
            pts = [r for r in rows if r["shape_function"] == shape]
            label = shape + (" (gamma %s)" % gamma if gamma else "")
            ax.loglog([r["wall_seconds"] for r in pts], [r[key] for r in pts], "o-", label=label)
        ax.set_xlabel("wall time (s, one thread, median of %d)" % args.repeats)
        ax.set_ylabel(key)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend()
    fig.suptitle("Vibrating bar: error against run time (h = 0.05 ... 0.00625 m)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "pareto.png"), dpi=90)


if __name__ == "__main__":
    main()
