#!/usr/bin/env python3
"""A step that fails alike on every rank (a consistent-mass solve that does not converge)
on two MPI ranks: exit code 1 on every rank, one message naming the step, and the
output written so far kept, with summary.json's status 'aborted'.

    failed_solve_ranks.py LME_MPM PRM OUT_DIR
"""
import json
import os
import shutil
import subprocess
import sys


def main():
    exe, prm, out = sys.argv[1], sys.argv[2], sys.argv[3]
    shutil.rmtree(out, ignore_errors=True)
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", exe, prm,
           "--threads", "1", "--set", "Output/Directory=" + out,
           "--set", "Shape functions/Type=bspline", "--set", "Time/Mass matrix corrections=0",
           "--set", "Time/Mass matrix=consistent",
           "--set", "Time/Consistent mass iterations=2"]
    env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1")
    env.setdefault("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=300)
    text = r.stdout + r.stderr
    errors = [l for l in text.splitlines() if l.startswith("lme-mpm: error")]
    print(f"exit {r.returncode}; {errors}")
    failures = []
    if r.returncode != 1:
        failures.append(f"exit code {r.returncode}, expected 1")
    if len(errors) != 1 or "Run stopped at step" not in errors[0] \
            or "'Time/Consistent mass iterations' = 2" not in errors[0]:
        failures.append("expected one message naming the step and the entry:\n" + text)
    if "MPI_ABORT" in text or "MPI_Abort" in text:
        failures.append("the ranks were aborted:\n" + text)
    try:
        with open(os.path.join(out, "summary.json")) as f:
            status = json.load(f).get("status")
        if status != "aborted":
            failures.append(f"summary.json status {status!r}, expected 'aborted'")
    except (OSError, json.JSONDecodeError) as e:
        failures.append(f"no summary.json kept: {e}")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
