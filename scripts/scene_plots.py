"""Helpers shared by the scene plot scripts: reading an output directory's CSV files
and the command line of a script that draws one panel column per run."""
import argparse
import csv
import os
import sys


def read_rows(path, scene):
    """The rows of CSV file @p path as dictionaries; exits naming @p scene if the file
    is missing or empty."""
    if not os.path.exists(path):
        sys.exit("%s: missing (is it a %s run?)" % (path, scene))
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("%s: no rows" % path)
    return rows


def parse_runs(doc, default_out):
    """Parses 'runs... [--labels a,b] [--out file.png]'; returns (args, labels)."""
    ap = argparse.ArgumentParser(description=doc,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="output directories")
    ap.add_argument("--labels", help="comma-separated titles, one per run")
    ap.add_argument("--out", default=default_out)
    args = ap.parse_args()
    labels = args.labels.split(",") if args.labels else [os.path.basename(
        os.path.normpath(r)) for r in args.runs]
    if len(labels) != len(args.runs):
        sys.exit("--labels needs one title per run")
    return args, labels
