#!/usr/bin/env python3
"""A distributed run resumed from its checkpoints ends where it would have.

Runs a scene on N MPI ranks to its end, writing checkpoints every K steps (one file
per rank), then resumes it from the last checkpoint on N ranks and checks that the
resumed run ends in the same particle states (summary.json's state_checksum, bit for
bit) and rewrites history.csv byte for byte. Resuming on another number of ranks
must stop with a message that names the rank count to use.

usage: resume_ranks.py LME_MPM PRM OUTDIR NRANKS STEPS [--set "A/B=v" ...]
"""
import json
import os
import shutil
import sys

from compare_ranks import mpirun


def run(exe, prm, out, ranks, extra, resume=False):
    return mpirun(exe, prm, out, ranks, extra + (["--resume", out] if resume else []),
                  tail=2000)


def outcome(out):
    with open(os.path.join(out, "summary.json")) as f:
        checksum = json.load(f)["state_checksum"]
    with open(os.path.join(out, "history.csv")) as f:
        return checksum, f.read()


def main():
    exe, prm, out, n, steps = (sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]),
                               int(sys.argv[5]))
    extra = sys.argv[6:] + ["--set", f"Checkpoint/Every steps={steps}"]
    shutil.rmtree(out, ignore_errors=True)
    failures = []
    if run(exe, prm, out, n, extra).returncode != 0:
        sys.exit(f"FAIL: the run on {n} ranks failed")
    files = sorted(f for f in os.listdir(out) if f.startswith("checkpoint."))
    expected = [f"checkpoint.{r}.bin" for r in range(n)]
    if not all(f in files for f in expected):
        failures.append(f"checkpoint files {files}, expected {expected}")
    first = outcome(out)
    behind_dir = out + "_behind"
    shutil.rmtree(behind_dir, ignore_errors=True)
    shutil.copytree(out, behind_dir)

    resumed = run(exe, prm, out, n, extra, resume=True)
    if resumed.returncode != 0:
        failures.append(f"the resumed run exited with {resumed.returncode}")
    else:
        second = outcome(out)
        if second[0] != first[0]:
            failures.append(f"state checksum {second[0]} after resuming, {first[0]} "
                            "without")
        if second[1] != first[1]:
            failures.append("history.csv differs after resuming")

    # A last checkpoint that rank 1 could not complete (a full disk) leaves its
    # previous one in place: every rank goes back to the step they all hold.
    last = os.path.join(behind_dir, "checkpoint.1.bin")
    if os.path.exists(last + ".prev"):
        shutil.copyfile(last + ".prev", last)
        behind = run(exe, prm, behind_dir, n, extra, resume=True)
        if behind.returncode != 0:
            failures.append(f"resuming with rank 1 a checkpoint behind exited with "
                            f"{behind.returncode}")
        elif outcome(behind_dir) != first:
            failures.append("resuming with rank 1 a checkpoint behind changed the run")
    else:
        failures.append("no checkpoint.1.bin.prev to go back to")

    wrong = run(exe, prm, out, 1, extra, resume=True)
    if wrong.returncode == 0 or f"mpirun -np {n}" not in wrong.stdout:
        failures.append("resuming on one rank was not refused with the rank count named")

    for f in failures:
        print("FAIL:", f)
    if failures:
        sys.exit(1)
    print(f"PASS: resumed on {n} ranks, same checksum {first[0]} and history")


if __name__ == "__main__":
    main()
