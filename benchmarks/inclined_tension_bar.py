#!/usr/bin/env python3
"""The inclined tension bar (prm/inclined_tension_bar.prm) at several angles, shape
function families and resolutions: the crack band's energy per unit crack area
(fracture_energy_ratio, 1 when the crack dissipates G_F) and the peak stress against
the weak zone's f_t, as a table (doc/validation.md, "Inclined tension bar"). With
--dim 3 the bar of prm/inclined_tension_bar_3d.prm, each angle an "angle,out-of-plane
angle" pair (doc/validation.md, "Inclined tension bar in 3D").

    benchmarks/inclined_tension_bar.py --build build --out output/inclined_bar \
        [--angles 0 30 45] [--cells 0.0025 0.00125] [--families linear lme ...]
    benchmarks/inclined_tension_bar.py --dim 3 --angles 0,0 30,0 30,35 \
        --cells 0.0025 0.002 --families linear bspline lme1.8 --threads 1 --jobs 2

--jobs N runs N cases at once (each on --threads threads); the table keeps its order.
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys

FAMILIES = {
    "linear": ["Shape functions/Type=linear"],
    "ugimp": ["Shape functions/Type=ugimp"],
    "bspline": ["Shape functions/Type=bspline"],
    "lme1.8": ["Shape functions/Type=lme", "Shape functions/LME gamma=1.8"],
    "lme3.5": ["Shape functions/Type=lme", "Shape functions/LME gamma=3.5"],
}
F_T = 2.7e6  # the weak zone's tensile strength in prm/inclined_tension_bar.prm


def run(build, out, family, angle, h, extra, threads, dim):
    turn, _, tilt = angle.partition(",")
    d = os.path.join(out, f"{dim}d_{family}_a{turn}_{tilt or 0}_h{h}")
    sets = FAMILIES[family] + [f"Scene/inclined tension bar/Angle={turn}",
                               f"Grid/Cell size={h}", f"Output/Directory={d}",
                               "Output/Verbosity=0"] + extra
    if tilt:
        sets.append(f"Scene/inclined tension bar/Out-of-plane angle={tilt}")
    prm = "prm/inclined_tension_bar.prm" if dim == 2 else "prm/inclined_tension_bar_3d.prm"
    cmd = [os.path.join(build, "lme-mpm"), prm, "--threads", str(threads)]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        return json.load(open(os.path.join(d, "summary.json")))
    except OSError:
        return {"status": "no summary"}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default="build")
    p.add_argument("--out", default="output/inclined_bar")
    p.add_argument("--angles", nargs="+", default=["0", "30", "45"])
    p.add_argument("--cells", nargs="+", default=["0.0025", "0.00125"])
    p.add_argument("--families", nargs="+", default=list(FAMILIES))
    p.add_argument("--set", action="append", default=[], help="extra --set entries")
    p.add_argument("--threads", default="2")
    p.add_argument("--dim", type=int, choices=(2, 3), default=2)
    p.add_argument("--jobs", type=int, default=1, help="cases run at once")
    a = p.parse_args()
    os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    print("| family | angle | h (mm) | peak / f_t | energy ratio | snapped | failed | drift | "
          "particles | steps | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    worst = 0
    cases = [(family, angle, h) for family in a.families for h in a.cells
             for angle in a.angles]
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        summaries = pool.map(
            lambda c: run(a.build, a.out, c[0], c[1], c[2], a.set, a.threads, a.dim), cases)
        for (family, angle, h), s in zip(cases, summaries):
            ratio = s.get("fracture_energy_ratio", float("nan"))
            peak = s.get("peak_stress", float("nan")) / F_T
            worst = max(worst, abs(ratio - 1), abs(peak - 1))
            print(f"| {family} | {angle} | {float(h) * 1e3:g} | {peak:.3f} | "
                  f"{ratio:.3f} | {int(s.get('eigensoftening_snap_back_particles', 0))} | "
                  f"{int(s.get('failed_particles', 0))} | "
                  f"{s.get('max_energy_drift', float('nan')):.2g} | "
                  f"{int(s.get('particles', 0))} | {int(s.get('steps', 0))} | "
                  f"{s.get('wall_seconds', float('nan')):.0f} |", flush=True)
    print(f"largest deviation from 1: {worst:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
