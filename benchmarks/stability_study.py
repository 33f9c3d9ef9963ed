#!/usr/bin/python3
"""Stability sweeps: the largest stable CFL number per shape function (two-disc
collision and vibrating bar), and the effect of Newmark gamma, LME gamma and particles
per cell on energy drift and error. Writes stability.csv and prints a summary.

    /usr/bin/python3 benchmarks/stability_study.py --build build --out output/stability
    /usr/bin/python3 benchmarks/stability_study.py --studies amplitude   # one study

A run counts as stable when it completes (no guard fired) with total energy within
10 % of its initial value.
"""
import argparse
import csv
import json
import os
import subprocess


def run(binary, scene, out, settings):
    cmd = [binary, scene, "--threads", "1", "--set", "Output/Directory=" + out,
           "--set", "Output/Write particle files=false", "--set", "Output/Verbosity=0",
           "--set", "Time/Maximum CFL=2"]
    for s in settings:
        cmd += ["--set", s]
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError):
        return {"status": "failed before output"}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default="build")
    p.add_argument("--out", default="output/stability")
    p.add_argument("--studies", nargs="+",
                   default=["cfl", "newmark_gamma", "lme_gamma", "particles_per_cell", "amplitude"])
    a = p.parse_args()
    binary = os.path.join(a.build, "lme-mpm")
    os.makedirs(a.out, exist_ok=True)
    rows = []

    def record(study, scene, settings, value):
        out = os.path.join(a.out, "run")
        if os.path.exists(os.path.join(out, "summary.json")):
            os.remove(os.path.join(out, "summary.json"))
        s = run(binary, scene, out, settings)
        stable = s.get("status") == "completed" and s.get("max_energy_drift", 1) < 0.1
        row = {"study": study, "scene": os.path.basename(scene), "settings": "; ".join(settings),
               "value": value, "status": s.get("status"), "stable": stable,
               "max_energy_drift": s.get("max_energy_drift", ""),
               "error_displacement_l2": s.get("max_error_displacement_l2", "")}
        rows.append(row)
        print(row, flush=True)
        return stable

    cfls = [0.2, 0.4, 0.6, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.5]
    for scene, corrections in ([] if "cfl" not in a.studies else [("prm/vibrating_bar.prm", ["0", "2"]),
                               ("prm/two_disk_collision.prm", ["0"])]):
        for k in corrections:
            for shape in ["linear", "ugimp", "bspline", "lme"]:
                for cfl in cfls:
                    st = record("cfl", scene, ["Shape functions/Type=" + shape, "Time/CFL=%g" % cfl,
                                               "Time/Mass matrix corrections=" + k], cfl)
                    if not st:
                        break
    for g in ["0.5", "0.6", "0.75", "1"] if "newmark_gamma" in a.studies else []:
        record("newmark_gamma", "prm/vibrating_bar.prm", ["Time/Newmark gamma=" + g], g)
    for g in ["0.8", "1.8", "3.5", "6.8", "10"] if "lme_gamma" in a.studies else []:
        record("lme_gamma", "prm/vibrating_bar.prm",
               ["Shape functions/Type=lme", "Shape functions/LME gamma=" + g], g)
    for n in ["1", "2", "3", "4"] if "particles_per_cell" in a.studies else []:
        for shape in ["linear", "lme"]:
            record("particles_per_cell", "prm/two_disk_collision.prm",
                   ["Shape functions/Type=" + shape, "Body 1/Particles per cell direction=" + n,
                    "Body 2/Particles per cell direction=" + n], n)
    # Amplitude, up to large deformation: the bar's strain amplitude is v0 / c
    # (c = omega / beta = 316.2 m/s). The error is against the small-strain exact
    # solution, which is also what the small-strain solver computes: it stays at the
    # discretisation error, and the runs show whether large motions stay stable
    # (particles crossing many cells, density changes of tens of per cent).
    c, omega, beta = 316.22776601683796, "496.72941328980507", "1.5707963267948966"
    for strain in ["3e-8", "1e-3", "1e-2", "0.05", "0.1", "0.2"] if "amplitude" in a.studies else []:
        consts = "v0=%.12g, beta=%s" % (float(strain) * c, beta)
        for shape in ["linear", "lme"]:
            record("amplitude", "prm/vibrating_bar.prm",
                   ["Shape functions/Type=" + shape,
                    "Body 1/Initial velocity/Function constants=" + consts,
                    "Verification/Exact displacement/Function constants=%s, omega=%s" % (consts, omega),
                    "Verification/Exact velocity/Function constants=%s, omega=%s" % (consts, omega),
                    "Verification/Exact stress/Function constants=%s, omega=%s, E=1e8" % (consts, omega)],
                   "%s (%s)" % (strain, shape))
    with open(os.path.join(a.out, "stability.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
