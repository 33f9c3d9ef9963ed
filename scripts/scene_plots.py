"""Helpers shared by the scene plot scripts: reading an output directory's CSV files
and the command line of a script that draws one panel column per run."""
import argparse
import csv
import json
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


def read_parameters(run):
    """The entries of the run's own parameters.prm (as the run wrote it) as a dictionary
    from 'Subsection/Entry' paths to their value strings; exits if the file is missing."""
    path = os.path.join(run, "parameters.prm")
    if not os.path.exists(path):
        sys.exit("%s: missing (is it an lme-mpm output directory?)" % path)
    values, sections = {}, []
    with open(path) as f:
        for line in f:
            text = line.split("#", 1)[0].strip()
            if text.startswith("subsection "):
                sections.append(text[len("subsection "):].strip())
            elif text == "end":
                sections.pop()
            elif text.startswith("set ") and "=" in text:
                name, value = text[4:].split("=", 1)
                values["/".join(sections + [name.strip()])] = value.strip()
    return values


def parameter(values, entry, run):
    """The value of @p entry in @p values (read_parameters()), as a float when it is
    one; exits naming the run if it is absent."""
    if entry not in values:
        sys.exit("%s/parameters.prm: no entry '%s'" % (run, entry))
    try:
        return float(values[entry])
    except ValueError:
        return values[entry]


def body_material(values, body_name, run):
    """The number of the 'Material N' that the body named @p body_name is made of."""
    n = int(parameter(values, "Problem/Number of bodies", run))
    for b in range(1, n + 1):
        if values.get("Body %d/Name" % b) == body_name:
            return int(parameter(values, "Body %d/Material" % b, run))
    sys.exit("%s/parameters.prm: no Body N named '%s'" % (run, body_name))


def read_summary(run):
    """summary.json of the run as a dictionary (empty if the run wrote none)."""
    path = os.path.join(run, "summary.json")
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return json.load(f)
