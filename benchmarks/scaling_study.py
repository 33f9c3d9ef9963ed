#!/usr/bin/python3
"""Cost against problem size: the throughput block (benchmarks/throughput.prm and
throughput_3d.prm, an elastic block with a smooth velocity field, four particles per
cell in 2D and eight in 3D) grown to 1e4, 1e5, 1e6 and 4e6 particles at the same cell
size, 2D and 3D, linear and LME functions, one and two threads. Writes scaling.csv
(one row per run) and prints a table of particle-steps per second (median of the
repeats) and memory per particle; --plot draws doc/figures/scaling.png.

    /usr/bin/python3 benchmarks/scaling_study.py --build build --out output/scaling
    /usr/bin/python3 benchmarks/scaling_study.py --sizes 1e4 1e5 --dims 2 --plot

Every size of a (dimension, family) runs the same number of steps, so the first step
(a cold LME solve, the first sort) weighs the same at every size. Memory per particle
is the increase of `peak_resident_megabytes` (summary.json) over a run of one cell's
particles on the same grid, divided by the particles; the grid's own memory is
reported per node (the few-particle run's increase over that on the smallest grid).
The 3D LME block of 4e6 particles needs about 17 GB. About 25 minutes with the
defaults.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess

# Steps per (dimension, family): enough for the first step to weigh little.
STEPS = {(2, "linear"): 40, (2, "lme"): 20, (3, "linear"): 20, (3, "lme"): 10}
DT = 8e-5  # the blocks' time step (CFL 0.29 at h = 0.01 m)


def block(dim, n):
    """The block's shape, grid corners and velocity for about n particles."""
    if dim == 2:
        s = (n / 1e5) ** 0.5
        lx, ly = round(250 * s) / 100, round(100 * s) / 100
        return (f"rectangle(0, 0, {lx}, {ly})", "-0.1, -0.1",
                f"{lx + 0.1:.2f}, {ly + 0.1:.2f}",
                f"0.01*sin(2*pi*x/{lx})*cos(pi*y/{ly}); 0.01*cos(2*pi*x/{lx})*sin(pi*y/{ly})")
    s = (n / 1e5) ** (1 / 3)
    lx, lz = round(25 * s) / 100, round(20 * s) / 100
    return (f"rectangle(0, 0, 0, {lx}, {lx}, {lz})", "-0.04, -0.04, -0.04",
            f"{lx + 0.04:.2f}, {lx + 0.04:.2f}, {lz + 0.04:.2f}",
            f"0.01*sin(2*pi*x/{lx}); 0.01*cos(2*pi*y/{lx}); 0.01*sin(pi*z/{lz})")


