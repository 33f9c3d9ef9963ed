#!/usr/bin/python3
"""Stability sweeps: the largest stable CFL number per shape function (two-disc
collision and vibrating bar), and the effect of Newmark gamma, LME gamma and particles
per cell on energy drift and error. Writes stability.csv and prints a summary.

    /usr/bin/python3 benchmarks/stability_study.py --build build --out output/stability
    /usr/bin/python3 benchmarks/stability_study.py --studies amplitude   # one study
    /usr/bin/python3 benchmarks/stability_study.py --studies speed --threads 2

The speed study (doc/stability.md, "Particle speed") runs the vibrating bar on 160
cells for three periods at a peak particle speed v0/c = 0.1 with the CFL number, the
particle travel limit and the particle update varied, and at v0/c from 1e-3 to 0.03
with CFL 0.3, and writes stability_speed.csv and, with --plot,
doc/figures/stability_speed.png (about 16 minutes on two threads).

    /usr/bin/python3 benchmarks/stability_study.py --studies mass_speed --threads 2

The mass-speed study runs the same bar at v0/c = 0.1 with the lumped mass, two
corrections and the consistent mass (doc/stability.md), linear functions at CFL 0.3
with and without the travel limit and cubic B-splines at CFL 0.1 (0.01 cells per step,
the limit's own value), and writes stability_mass_speed.csv (about 10 minutes on two
threads).

A run counts as stable when it completes (no guard fired) with total energy within
10 % of its initial value.
"""
import argparse
import csv
import json
import os
import subprocess


def run(binary, scene, out, settings, threads=1):
    cmd = [binary, scene, "--threads", str(threads), "--set", "Output/Directory=" + out,
           "--set", "Output/Write particle files=false", "--set", "Output/Verbosity=0",
           "--set", "Time/Maximum CFL=2", "--set", "Time/Particle travel per step=0"]
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
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--plot", action="store_true", help="draw the speed study's figure")
    a = p.parse_args()
    if "speed" in a.studies:
        speed_study(a)
        return
    if "mass_speed" in a.studies:
        cases = []
        for mass in MASS:
            cases += [("linear", 0.1, 0.3, "flip", travel, mass) for travel in [0, 0.01]]
            cases.append(("bspline", 0.1, 0.1, "flip", 0, mass))
        speed_study(a, cases, "stability_mass_speed.csv")
        return
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


def energy_extremes(out):
    """Largest and last total energy over the initial one, from history.csv."""
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    e = [float(r["total_energy"]) for r in rows]
    return max(e) / e[0], e[-1] / e[0]


MASS = {"K=2 (file)": [], "lumped": ["Time/Mass matrix corrections=0"],
        "consistent": ["Time/Mass matrix corrections=0", "Time/Mass matrix=consistent"]}


