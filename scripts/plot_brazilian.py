#!/usr/bin/python3
"""Brazilian test: the load against the strips' approach for one or more runs, and the
final damage field of the first run, in one PNG.

    /usr/bin/python3 scripts/plot_brazilian.py output/brazilian --out brazilian.png

Each argument is an output directory of prm/brazilian.prm (history.csv, summary.json,
damage.csv). The load is force_top_y (N, for the run's thickness); the approach is
displacement_bottom_y - displacement_top_y (the strips' mean displacements). The load
axis is drawn as the nominal splitting stress 2 P / (pi D t) when --diameter and
--thickness are given (defaults: the scene's 0.15 m and 1 m).
"""
import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_columns(path, names):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("%s: no rows" % path)
    for n in names:
        if n not in rows[0]:
            sys.exit("%s: no column '%s' (is it a Brazilian run?)" % (path, n))
    return {n: [float(r[n]) for r in rows] for n in names}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="output directories")
    ap.add_argument("--out", default="brazilian.png")
    ap.add_argument("--diameter", type=float, default=0.15)
    ap.add_argument("--thickness", type=float, default=1.0)
    ap.add_argument("--tensile-strength", type=float, default=5.4e6,
                    help="f_t (Pa), drawn as a line")
    args = ap.parse_args()

    nominal = 2 / (math.pi * args.diameter * args.thickness)
    fig, (ax, ad) = plt.subplots(1, 2, figsize=(11, 4.8))
    for run in args.runs:
        h = read_columns(os.path.join(run, "history.csv"),
                         ["force_top_y", "displacement_top_y", "displacement_bottom_y"])
        approach = [1e6 * (b - t) for t, b in zip(h["displacement_top_y"],
                                                   h["displacement_bottom_y"])]
        stress = [1e-6 * nominal * p for p in h["force_top_y"]]
        label = os.path.basename(os.path.normpath(run))
        summary = os.path.join(run, "summary.json")
        if os.path.exists(summary):
            with open(summary) as f:
                s = json.load(f)
            if s.get("splitting_strength") is not None:
                label += " (peak %.2f MPa)" % (1e-6 * s["splitting_strength"])
        ax.plot(approach, stress, label=label)
    ax.axhline(1e-6 * args.tensile_strength, color="k", ls=":", lw=1, label="f_t")
    ax.set_xlabel("approach of the strips (um)")
    ax.set_ylabel("2 P / (pi D t) (MPa)")
    ax.set_title("load")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)

    damage = os.path.join(args.runs[0], "damage.csv")
    if os.path.exists(damage):
        with open(damage, newline="") as f:
            rows = list(csv.DictReader(f))
        x = [float(r["x0_0"]) for r in rows]
        y = [float(r["x0_1"]) for r in rows]
        d = [float(r["damage"]) for r in rows]
        order = sorted(range(len(d)), key=lambda i: d[i])  # damaged on top
        sc = ad.scatter([x[i] for i in order], [y[i] for i in order],
                        c=[d[i] for i in order], s=2, cmap="inferno_r", vmin=0, vmax=1)
        fig.colorbar(sc, ax=ad, label="damage")
        ad.set_aspect("equal")
        ad.set_title("damage at the end (reference positions)")
        ad.set_xlabel("x (m)")
        ad.set_ylabel("y (m)")
    else:
        ad.text(0.5, 0.5, "no damage.csv", ha="center")
    fig.tight_layout()
    fig.savefig(args.out, dpi=130)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
