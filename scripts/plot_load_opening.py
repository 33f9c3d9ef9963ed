#!/usr/bin/python3
"""Load against opening for any run with a force column and an opening gauge: the
softening curve of a notched beam, an SCB or a user's own specimen, with the peak and
the work of fracture read from it.

    /usr/bin/python3 scripts/plot_load_opening.py output/notched_beam_servo \\
        --out load_cmod.png

Each argument is an output directory (history.csv, summary.json). The opening is the
gauge column --opening (default: the run's only 'opening_<name>' column, from
'Output/Opening gauges'); the load is the column --force (default: of the
'force_<body>_mean_<axis>' columns, the one of largest magnitude, which is the loading
device's reaction in a load test), drawn as a positive number. --csv writes the curves
drawn (run, opening in m, load in N) for other tools.
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_plots import read_rows, read_summary  # noqa: E402


def choose_columns(rows, run, force=None, opening=None):
    """The (force, opening) column names to draw for the run whose history rows are
    @p rows; exits naming the run and the columns it has when a choice is impossible."""
    names = list(rows[0].keys())
    if opening is None:
        gauges = [n for n in names if n.startswith("opening_")]
        if len(gauges) != 1:
            sys.exit("%s: %s opening_<name> columns (%s): name one with --opening"
                     % (run, len(gauges), ", ".join(gauges) or "add 'Output/Opening gauges'"))
        opening = gauges[0]
    if force is None:
        forces = [n for n in names if n.startswith("force_") and "_mean_" in n]
        if not forces:
            sys.exit("%s: no force_<body>_mean_<axis> column: name one with --force" % run)
        force = max(forces, key=lambda n: max(abs(float(r[n])) for r in rows))
    for n in (force, opening):
        if n not in names:
            sys.exit("%s: no column '%s'" % (run, n))
    return force, opening


def curve(run, force=None, opening=None):
    """(opening in m, load in N, force column, opening column) of one run; the load's
    sign is turned so that its peak is positive."""
    rows = read_rows(os.path.join(run, "history.csv"), "lme-mpm")
    force, opening = choose_columns(rows, run, force, opening)
    w = [float(r[opening]) for r in rows]
    p = [float(r[force]) for r in rows]
    sign = 1.0 if max(p) >= -min(p) else -1.0
    return w, [sign * x for x in p], force, opening


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="output directories")
    ap.add_argument("--force", help="history column of the load (N)")
    ap.add_argument("--opening", help="history column of the opening (m)")
    ap.add_argument("--out", default="load_opening.png")
    ap.add_argument("--csv", help="also write the curves to this CSV file")
    args = ap.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    table = []
    for run in args.runs:
        w, p, force, opening = curve(run, args.force, args.opening)
        i = max(range(len(p)), key=lambda k: p[k])
        label = os.path.basename(os.path.normpath(run))
        s = read_summary(run)
        print("%s: peak %.6g N (%s) at %s = %.6g m; "
              "work_of_fracture %s J" % (label, p[i], force, opening, w[i],
                                        s.get("work_of_fracture", "not reported")))
        ax.plot([1e3 * x for x in w], p, label="%s (peak %.4g N)" % (label, p[i]))
        table += [(label, x, y) for x, y in zip(w, p)]
    ax.set_xlabel("opening (mm)")
    ax.set_ylabel("load (N)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=130)
    print("wrote", args.out)
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(["run", "opening", "load"])
            out.writerows(table)


if __name__ == "__main__":
    main()
