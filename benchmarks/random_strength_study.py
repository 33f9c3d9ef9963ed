#!/usr/bin/python3
"""Scatter of a notched beam's peak load and crack path under a random tensile strength.

    /usr/bin/python3 benchmarks/random_strength_study.py build/lme-mpm [--seeds 10]
        [--cov 0.18] [--length 0.02] [--out output/random_strength]

Runs benchmarks/notched_beam_servo.prm (CMOD control) once with the homogeneous
strength and once per seed with 'Material 1/Fracture/Strength variability' lognormal
(coefficient of variation --cov, correlation length --length), and prints a Markdown
table: per run the peak load (device_peak_load), the work of fracture, and the crack's
path: the mean and the extreme x (at t = 0) of the fully damaged particles above the
notch tip, against the notch's centre line x = 0.23 m; then the mean and coefficient of
variation of the peak over the seeds.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
NOTCH_X, NOTCH_TIP_Y = 0.23, 0.07


def run(binary, out, sets):
    cmd = [binary, os.path.join(HERE, "notched_beam_servo.prm"), "--threads", "2",
           "--set", "Output/Directory=" + out, "--set", "Output/Verbosity=0"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    xs = []
    with open(os.path.join(out, "damage.csv"), newline="") as f:
        for r in csv.DictReader(f):
            if float(r["damage"]) >= 0.99 and float(r["x0_1"]) > NOTCH_TIP_Y:
                xs.append(float(r["x0_0"]))
    return dict(peak=s["device_peak_load"], wof=s.get("work_of_fracture", float("nan")),
                mean_x=sum(xs) / len(xs) if xs else float("nan"),
                spread=max(abs(x - NOTCH_X) for x in xs) if xs else float("nan"),
                n=len(xs))


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("binary")
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--cov", type=float, default=0.18)
    ap.add_argument("--length", type=float, default=0.02)
    ap.add_argument("--out", default="output/random_strength")
    args = ap.parse_args()
    section = "Material 1/Fracture/Strength variability/"
    rows = [("homogeneous", run(args.binary, os.path.join(args.out, "homogeneous"), []))]
    for seed in range(1, args.seeds + 1):
        sets = [section + "Distribution=lognormal",
                section + "Coefficient of variation=%g" % args.cov,
                section + "Correlation length=%g" % args.length, section + "Seed=%d" % seed]
        rows.append(("seed %d" % seed, run(args.binary, os.path.join(args.out, "seed%d" % seed),
                                           sets)))
        print("seed", seed, rows[-1][1], file=sys.stderr)
    print("| run | peak load (kN) | work of fracture (J) | crack mean x - 0.23 m (mm) "
          "| farthest damaged particle from x = 0.23 m (mm) | fully damaged particles |")
    print("|---|---|---|---|---|---|")
    for name, r in rows:
        print("| %s | %.3f | %.3f | %+.1f | %.1f | %d |" % (
            name, 1e-3 * r["peak"], r["wof"], 1e3 * (r["mean_x"] - NOTCH_X),
            1e3 * r["spread"], r["n"]))
    peaks = [r["peak"] for _, r in rows[1:]]
    mean = sum(peaks) / len(peaks)
    sd = math.sqrt(sum((p - mean) ** 2 for p in peaks) / (len(peaks) - 1)) if len(peaks) > 1 else 0
    print("\nOver %d seeds: mean peak %.3f kN (homogeneous %.3f kN), coefficient of "
          "variation %.3f." % (len(peaks), 1e-3 * mean, 1e-3 * rows[0][1]["peak"], sd / mean))


if __name__ == "__main__":
    main()
