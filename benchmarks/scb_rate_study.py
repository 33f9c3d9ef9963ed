#!/usr/bin/env python3
"""Loading-rate and time-step convergence study of the semicircular bending scene.

The SCB specimen is loaded quasi-statically: the roller's travel to the peak takes far
more than the specimen's wave transit. Explicit steps cost the same at any rate, so a
faster loading roller gives the same quasi-static answer in fewer steps, until inertia
enters. This script runs prm/semicircular_bending.prm at each loading velocity of
--rates (m/s) and notch angle of --angles, and prints per angle, against the slowest
rate: the peak load, the fracture energy ratio, the roller travel at the peak, the
post-peak curve's difference (the largest |F(u) - F_slowest(u)| over the common travel
after the slowest run's peak, relative to its peak), the roller's travel from the peak
until the load first falls below half of it (the collapse), the ratio of kinetic to
strain energy at the peak, steps and wall time. Every run writes its history rows (where the
peak is read and the stop is checked) at the same roller travel, 0.4 um.

With --cfls it also runs each rate at those CFL numbers (Time/CFL, the step's fraction of
the wave's cell transit): the step the file takes, 0.3, is far below the explicit limit,
and the study shows how much larger a step keeps the answer. The reference is the
slowest rate at the smallest CFL number.

    /usr/bin/python3 benchmarks/scb_rate_study.py --build build [--threads 2]
        [--rates 0.002 0.005 0.01 0.02] [--cfls 0.3 0.6 0.9] [--angles 0 30 60]
        [--out output/scb_rates]

--reuse reads runs already in --out. Each run writes only history.csv and summary.json.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time


def interval(rate):
    """History rows at equal roller travel (0.4 um, the shipped 2e-4 s at 2 mm/s): the
    peak and the stop are read on these rows, so coarser rows at a faster rate would
    miss the peak and stop later in the collapse."""
    return 4e-7 / rate


def run(build, out, angle, rate, cfl, threads, reuse):
    directory = os.path.join(out, f"a{angle}_v{rate:g}" + ("" if cfl == 0.3 else
                                                           f"_cfl{cfl:g}"))
    if not (reuse and os.path.exists(os.path.join(directory, "summary.json"))):
        start = time.time()
        subprocess.run([os.path.join(build, "lme-mpm"), "prm/semicircular_bending.prm",
                        "--threads", str(threads),
                        "--set", f"Scene/semicircular bending/Notch angle={angle}",
                        "--set", f"Scene/semicircular bending/Loading velocity={rate}",
                        "--set", f"Time/CFL={cfl:g}",
                        "--set", f"Output/Directory={directory}",
                        "--set", f"Output/Output interval={interval(rate):.6g}",
                        "--set", "Output/Verbosity=0",
                        "--set", "Output/Write particle files=false"],
                       check=True, stdout=subprocess.DEVNULL)
        print(f"angle {angle}, {rate * 1e3:g} mm/s, CFL {cfl:g}: "
              f"{time.time() - start:.0f} s",
              file=sys.stderr)
    with open(os.path.join(directory, "summary.json")) as f:
        summary = json.load(f)
    summary = summary.get("results", summary)
    with open(os.path.join(directory, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    u = [-float(r["displacement_load_y"]) for r in rows]
    F = [float(r["force_load_y"]) for r in rows]
    kin = [float(r["kinetic_energy"]) for r in rows]
    strain = [float(r["strain_energy"]) for r in rows]
    return summary, u, F, kin, strain


def interpolate(u, F, x):
    """F at travel x on a curve whose travel grows monotonically (linear)."""
    lo, hi = 0, len(u) - 1
    if x <= u[0]:
        return F[0]
    if x >= u[-1]:
        return F[-1]
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if u[mid] <= x:
            lo = mid
        else:
            hi = mid
    w = (x - u[lo]) / (u[hi] - u[lo]) if u[hi] > u[lo] else 0.0
    return F[lo] + w * (F[hi] - F[lo])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="output/scb_rates")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--rates", type=float, nargs="+",
                        default=[0.002, 0.005, 0.01, 0.02])
    parser.add_argument("--cfls", type=float, nargs="+", default=[0.3])
    parser.add_argument("--angles", type=int, nargs="+", default=[0, 30, 60])
    parser.add_argument("--reuse", action="store_true")
    args = parser.parse_args()
    os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    build = os.path.abspath(args.build)
    variants = [(rate, cfl) for rate in sorted(args.rates) for cfl in sorted(args.cfls)]
    print("| angle | rate (mm/s) | CFL | peak (N) | vs reference | energy ratio | "
          "vs reference | travel at peak (mm) | post-peak max diff / peak | "
          "peak to half peak (um) | kinetic / strain at peak | steps | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for angle in args.angles:
        results = [((rate, cfl), run(build, args.out, angle, rate, cfl, args.threads,
                                     args.reuse))
                   for rate, cfl in variants]
        s0, u0, F0, _, _ = results[0][1]
        peak0 = max(F0)
        i0 = F0.index(peak0)
        for (rate, cfl), (s, u, F, kin, strain) in results:
            peak = max(F)
            i = F.index(peak)
            # Post-peak: the common travel after the slowest run's peak.
            u_end = min(u0[-1], u[-1])
            diff = 0.0
            for k in range(i0, len(u0)):
                if u0[k] > u_end:
                    break
                diff = max(diff, abs(interpolate(u, F, u0[k]) - F0[k]))
            ratio = s.get("fracture_energy_ratio", float("nan"))
            ratio0 = s0.get("fracture_energy_ratio", float("nan"))
            ke = kin[i] / strain[i] if strain[i] > 0 else float("nan")
            half = next((u[k] for k in range(i, len(u)) if F[k] < 0.5 * peak), u[-1])
            print(f"| {angle} | {rate * 1e3:g} | {cfl:g} | {peak:.1f} | {100 * (peak / peak0 - 1):+.2f} % "
                  f"| {ratio:.3f} | {100 * (ratio / ratio0 - 1):+.2f} % | {1e3 * u[i]:.4f} "
                  f"| {diff / peak0:.3f} | {1e6 * (half - u[i]):.1f} | {ke:.2e} | {int(s['steps'])} "
                  f"| {s['wall_seconds']:.0f} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
