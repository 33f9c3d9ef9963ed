#!/usr/bin/env python3
"""Bad input on several MPI ranks: one message (rank 0's), a clean exit with code 1 on
every rank (no MPI_Abort), and nothing written.

    bad_input_ranks.py LME_MPM PRM OUT_DIR RANKS
"""
import os
import shutil
import subprocess
import sys


def main():
    exe, prm, out, ranks = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
    shutil.rmtree(out, ignore_errors=True)
    cases = [
        # An entry out of range, a misspelled entry, an expression with an unknown name.
        (["Time/CFL=7"], "Time/CFL"),
        (["Time/End tme=1"], "Time/End tme"),
        (["Body 1/Initial velocity/Function expression=q*x; 0"], "Body 1/Initial velocity"),
        # Two mass treatments at once (the file asks for corrections).
        (["Time/Mass matrix=consistent"], "Time/Mass matrix"),
    ]
    failures = []
    for sets, entry in cases:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", ranks, exe, prm,
               "--threads", "1", "--set", "Output/Directory=" + out]
        for s in sets:
            cmd += ["--set", s]
        env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1")
        r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=120)
        text = r.stdout + r.stderr
        errors = [l for l in text.splitlines() if l.startswith("lme-mpm: error")]
        print(f"{sets}: exit {r.returncode}, {len(errors)} message(s): {errors}")
        if r.returncode != 1:
            failures.append(f"{sets}: exit code {r.returncode}, expected 1")
        if len(errors) != 1 or entry not in errors[0]:
            failures.append(f"{sets}: expected one message naming '{entry}':\n{text}")
        if "MPI_ABORT" in text or "MPI_Abort" in text:
            failures.append(f"{sets}: the ranks were aborted:\n{text}")
        if os.path.exists(out):
            failures.append(f"{sets}: wrote {out}")
    if failures:
        print("\n".join(failures))
        sys.exit(1)


if __name__ == "__main__":
    main()
