#!/usr/bin/python3
"""The mass matrix against error and run time: the vibrating bar for every shape
function with the lumped mass, K = 1, 2, 4 Jacobi corrections and the consistent mass
(`Time/Mass matrix = consistent`), over grid levels at one CFL number, and the largest
stable CFL number of each treatment. Writes errors.csv and stability.csv into --out and
prints the tables as Markdown.

    /usr/bin/python3 benchmarks/mass_matrix_study.py --build build --out output/mass_matrix

A run that stops (unstable, or a solve that does not converge) is a row with its
status; the study goes on.
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess

SHAPES = [("linear", []), ("ugimp", ["Body 1/Particle placement=uniform"]),
          ("bspline", []), ("lme", ["Shape functions/LME gamma=1.8"])]
TREATMENTS = [("lumped", ["Time/Mass matrix corrections=0"]),
              ("K=1", ["Time/Mass matrix corrections=1"]),
              ("K=2", ["Time/Mass matrix corrections=2"]),
              ("K=4", ["Time/Mass matrix corrections=4"]),
              ("consistent", ["Time/Mass matrix corrections=0",
                              "Time/Mass matrix=consistent",
                              "Time/Consistent mass iterations=3000"])]


def run(binary, out, settings):
    shutil.rmtree(out, ignore_errors=True)
    cmd = [binary, "prm/vibrating_bar.prm", "--threads", "1",
           "--set", "Output/Directory=" + out,
           "--set", "Output/Write particle files=false", "--set", "Output/Verbosity=0"]
    for s in settings:
        cmd += ["--set", s]
    rc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
    try:
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
    except OSError:
        s = {}
    r = s.get("results", s)
    r["status"] = s.get("status", "completed" if rc == 0 else "stopped")
    r["rc"] = rc
    return r


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="output/mass_matrix")
    parser.add_argument("--cfl", default="0.1")
    parser.add_argument("--levels", default="0.05,0.025,0.0125,0.00625")
    parser.add_argument("--stability-cfl", default="0.05,0.1,0.2,0.3,0.5,0.8,1.2")
    parser.add_argument("--ppc", default="2", help="particles per cell direction")
    args = parser.parse_args()
    binary = os.path.join(args.build, "lme-mpm")
    os.makedirs(args.out, exist_ok=True)
    scratch = os.path.join(args.out, "run")
    rows = []
    for shape, extra in SHAPES:
        for name, settings in TREATMENTS:
            previous = None
            for h in args.levels.split(","):
                r = run(binary, scratch, ["Shape functions/Type=" + shape, "Grid/Cell size=" + h,
                                          "Time/CFL=" + args.cfl,
                                          "Body 1/Particles per cell direction=" + args.ppc]
                        + extra + settings)
                ok = r["rc"] == 0
                e = r.get("max_error_displacement_l2", math.nan) if ok else math.nan
                s = r.get("max_error_stress_l2", math.nan) if ok else math.nan
                row = {"shape_function": shape, "mass": name, "h": h, "rc": r["rc"],
                       "steps": r.get("steps", 0), "wall_seconds": r.get("wall_seconds", math.nan),
                       "error_displacement_l2": e, "error_stress_l2": s,
                       "order_displacement": "", "order_stress": "",
                       "mean_iterations": r.get("mass_solve_mean_iterations", ""),
                       "max_energy_drift": r.get("max_energy_drift", math.nan)}
                if previous and ok and previous["rc"] == 0:
                    row["order_displacement"] = "%.2f" % math.log2(previous["error_displacement_l2"] / e)
                    row["order_stress"] = "%.2f" % math.log2(previous["error_stress_l2"] / s)
                rows.append(row)
                previous = row
                print(row, flush=True)
    with open(os.path.join(args.out, "errors.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print("\n| shape functions | mass | h (m) | steps | wall (s) | error_displacement_l2 | order "
          "| error_stress_l2 | order | mean iterations |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r["rc"] != 0:
            print("| %s | %s | %s | stopped at step %s | | | | | | %s |" % (
                r["shape_function"], r["mass"], r["h"], r["steps"], r["mean_iterations"]))
            continue
        it = "%.1f" % r["mean_iterations"] if r["mean_iterations"] != "" else ""
        print("| %s | %s | %s | %d | %.2f | %.3e | %s | %.3e | %s | %s |" % (
            r["shape_function"], r["mass"], r["h"], r["steps"], r["wall_seconds"],
            r["error_displacement_l2"], r["order_displacement"], r["error_stress_l2"],
            r["order_stress"], it))

    stable = []
    for shape, extra in SHAPES:
        for name, settings in TREATMENTS:
            best, first_bad = None, None
            for cfl in args.stability_cfl.split(","):
                r = run(binary, scratch, ["Shape functions/Type=" + shape, "Time/CFL=" + cfl,
                                          "Time/Maximum CFL=2",
                                          "Body 1/Particles per cell direction=" + args.ppc]
                        + extra + settings)
                if r["rc"] == 0 and r.get("max_energy_drift", 1) < 0.01:
                    best = cfl
                else:
                    first_bad = cfl
                    break
            stable.append({"shape_function": shape, "mass": name,
                           "largest_stable_cfl": best or "none", "first_unstable_cfl": first_bad or ""})
            print(stable[-1], flush=True)
    with open(os.path.join(args.out, "stability.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(stable[0].keys()))
        w.writeheader()
        w.writerows(stable)
    print("\n| shape functions | mass | largest stable CFL (of %s) | first unstable |" %
          args.stability_cfl.replace(",", ", "))
    print("|---|---|---|---|")
    for r in stable:
        print("| %s | %s | %s | %s |" % (r["shape_function"], r["mass"],
                                         r["largest_stable_cfl"], r["first_unstable_cfl"]))
    shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
