#!/usr/bin/env python3
"""Runs a scene on 1 and on N MPI ranks and checks that they agree.

The split over ranks must not change the physics: the particles' final states
(summary.json's state_checksum, a sum of per-particle hashes of every field) are
equal bit for bit, every history.csv column agrees to 1e-10 of its largest magnitude
(of the largest component, for a vector's x, y, z columns; at least 1e-9 of the
history's largest value: reactions and contact forces are summed per rank, then over
the ranks, so a component that is round-off differs), and no particle is lost or copied by the migration
(the particle count and total mass at the end equal those at the start). Where no
particle is reordered on one rank (`particle_reorder_share` 0), none may be on N: the
ghosts are then refilled in their slots.

With --tolerance TOL (before the --set options) the runs are compared within TOL
instead: a solve to a tolerance (the consistent mass's conjugate gradients) sums
over the ranks in another order, so the states agree to the solver's tolerance and
not bit for bit. The checksums are then printed, not compared, and the iterations
per solve (mass_solve_iterations) may differ by a few in a hundred.

usage: compare_ranks.py LME_MPM PRM OUTDIR NRANKS [--tolerance TOL] [--set "A/B=v" ...]
"""
import csv
import json
import os
import shutil
import subprocess
import sys

TOLERANCE = 1e-10


def mpirun(exe, prm, out, ranks, extra, tail=3000):
    """Runs lme-mpm on @p ranks ranks, one thread each, writing to @p out; prints the
    command and the end of its output and returns the finished process."""
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), exe,
           prm, "--threads", "1", "--set", "Output/Directory=" + out] + extra
    env = dict(os.environ)
    # Containers often lack what Open MPI's single-copy transfer wants.
    env.setdefault("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
    env.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
    print(" ".join(cmd), flush=True)
    result = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, timeout=1200)
    print(result.stdout[-tail:])
    return result


def run(exe, prm, out, ranks, extra):
    shutil.rmtree(out, ignore_errors=True)
    result = mpirun(exe, prm, out, ranks, extra)
    if result.returncode != 0:
        sys.exit(f"FAIL: the run on {ranks} rank(s) exited with {result.returncode}")
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.reader(f))
    return summary, rows


def main():
    exe, prm, out, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    extra = sys.argv[5:]
    global TOLERANCE
    bitwise = True
    if extra[:1] == ["--tolerance"]:
        TOLERANCE, bitwise, extra = float(extra[1]), False, extra[2:]
    one, h1 = run(exe, prm, os.path.join(out, "np1"), 1, extra)
    many, hn = run(exe, prm, os.path.join(out, f"np{n}"), n, extra)
    failures = []
    values = one.get("values", one)
    values_n = many.get("values", many)
    if values_n.get("ranks") != n:
        failures.append(f"the second run reports {values_n.get('ranks')} ranks, not {n}")
    for s, v in (("1 rank", values), (f"{n} ranks", values_n)):
        if v["final_particles"] != v["particles"]:
            failures.append(f"{s}: {v['final_particles']} particles at the end, "
                            f"{v['particles']} at the start")
        if abs(v["final_mass"] - v["initial_mass"]) > 1e-14 * v["initial_mass"]:
            failures.append(f"{s}: mass {v['final_mass']!r} at the end, "
                            f"{v['initial_mass']!r} at the start")
    # Where no particle changes cell on one rank, none changes its owner or the halo
    # it lies in on several, so the ghosts keep their slots and no rank reorders.
    if values.get("particle_reorder_share") == 0 and \
            values_n.get("particle_reorder_share", 0) != 0:
        failures.append(f"no particle is reordered on 1 rank, but a share of "
                        f"{values_n['particle_reorder_share']} of the sorts reorders on "
                        f"{n}: the ghosts did not keep their slots")
    if bitwise and one["state_checksum"] != many["state_checksum"]:
        failures.append(f"particle states differ: checksum {one['state_checksum']} on 1 "
                        f"rank, {many['state_checksum']} on {n}")
    if h1[0] != hn[0] or len(h1) != len(hn):
        failures.append(f"history.csv: {len(h1)} rows on 1 rank, {len(hn)} on {n}, "
                        "or different columns")
    else:
        worst = (0.0, "")
        # A vector's components are measured against its largest component (the
        # sideways force of a symmetric impact is round-off of the vertical one), and a
        # vector that is zero but for round-off (1e-33 N) against 1e-9 of the
        # history's largest value.
        floor = 1e-9 * max(abs(float(x)) for r in h1[1:] for x in r)
        def family(name):
            return name[:-2] if name[-2:] in ("_x", "_y", "_z") else name
        largest = {}
        for c, name in enumerate(h1[0]):
            m = max(abs(float(r[c])) for r in h1[1:])
            largest[family(name)] = max(largest.get(family(name), 0.0), m)
        for c, name in enumerate(h1[0]):
            col1 = [float(r[c]) for r in h1[1:]]
            coln = [float(r[c]) for r in hn[1:]]
            scale = max(largest[family(name)], floor, 1e-300)
            diff = max(abs(a - b) for a, b in zip(col1, coln)) / scale
            allowed = TOLERANCE
            if not bitwise and name == "mass_solve_iterations":
                allowed = 0.05
            else:
                worst = max(worst, (diff, name))
            if diff > allowed:
                failures.append(f"history.csv column {name}: relative difference {diff:.3e}"
                                f" > {TOLERANCE}")
        print(f"history: {len(h1) - 1} rows, {len(h1[0])} columns; largest relative "
              f"difference {worst[0]:.3e} ({worst[1]})")
    print(f"checksums: {one['state_checksum']} (1 rank), {many['state_checksum']} ({n})")
    print(f"particles {values['particles']}, final on {n} ranks "
          f"{values_n['final_particles']}; mass {values_n['initial_mass']!r} -> "
          f"{values_n['final_mass']!r}")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
