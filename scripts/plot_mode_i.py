#!/usr/bin/env python3
"""Mode-I panel: reaction against imposed displacement for several runs, the Griffith
prediction drawn in, and a table of peak, displacement at peak, oscillation of the
loading branch and crack extent through the ligament.

    python3 scripts/plot_mode_i.py output/mode_i_panel*/ --out mode_i_panel.png

Each argument is an output directory (history.csv, summary.json, parameters.prm and,
for the crack, failed_particles.csv). The panel, its crack and its material come from
the first run's parameters.prm (Body 1's rectangle and slot, Material 1's E, nu and
G_c, the thickness). On the shipped panel's proportions (a / W = 1/4, H = W, nu = 0.333,
plane strain) the Griffith line is the finite-element one of doc/reference_data.md
section 2 (stiffness 0.990 and delta_c = 0.00651 at E = 1.06, G_c = 1e-4, W = t = 1),
scaled to the run's E, G_c, size and thickness; on other proportions it is the
fixed-grip strip's (delta_c = sqrt(G_c H / (2 E')), stiffness E' W t / H), which the
script says. Options override any value."""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_plots import parameter, read_parameters  # noqa: E402


def read_history(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def oscillation(d, P, fraction=0.9):
    """RMS deviation from a straight-line fit of the loading branch up to `fraction` of
    the peak, relative to the peak (0 for a perfectly straight branch)."""
    ipk = int(np.argmax(P))
    upto = np.nonzero(P[: ipk + 1] >= fraction * P[ipk])[0]
    end = upto[0] if len(upto) else ipk
    x, y = d[: end + 1], P[: end + 1]
    if len(x) < 3:
        return float("nan")
    a, b = np.polyfit(x, y, 1)
    return float(np.sqrt(np.mean((y - (a * x + b)) ** 2)) / P[ipk])


def stiffness(d, P, at):
    """P / (2 delta) where the opening first reaches `at` (on the linear branch)."""
    i = int(np.searchsorted(d, at))
    return float(P[i] / (2 * d[i])) if i < len(d) and d[i] > 0 else float("nan")


def ligament_cut(run, a, width, y_crack, band, bins):
    """Fraction of the ligament (x from a to width) in which some particle within
    `band` of the crack line has failed; 1 means the crack ran through."""
    path = os.path.join(run, "failed_particles.csv")
    if not os.path.exists(path):
        return float("nan"), float("nan")
    data = np.atleast_2d(np.genfromtxt(path, delimiter=",", names=True))
    if data.size == 0 or "x0_0" not in data.dtype.names:
        return 0.0, float("nan")
    x0, y0 = np.ravel(data["x0_0"]), np.ravel(data["x0_1"])
    near = np.abs(y0 - y_crack) <= band
    edges = np.linspace(a, width, bins + 1)
    hit = [np.any(near & (x0 >= lo) & (x0 < hi)) for lo, hi in zip(edges[:-1], edges[1:])]
    spread = float(np.max(np.abs(y0[near] - y_crack))) if near.any() else float("nan")
    return float(np.mean(hit)), spread


def call_arguments(text, name, run):
    """The numbers of 'name(a, b, ...)' in @p text."""
    text = text.strip()
    if not text.startswith(name + "("):
        sys.exit("%s/parameters.prm: expected %s(...), got '%s'" % (run, name, text))
    return [float(v) for v in text[len(name) + 1:-1].split(",")]


def griffith(run):
    """The panel's Griffith line from the run's own parameters.prm: (stiffness P/(2 delta),
    delta_c, crack length, width, crack height, note)."""
    v = read_parameters(run)
    x0, y0, x1, y1 = call_arguments(parameter(v, "Body 1/Shape", run), "rectangle", run)
    slot = call_arguments(v.get("Body 1/Holes", "").split(";")[0] or "slot(0,0,0,0,0)",
                          "slot", run)
    W, H, a, y_crack = x1 - x0, y1 - y0, slot[2], slot[1]
    E = parameter(v, "Material 1/linear elastic/Young's modulus", run)
    nu = parameter(v, "Material 1/linear elastic/Poisson's ratio", run)
    G_c = parameter(v, "Material 1/Fracture/Fracture energy", run)
    t = parameter(v, "Problem/Thickness", run)
    strain = parameter(v, "Problem/Plane assumption", run) == "plane strain"
    E_prime = E / (1 - nu * nu) if strain else E
    reference = (strain and abs(nu - 0.333) < 1e-3 and abs(a / W - 0.25) < 1e-6
                 and abs(H / W - 1) < 1e-6)
    if reference:
        # The finite-element values scale as E t (stiffness) and sqrt(G_c H / E).
        k = 0.990 * (E / 1.06) * t
        delta_c = 0.00651 * math.sqrt((G_c / 1e-4) * (H / 1.0) / (E / 1.06))
        note = "finite-element Griffith line of the reference panel, scaled"
    else:
        k = E_prime * W * t / H
        delta_c = math.sqrt(G_c * H / (2 * E_prime))
        note = ("fixed-grip strip formula: the panel's proportions differ from the "
                "reference (a/W %.3g, H/W %.3g, nu %.3g)" % (a / W, H / W, nu))
    return k, delta_c, a, W, y_crack, note


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="output directories")
    ap.add_argument("--out", default="mode_i_panel.png")
    ap.add_argument("--stiffness", type=float, help="P/(2 delta) of the panel")
    ap.add_argument("--delta-c", type=float, help="Griffith opening per edge")
    ap.add_argument("--crack-length", type=float)
    ap.add_argument("--width", type=float)
    ap.add_argument("--crack-y", type=float)
    ap.add_argument("--band", type=float, default=0.1, help="half-width of the crack band checked")
    ap.add_argument("--table", default=None, help="also write the table to this CSV")
    args = ap.parse_args()
    k, delta_c, a, W, y_crack, note = griffith(args.runs[0])
    for name, value in (("stiffness", k), ("delta_c", delta_c), ("crack_length", a),
                        ("width", W), ("crack_y", y_crack)):
        if getattr(args, name) is None:
            setattr(args, name, value)
    print("Griffith: stiffness %.4g, delta_c %.4g, peak %.4g (%s)"
          % (args.stiffness, args.delta_c, 2 * args.stiffness * args.delta_c, note))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    P_c = 2 * args.stiffness * args.delta_c
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    dmax = 0.0
    rows = []
    for run in args.runs:
        h = read_history(os.path.join(run, "history.csv"))
        d, P = h["displacement_top_y"], h["force_top_y"]
        label = os.path.basename(os.path.normpath(run))
        summary = {}
        if os.path.exists(os.path.join(run, "summary.json")):
            with open(os.path.join(run, "summary.json")) as f:
                summary = json.load(f)
        peak = summary.get("peak_force", float(np.max(P)))
        d_peak = summary.get("displacement_at_peak", float(d[np.argmax(P)]))
        cut, spread = ligament_cut(run, args.crack_length, args.width, args.crack_y, args.band, 30)
        rows.append(dict(run=label, shape_function=summary.get("shape_function", "?"),
                         peak_force=peak, peak_error=peak / P_c - 1,
                         displacement_at_peak=d_peak, displacement_error=d_peak / args.delta_c - 1,
                         oscillation=oscillation(d, P), ligament_cut=cut, crack_band_halfwidth=spread,
                         stiffness=stiffness(d, P, 0.6 * args.delta_c),
                         status=summary.get("status", "?")))
        ax.plot(d, P, label=f"{label} (peak {peak:.4f})", lw=1.2)
        dmax = max(dmax, float(np.max(d)))
    ax.plot([0, args.delta_c, args.delta_c], [0, P_c, 0], "k--", lw=1.2,
            label=f"Griffith (peak {P_c:.4f})")
    ax.set_xlabel("imposed displacement of the top edge, delta")
    ax.set_ylabel("reaction on the top edge, P")
    ax.set_xlim(0, dmax)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=130)

    keys = list(rows[0].keys())
    print(" | ".join(keys))
    for r in rows:
        print(" | ".join(f"{r[k]:.4g}" if isinstance(r[k], float) else str(r[k]) for k in keys))
    if args.table:
        with open(args.table, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            w.writerows(rows)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