def run(a, dim, family, n, threads, shape=None):
    body, lower, upper, velocity = block(dim, n)
    scene = os.path.join(a.source, "benchmarks",
                         "throughput.prm" if dim == 2 else "throughput_3d.prm")
    out = os.path.join(a.out, f"d{dim}_{family}_{n:g}_t{threads}")
    cmd = [os.path.join(a.build, "lme-mpm"), scene, "--threads", str(threads),
           "--set", "Output/Directory=" + out, "--set", "Output/Verbosity=0",
           "--set", "Shape functions/Type=" + family,
           "--set", "Grid/Lower corner=" + lower, "--set", "Grid/Upper corner=" + upper,
           "--set", "Body 1/Shape=" + (shape or body),
           "--set", "Body 1/Initial velocity/Function expression=" + velocity,
           "--set", f"Time/End time={STEPS[(dim, family)] * DT:.6g}",
           "--set", f"Output/Output interval={STEPS[(dim, family)] * DT:.6g}"]
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
    except (OSError, json.JSONDecodeError):
        return None
    return s if s.get("status") == "completed" else None


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default="build")
    p.add_argument("--source", default=os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))))
    p.add_argument("--out", default="output/scaling")
    p.add_argument("--sizes", nargs="+", type=float, default=[1e4, 1e5, 1e6, 4e6])
    p.add_argument("--dims", nargs="+", type=int, default=[2, 3])
    p.add_argument("--families", nargs="+", default=["linear", "lme"])
    p.add_argument("--threads", nargs="+", type=int, default=[1, 2])
    p.add_argument("--repeats", type=int, default=3,
                   help="runs of each case (sizes up to 1e5; larger ones run once)")
    p.add_argument("--plot", action="store_true")
    p.add_argument("--from-csv", help="print the table (and --plot) of an earlier "
                   "scaling.csv instead of running")
    a = p.parse_args()
    if a.from_csv:
        with open(a.from_csv) as f:
            rows = [{k: (v if k in ("family", "size") else float(v)) for k, v in r.items()}
                    for r in csv.DictReader(f)]
        for r in rows:
            r["dim"], r["threads"] = int(r["dim"]), int(r["threads"])
        table(rows)
        if a.plot:
            plot(rows, os.path.join(a.source, "doc", "figures", "scaling.png"))
        return
    os.makedirs(a.out, exist_ok=True)

    rows = []
    for dim in a.dims:
        for family in a.families:
            # A run of one cell's particles on each grid: the memory the program and
            # the grid take whatever the particles.
            tiny = "rectangle(0, 0, 0.01, 0.01)" if dim == 2 else \
                "rectangle(0, 0, 0, 0.01, 0.01, 0.01)"
            smallest_mb = None
            for n in sorted(a.sizes):
                base = run(a, dim, family, int(n), 1, shape=tiny)
                base_mb = base["peak_resident_megabytes"] if base else float("nan")
                smallest_mb = base_mb if smallest_mb is None else smallest_mb
                grid_bytes_per_node = 1e6 * (base_mb - smallest_mb) / base["nodes"] \
                    if base else float("nan")
                repeats = a.repeats if n <= 1e5 else 1
                for r in range(repeats):  # repeats outermost over the thread counts
                    for threads in a.threads:
                        s = run(a, dim, family, int(n), threads)
                        if s is None:
                            print(f"d{dim} {family} {n:g} t{threads}: failed")
                            continue
                        rows.append({
                            "dim": dim, "family": family, "size": f"{n:g}",
                            "particles": s["particles"], "threads": threads,
                            "steps": s["steps"], "wall_seconds": s["wall_seconds"],
                            "particle_steps_per_second": s["particle_steps_per_second"],
                            "peak_resident_megabytes": s["peak_resident_megabytes"],
                            "baseline_megabytes": base_mb, "nodes": s["nodes"],
                            "grid_bytes_per_node": grid_bytes_per_node,
                            "bytes_per_particle": 1e6 * (s["peak_resident_megabytes"]
                                                         - base_mb) / s["particles"]})
                        print("d{dim} {family:6} {particles:>8} t{threads} steps {steps}:"
                              " {particle_steps_per_second:.3g} particle-steps/s,"
                              " {bytes_per_particle:.0f} B/particle".format(**rows[-1]),
                              flush=True)
    with open(os.path.join(a.out, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    table(rows)
    if a.plot:
        plot(rows, os.path.join(a.source, "doc", "figures", "scaling.png"))


def summarise(rows):
    """Median rate and memory per (dim, family, threads, size)."""
    groups = {}
    for r in rows:
        groups.setdefault((r["dim"], r["family"], r["threads"], float(r["size"])),
                          []).append(r)
    return {k: (statistics.median(x["particles"] for x in v),
                statistics.median(x["particle_steps_per_second"] for x in v),
                statistics.median(x["bytes_per_particle"] for x in v), len(v),
                v[0]["grid_bytes_per_node"])
            for k, v in sorted(groups.items())}


def table(rows):
    s = summarise(rows)
    print("\n| dim | family | threads | particles | runs | particle-steps/s | "
          "against 1e5 | memory per particle (B) | grid per node (B) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for (dim, family, threads, n), (particles, rate, mem, count, grid) in s.items():
        ref = s.get((dim, family, threads, 1e5))
        ratio = f"{rate / ref[1]:.2f}" if ref else "-"
        print(f"| {dim} | {family} | {threads} | {particles:.0f} | {count} | {rate:.3g} | "
              f"{ratio} | {mem:.0f} | {grid:.0f} |")


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = summarise(rows)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2))
    keys = sorted({k[:3] for k in s})
    colours = {}
    for dim, family, threads in keys:
        colour = colours.setdefault((dim, family), f"C{len(colours)}")
        pts = sorted((v[0], v[1], v[2]) for k, v in s.items() if k[:3] == (dim, family, threads))
        style = "-" if threads == 1 else "--"
        label = f"{dim}D {family}, {threads} thread{'s' if threads > 1 else ''}"
        ax.plot([q[0] for q in pts], [q[1] for q in pts], style, color=colour, marker="o",
                label=label)
        if threads == 1:
            bx.plot([q[0] for q in pts], [q[2] for q in pts], color=colour, marker="o",
                    label=f"{dim}D {family}")
    for x, ylabel in ((ax, "particle-steps per second"), (bx, "memory per particle (B)")):
        x.set_xscale("log")
        x.set_xlabel("particles")
        x.set_ylabel(ylabel)
        x.grid(True, which="both", alpha=0.3)
    ax.set_yscale("log")
    bx.set_yscale("log")
    ax.set_title("throughput block, 20-40 steps (solid: 1 thread, dashed: 2)", fontsize=9)
    bx.set_title("peak resident set over a few-particle run, per particle", fontsize=9)
    ax.legend(fontsize=7, ncol=2, loc="lower left")
    ax.set_ylim(bottom=4e4)
    bx.legend(fontsize=7, loc="center right")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print("wrote", path)


if __name__ == "__main__":
    main()
