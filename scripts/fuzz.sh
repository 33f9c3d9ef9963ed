#!/usr/bin/env bash
# A longer fuzz run of the input than CI's: random single-entry edits of the shipped
# scenes (tests/input/test_fuzz.cc), each of which must run cleanly or stop with a message
# naming an entry. Prints the outcome counts and every run-time guard it met.
#
#   scripts/fuzz.sh [build-dir] [cases] [first-seed] [seeds]
set -euo pipefail
build=${1:-build}
cases=${2:-5000}
seed=${3:-1}
seeds=${4:-4}
for ((s = seed; s < seed + seeds; ++s)); do
  echo "seed $s, $cases cases:"
  LME_MPM_FUZZ_SEED=$s LME_MPM_FUZZ_CASES=$cases \
    "$build/unit_tests" --gtest_filter='Fuzz.*' | grep -vE '^\[|^Running|^Note|^$'
done