def speed_study(a, cases=None, name="stability_speed.csv"):
    """Energy of the vibrating bar against particle speed, CFL, travel limit, update and
    mass treatment (cases: shape, v0/c, CFL, update, travel limit, mass)."""
    binary = os.path.join(a.build, "lme-mpm")
    os.makedirs(a.out, exist_ok=True)
    c, beta = 316.22776601683796, "1.5707963267948966"
    three_periods = 3 * 0.012649110640673518
    # At v0/c = 0.1 every shape function with FLIP at three CFL numbers (no travel
    # limit), XPIC(2) at CFL 0.3, and the travel limit 0.01 at CFL 0.3; below 0.1 the
    # speed axis at CFL 0.3 with FLIP.
    if cases is None:
        cases = []
        for shape in ["linear", "ugimp", "bspline", "lme"]:
            cfls = [0.3, 0.1] if shape == "lme" else [0.3, 0.1, 0.03]
            cases += [(shape, 0.1, cfl, "flip", 0, "K=2 (file)") for cfl in cfls]
            cases += [(shape, 0.1, 0.3, "xpic", 0, "K=2 (file)"),
                      (shape, 0.1, 0.3, "flip", 0.01, "K=2 (file)")]
        for shape in ["linear", "bspline"]:
            cases += [(shape, vc, 0.3, "flip", 0, "K=2 (file)") for vc in [1e-3, 1e-2, 3e-2]]
    rows = []
    for shape, vc, cfl, update, travel, mass in cases:
        out = os.path.join(a.out, "run")
        if os.path.exists(os.path.join(out, "summary.json")):
            os.remove(os.path.join(out, "summary.json"))
        settings = ["Shape functions/Type=" + shape, "Grid/Cell size=0.00625",
                    "Time/End time=%.17g" % three_periods, "Time/CFL=%g" % cfl,
                    "Time/Particle update=" + update,
                    "Time/Particle travel per step=%g" % travel,
                    "Verification/Compare with exact solution=false",
                    "Body 1/Initial velocity/Function constants=v0=%.12g, beta=%s" % (vc * c, beta)]
        s = run(binary, "prm/vibrating_bar.prm", out, settings + MASS[mass], a.threads)
        row = {"shape": shape, "v_over_c": vc, "cfl": cfl, "update": update, "mass": mass,
               "travel_limit": travel, "status": s.get("status"),
               "steps": s.get("steps", ""),
               "largest_travel_per_step": min(cfl * vc, travel) if travel > 0 else cfl * vc,
               "max_energy_drift": s.get("max_energy_drift", ""),
               "wall_seconds": s.get("wall_seconds", "")}
        try:
            row["max_total_over_initial"], row["final_total_over_initial"] = energy_extremes(out)
        except (OSError, KeyError, ValueError, ZeroDivisionError):
            row["max_total_over_initial"] = row["final_total_over_initial"] = ""
        rows.append(row)
        print(row, flush=True)
    with open(os.path.join(a.out, name), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    if a.plot and name == "stability_speed.csv":
        plot_speed(rows, "doc/figures/stability_speed.png")


def plot_speed(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for shape, colour in [("linear", "C0"), ("ugimp", "C3"), ("bspline", "C1"), ("lme", "C2")]:
        flip = sorted((r["largest_travel_per_step"], r["max_energy_drift"]) for r in rows
                      if r["shape"] == shape and r["update"] == "flip" and r["travel_limit"] == 0
                      and r["v_over_c"] == 0.1 and r["max_energy_drift"] != "")
        if flip:
            axes[0].loglog([x for x, _ in flip], [max(y, 1e-6) for _, y in flip], "o-",
                           color=colour, label=shape + " (FLIP)")
        for update, marker in [("xpic", "s"), ("flip", "^")]:
            pts = [r for r in rows if r["shape"] == shape and r["v_over_c"] == 0.1 and r["cfl"] == 0.3
                   and r["update"] == update and (update == "xpic" or r["travel_limit"] > 0)]
            for r in pts:
                axes[0].loglog([r["largest_travel_per_step"]], [max(r["max_energy_drift"], 1e-6)],
                               marker, color=colour, mfc="none", ms=9)
        speed = sorted((r["v_over_c"], r["max_energy_drift"]) for r in rows
                       if r["shape"] == shape and r["update"] == "flip" and r["travel_limit"] == 0
                       and r["cfl"] == 0.3 and r["max_energy_drift"] != "")
        if len(speed) > 1:
            axes[1].loglog([x for x, _ in speed], [max(y, 1e-6) for _, y in speed], "o-",
                           color=colour, label=shape)
    axes[0].axhline(0.01, color="grey", ls=":")
    axes[1].axhline(0.01, color="grey", ls=":")
    axes[0].set_xlabel("largest particle travel per step / h")
    axes[0].set_ylabel("largest energy drift")
    axes[0].set_title("v0/c = 0.1 (squares: XPIC(2), triangles: travel limit 0.01)")
    axes[1].set_xlabel("peak particle speed v0 / c")
    axes[1].set_ylabel("largest energy drift")
    axes[1].set_title("CFL 0.3, FLIP")
    for ax in axes:
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
