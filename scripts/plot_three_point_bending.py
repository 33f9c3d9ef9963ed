#!/usr/bin/python3
"""Three-point bending of a notched beam: load against crack mouth opening (CMOD) and
against the load-point deflection, with the final damage field of the beam, in one
PNG; with --reference, the load-CMOD envelope of the test series the shipped beam
reproduces (Gregoire et al. 2013, beam B4) drawn behind the curves.

    /usr/bin/python3 scripts/plot_three_point_bending.py output/three_point_bending \\
        --reference --out three_point_bending.png

Each argument is an output directory of a 'three point bending' run (history.csv,
summary.json, parameters.prm, damage.csv). The load is force_<loading roller>_mean_y
(N, for the run's width: Problem/Thickness in 2D), the CMOD is opening_cmod (mm) and the
deflection is the loading roller's travel from its seat (mm). The beam's geometry comes
from the run's own parameters.prm. --csv writes the curves drawn (run, cmod, deflection
in m, load in N).
"""
import argparse
import csv
import os
import sys

import matplotlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_plots import parameter, read_parameters, read_rows, read_summary  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENE = "Scene/three point bending/"

# Gregoire, Rojas-Solano & Pijaudier-Cabot (2013), beam B4 (D = 50 mm, b = 50 mm, S =
# 125 mm, a0 = D/2): the lowest and highest load (N) over the specimens at each CMOD
# (mm), read from the envelope the tests' curves span (doc/reference_data.md).
B4_ENVELOPE = [(0.0050, 365.5, 427.0), (0.0180, 932.8, 1059.1), (0.0230, 863.2, 1113.9),
               (0.0300, 787.4, 1018.1), (0.0500, 637.3, 896.0), (0.0750, 453.5, 710.9),
               (0.0975, 388.7, 649.8), (0.1500, 258.0, 527.7), (0.2000, 169.6, 411.5)]


def curves(run):
    """(cmod mm, deflection mm, load N, parameters) of one run."""
    values = read_parameters(run)
    load = values.get(SCENE + "Loading roller", "load")
    rows = read_rows(os.path.join(run, "history.csv"), "three point bending")
    for column in ("opening_cmod", "force_%s_mean_y" % load, "displacement_%s_y" % load):
        if column not in rows[0]:
            sys.exit("%s/history.csv: no column '%s' (is it a three point bending run?)"
                     % (run, column))
    cmod = [1e3 * float(r["opening_cmod"]) for r in rows]
    deflection = [-1e3 * float(r["displacement_%s_y" % load]) for r in rows]
    force = [float(r["force_%s_mean_y" % load]) for r in rows]
    return cmod, deflection, force, values


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="output directories")
    ap.add_argument("--labels", help="comma-separated titles, one per run")
    ap.add_argument("--reference", action="store_true",
                    help="draw the B4 test envelope (Gregoire et al. 2013)")
    ap.add_argument("--out", default="three_point_bending.png")
    ap.add_argument("--csv", help="write the curves drawn to this CSV file")
    args = ap.parse_args()
    labels = args.labels.split(",") if args.labels else [
        os.path.basename(os.path.normpath(r)) for r in args.runs]
    if len(labels) != len(args.runs):
        sys.exit("--labels needs one title per run")

    fig = plt.figure(figsize=(11, 7.5))
    ax_c = fig.add_subplot(2, 2, 1)
    ax_d = fig.add_subplot(2, 2, 2)
    ax_f = fig.add_subplot(2, 1, 2)
    if args.reference:
        w = [p[0] for p in B4_ENVELOPE]
        ax_c.fill_between(w, [p[1] for p in B4_ENVELOPE], [p[2] for p in B4_ENVELOPE],
                          color="0.85", label="tests, B4 (Gregoire et al. 2013)")
    out = []
    for run, label in zip(args.runs, labels):
        cmod, deflection, force, values = curves(run)
        summary = read_summary(run)
        peak = summary.get("peak_force", max(force))
        ax_c.plot(cmod, force, label="%s: peak %.0f N" % (label, peak))
        ax_d.plot(deflection, force, label=label)
        out += [(label, 1e-3 * c, 1e-3 * d, f) for c, d, f in zip(cmod, deflection, force)]
    # The damage field of the first run, on the beam's reference configuration.
    run = args.runs[0]
    values = read_parameters(run)
    corner = [float(v) for v in str(parameter(values, SCENE + "Beam corner", run)).split(",")]
    length = parameter(values, SCENE + "Length", run)
    depth = parameter(values, SCENE + "Depth", run)
    damage = [r for r in read_rows(os.path.join(run, "damage.csv"), "three point bending")
              if r.get("body", "0") == "0"]
    sc = ax_f.scatter([1e3 * float(r["x0_0"]) for r in damage],
                      [1e3 * float(r["x0_1"]) for r in damage],
                      c=[float(r["damage"]) for r in damage], s=2, cmap="inferno_r",
                      vmin=0, vmax=1)
    ax_f.set_xlim(1e3 * corner[0], 1e3 * (corner[0] + length))
    ax_f.set_ylim(1e3 * corner[1], 1e3 * (corner[1] + depth))
    ax_f.set_aspect("equal")
    ax_f.set_xlabel("x (mm)")
    ax_f.set_ylabel("y (mm)")
    ax_f.set_title("damage at the end: %s" % labels[0])
    fig.colorbar(sc, ax=ax_f, shrink=0.8)
    ax_c.set_xlabel("CMOD (mm)")
    ax_d.set_xlabel("load-point deflection (mm)")
    for ax in (ax_c, ax_d):
        ax.set_ylabel("load (N)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["run", "cmod", "deflection", "load"])
            w.writerows(out)


if __name__ == "__main__":
    main()
