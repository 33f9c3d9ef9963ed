#!/usr/bin/python3
"""Semicircular bending: for each run, the final damage field of the specimen drawn on
its reference configuration (the crack path) above the load against the loading
roller's displacement, in one PNG.

    /usr/bin/python3 scripts/plot_semicircular_bending.py out/a0 out/a30 out/a60 \\
        --out scb.png

Each argument is an output directory of prm/semicircular_bending.prm (history.csv,
summary.json, damage.csv). The load is force_load_y (N, whole specimen thickness); the
displacement is -displacement_load_y (mm). The damage is the particles' effective
damage chi in [0, 1] (damage.csv, body 0 = the specimen).
"""
import json
import os

import matplotlib
from scene_plots import parse_runs, read_rows

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    args, labels = parse_runs(__doc__, "semicircular_bending.png")

    n = len(args.runs)
    fig, axes = plt.subplots(2, n, figsize=(4.2 * n, 6.4), squeeze=False)
    for i, run in enumerate(args.runs):
        damage = [r for r in read_rows(os.path.join(run, "damage.csv"), "semicircular bending")
                  if r.get("body", "0") == "0"]
        history = read_rows(os.path.join(run, "history.csv"), "semicircular bending")
        with open(os.path.join(run, "summary.json")) as f:
            summary = json.load(f)
        x = [1e3 * float(r["x0_0"]) for r in damage]
        y = [1e3 * float(r["x0_1"]) for r in damage]
        chi = [float(r["damage"]) for r in damage]
        top = axes[0][i]
        sc = top.scatter(x, y, c=chi, s=1.5, cmap="inferno_r", vmin=0, vmax=1)
        top.set_aspect("equal")
        top.set_xlabel("x (mm)")
        top.set_ylabel("y (mm)")
        top.set_title("%s: peak %.0f N" % (labels[i], summary.get("peak_force", 0)))
        fig.colorbar(sc, ax=top, shrink=0.6, label="damage")
        bottom = axes[1][i]
        bottom.plot([-1e3 * float(r["displacement_load_y"]) for r in history],
                    [float(r["force_load_y"]) for r in history])
        bottom.set_xlabel("loading roller displacement (mm)")
        bottom.set_ylabel("load (N)")
        bottom.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
