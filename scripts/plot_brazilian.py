#!/usr/bin/python3
"""Brazilian test: the load against the strips' approach for one or more runs, and the
final damage field of the first run, in one PNG.

    /usr/bin/python3 scripts/plot_brazilian.py output/brazilian --out brazilian.png

Each argument is an output directory of prm/brazilian.prm (history.csv, summary.json,
damage.csv, parameters.prm). The load is force_<top strip>_y, drawn as the nominal
splitting stress 2 P / (pi D t); the approach is the strips' mean displacements'
difference. D, t (Problem/Thickness in 2D, the scene's Length in 3D), the strips' names
and the disc's tensile strength f_t (drawn as a line) are read from each run's own
parameters.prm, so any disc is drawn to its own scale.
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_plots import body_material, parameter, read_parameters, read_summary  # noqa: E402


def read_columns(path, names):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("%s: no rows" % path)
    for n in names:
        if n not in rows[0]:
            sys.exit("%s: no column '%s' (is it a Brazilian run?)" % (path, n))
    return {n: [float(r[n]) for r in rows] for n in names}


def geometry(run):
    """The run's disc as its parameters.prm gives it: diameter D (m), thickness t (m),
    the top and bottom strips' names and the disc material's tensile strength (Pa, or
    None without eigensoftening)."""
    v = read_parameters(run)
    scene = "Scene/brazilian/"
    if parameter(v, "Scene/Type", run) != "brazilian":
        sys.exit("%s: Scene/Type is not 'brazilian'" % run)
    D = parameter(v, scene + "Diameter", run)
    t = (parameter(v, scene + "Length", run) if int(parameter(v, "Problem/Dimension", run)) == 3
         else parameter(v, "Problem/Thickness", run))
    m = body_material(v, parameter(v, scene + "Disc", run), run)
    f_t = v.get("Material %d/Fracture/Tensile strength" % m)
    model = v.get("Material %d/Fracture/Model" % m, "none")
    return dict(diameter=D, thickness=t, top=parameter(v, scene + "Top strip", run),
                bottom=parameter(v, scene + "Bottom strip", run),
                tensile_strength=float(f_t) if f_t is not None and model != "none" else None)


def curve(run):
    """(approach in um, nominal stress in MPa, geometry()) of one run."""
    g = geometry(run)
    top, bottom = g["top"], g["bottom"]
    h = read_columns(os.path.join(run, "history.csv"),
                     ["force_%s_y" % top, "displacement_%s_y" % top,
                      "displacement_%s_y" % bottom])
    approach = [1e6 * (b - t) for t, b in zip(h["displacement_%s_y" % top],
                                               h["displacement_%s_y" % bottom])]
    nominal = 2 / (math.pi * g["diameter"] * g["thickness"])
    stress = [1e-6 * nominal * p for p in h["force_%s_y" % top]]
    return approach, stress, g


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="output directories")
    ap.add_argument("--out", default="brazilian.png")
    args = ap.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, ad) = plt.subplots(1, 2, figsize=(11, 4.8))
    strengths = set()
    for run in args.runs:
        approach, stress, g = curve(run)
        label = os.path.basename(os.path.normpath(run)) + " (D %g mm)" % (1e3 * g["diameter"])
        s = read_summary(run)
        if s.get("splitting_strength") is not None:
            label += ", peak %.2f MPa" % (1e-6 * s["splitting_strength"])
        ax.plot(approach, stress, label=label)
        if g["tensile_strength"] is not None:
            strengths.add(g["tensile_strength"])
    for f_t in sorted(strengths):
        ax.axhline(1e-6 * f_t, color="k", ls=":", lw=1, label="f_t = %.3g MPa" % (1e-6 * f_t))
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
