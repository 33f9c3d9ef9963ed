#!/usr/bin/python3
"""Run time against error: the vibrating bar for every shape function over four grid
levels. Writes results.csv (one row per run; wall time is the median of --repeats runs
on one thread) and pareto.png (error against wall time, log-log).

    python3 benchmarks/run_time_vs_error.py --build build --out output/run_time_vs_error

--mass lists the mass treatments to compare, each a front of its own: lumped, K=1, K=2,
K=4 (Jacobi corrections) and consistent (default: the file's, two corrections); --cfl
sets the CFL number of every run (the consistent mass needs 0.1 with cubic B-splines).
A run that stops (unstable, or a solve that does not converge) is left out of the
front and printed.

    python3 benchmarks/run_time_vs_error.py --mass lumped,K=2,consistent --cfl 0.1
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
MASS = {"lumped": ["Time/Mass matrix corrections=0"],
        "K=1": ["Time/Mass matrix corrections=1"],
        "K=2": ["Time/Mass matrix corrections=2"],
        "K=4": ["Time/Mass matrix corrections=4"],
        "consistent": ["Time/Mass matrix corrections=0", "Time/Mass matrix=consistent"]}


def run(binary, scene, out, settings):
    cmd = [binary, scene, "--threads", "1", "--set", "Output/Directory=" + out,
           "--set", "Output/Write particle files=false", "--set", "Output/Verbosity=0"]
    for s in settings:
        cmd += ["--set", s]
    if subprocess.run(cmd).returncode != 0:
        return None
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="output/run_time_vs_error")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--mass", default="",
                        help="comma-separated treatments: " + ", ".join(MASS))
    parser.add_argument("--cfl", default="")
    args = parser.parse_args()
    masses = [m for m in args.mass.split(",") if m] or [""]
    for m in masses:
        if m and m not in MASS:
            parser.error(f"--mass: unknown treatment '{m}' (allowed: {', '.join(MASS)})")
    binary = os.path.join(args.build, "lme-mpm")
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for shape, gamma in SHAPES:
        for mass in masses:
            for h in LEVELS:
                settings = ["Shape functions/Type=" + shape, "Grid/Cell size=" + h]
                settings += MASS.get(mass, [])
                if args.cfl:
                    settings.append("Time/CFL=" + args.cfl)
                if gamma:
                    settings.append("Shape functions/LME gamma=" + gamma)
                if shape == "ugimp":  # particle boxes must tile the body for GIMP
                    settings.append("Body 1/Particle placement=uniform")
                walls = []
                for _ in range(args.repeats):
                    s = run(binary, "prm/vibrating_bar.prm", os.path.join(args.out, "run"),
                            settings)
                    if s is None:
                        break
                    walls.append(s["wall_seconds"])
                if s is None:
                    print(f"{shape} {mass} h = {h}: the run stopped", flush=True)
                    continue
                cells = round(1.25 / float(h)) * round(0.1 / float(h))
                rows.append({"shape_function": shape, "gamma": gamma, "mass": mass or "file",
                             "cells": cells, "particles": int(s["particles"]),
                             "steps": int(s["steps"]),
                             "wall_seconds": statistics.median(walls),
                             "error_displacement_l2": s["max_error_displacement_l2"],
                             "error_stress_l2": s["max_error_stress_l2"],
                             "mass_solve_mean_iterations":
                                 s.get("mass_solve_mean_iterations", "")})
                print(rows[-1], flush=True)
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key in zip(axes, ["error_displacement_l2", "error_stress_l2"]):
        for shape, gamma in SHAPES:
            for mass in masses:
                pts = [r for r in rows
                       if r["shape_function"] == shape and r["mass"] == (mass or "file")]
                if not pts:
                    continue
                label = shape + (" (gamma %s)" % gamma if gamma else "") + \
                    (", " + mass if mass else "")
                ax.loglog([r["wall_seconds"] for r in pts], [r[key] for r in pts], "o-",
                          label=label)
        ax.set_xlabel("wall time (s, one thread, median of %d)" % args.repeats)
        ax.set_ylabel(key)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=6 if len(masses) > 1 else 8)
    fig.suptitle("Vibrating bar: error against run time (h = 0.05 ... 0.00625 m)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "pareto.png"), dpi=90)


if __name__ == "__main__":
    main()
