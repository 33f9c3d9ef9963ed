#!/usr/bin/python3
"""Run time against error on a fracture scene: prm/brazilian.prm with every shape
function at three grid levels (strips 25 mm wide by default), each against a
fine-grid run of the same shape function. Writes results.csv and pareto.png into --out.

    /usr/bin/python3 benchmarks/brazilian_shape_functions.py --build build \\
        --out output/brazilian_shape_functions

Errors, per run, relative to the same shape function's run at --fine:
  - peak: |P_max - P_max,fine| / P_max,fine (summary.json peak_force);
  - centre: |k - k_fine| / k_fine, with k the centre sigma_xx over 2 P / (pi D t)
    averaged over the history rows of the elastic loading branch (from 0.2 ms to the
    first damage).
Wall time: the median of --repeats runs (all threads), runs of one level alternated
between shape functions. About 35 minutes on two cores with the defaults.
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SHAPES = ["linear", "ugimp", "bspline", "lme"]
LEVELS = ["0.005", "0.004", "0.0025"]


def centre_factor(rows):
    """The centre sigma_xx over 2 P / (pi D t), averaged over the elastic loading
    branch: rows from 0.2 ms (past the strips' ramp) until the first damage."""
    ratios = []
    for r in rows:
        if float(r["damage_total"]) > 0:
            break
        t, P = float(r["time"]), float(r["force_top_y"])
        if t >= 2e-4 and P > 0:
            ratios.append(float(r["probe_centre_sxx"]) / (2 * P / (math.pi * 0.15)))
    return statistics.mean(ratios)


def run(binary, out, shape, h, strip):
    cmd = [binary, "prm/brazilian.prm", "--set", "Output/Directory=" + out,
           "--set", "Scene/brazilian/Strip width=" + strip,
           "--set", "Output/Verbosity=0", "--set", "Shape functions/Type=" + shape,
           "--set", "Grid/Cell size=" + h]
    subprocess.run(cmd, check=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "history.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    return {"peak": summary["peak_force"], "centre": centre_factor(rows),
            "wall": summary["wall_seconds"], "particles": summary["particles"],
            "steps": summary["steps"], "status": summary["status"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="output/brazilian_shape_functions")
    ap.add_argument("--fine", default="0.00125")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--strip-width", default="0.025",
                    help="b (m); 0.025 spans five cells of the coarsest grid, the "
                         "scene's 0.010 only two (too few: doc/brazilian.md)")
    args = ap.parse_args()
    binary = os.path.join(args.build, "lme-mpm")
    os.makedirs(args.out, exist_ok=True)

    fine = {}
    for s in SHAPES:
        fine[s] = run(binary, os.path.join(args.out, "%s_fine" % s), s, args.fine,
                      args.strip_width)
        print(s, "fine:", fine[s], flush=True)
    rows = []
    for h in LEVELS:
        walls = {s: [] for s in SHAPES}
        last = {}
        for _ in range(args.repeats):
            for s in SHAPES:
                last[s] = run(binary, os.path.join(args.out, "%s_%s" % (s, h)), s, h,
                              args.strip_width)
                walls[s].append(last[s]["wall"])
        for s in SHAPES:
            r = last[s]
            rows.append({
                "shape_functions": s, "cell_size": h, "particles": r["particles"],
                "steps": r["steps"], "wall_median": statistics.median(walls[s]),
                "wall_runs": " ".join("%.2f" % w for w in walls[s]),
                "peak_force": r["peak"], "peak_force_fine": fine[s]["peak"],
                "error_peak": abs(r["peak"] - fine[s]["peak"]) / fine[s]["peak"],
                "centre_factor": r["centre"], "centre_factor_fine": fine[s]["centre"],
                "error_centre": abs(r["centre"] - fine[s]["centre"]) / fine[s]["centre"],
                "fine_wall": fine[s]["wall"]})
            print(rows[-1], flush=True)
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    plot(rows, args.out)


def plot(rows, out):
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    for ax, key, title in zip(axes, ["error_peak", "error_centre"],
                              ["peak load", "centre stress per load"]):
        for s in SHAPES:
            pts = [(float(r["wall_median"]), max(float(r[key]), 1e-5)) for r in rows
                   if r["shape_functions"] == s]
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=s)
        ax.set_xlabel("wall time (s, median of runs, two threads)")
        ax.set_ylabel("relative error against the fine grid")
        ax.set_title(title)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "pareto.png"), dpi=130)
    print("wrote", os.path.join(out, "results.csv"), "and pareto.png")


if __name__ == "__main__":
    main()
