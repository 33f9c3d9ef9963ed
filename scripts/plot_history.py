#!/usr/bin/python3
"""Plots chosen columns of one or more history.csv files into a PNG.

    scripts/plot_history.py output/vibrating_bar/history.csv --y error_displacement_l2
    scripts/plot_history.py a/history.csv b/history.csv --x displacement_top_y \\
        --y force_top_y --reference griffith.csv --out force.png

Each --y column becomes a line per file; --reference adds the curves of a CSV whose first
column is x and whose other columns are y (one curve each). Columns are matched by name;
a missing one is an error that lists the available names.
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("%s: no rows" % path)
    return rows


def column(rows, name, path):
    if name not in rows[0]:
        sys.exit("%s has no column '%s'; it has: %s" % (path, name, ", ".join(rows[0])))
    return [float(r[name]) for r in rows]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("files", nargs="+", help="history.csv files")
    p.add_argument("--x", default="time", help="column for the horizontal axis")
    p.add_argument("--y", nargs="+", default=["total_energy"], help="columns to plot")
    p.add_argument("--labels", nargs="*", help="one label per file")
    p.add_argument("--reference", help="CSV with reference curves (x first)")
    p.add_argument("--logy", action="store_true")
    p.add_argument("--out", default="history.png")
    a = p.parse_args()

    fig, ax = plt.subplots(figsize=(7, 4.5))
    labels = a.labels or a.files
    for path, label in zip(a.files, labels):
        rows = read(path)
        x = column(rows, a.x, path)
        for y in a.y:
            ax.plot(x, column(rows, y, path), label=(label if len(a.y) == 1 else label + ": " + y))
    if a.reference:
        ref = read(a.reference)
        names = list(ref[0].keys())
        xr = column(ref, names[0], a.reference)
        for n in names[1:]:
            ax.plot(xr, column(ref, n, a.reference), "k--", label="reference: " + n)
    ax.set_xlabel(a.x)
    ax.set_ylabel(", ".join(a.y))
    if a.logy:
        ax.set_yscale("log")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out, dpi=90)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
