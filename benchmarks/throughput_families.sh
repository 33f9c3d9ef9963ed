#!/bin/bash
# Throughput blocks (2D and 3D) of the tensor-product families, one thread, runs of two
# builds alternated: particle-steps per second, state checksum and peak memory per run.
#
#   benchmarks/throughput_families.sh BASE_DIR NEW_DIR [OUT_DIR]
#
# BASE_DIR and NEW_DIR each hold an lme-mpm program and its liblme_mpm.so* (a copy of
# a build directory's, run with LD_LIBRARY_PATH so that each finds its own library).
# REPEATS (default 3) rounds, each running every block, family and build once;
# FAMILIES (default "linear ugimp bspline") names the families.
set -euo pipefail
base=$1
new=$2
out=${3:-output/throughput_families}
repeats=${REPEATS:-3}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
echo "round block family build seconds particle_steps_per_second state_checksum peak_MB"
for i in $(seq "$repeats"); do
  for block in throughput throughput_3d; do
    for family in ${FAMILIES:-linear ugimp bspline}; do
      for build in base new; do
        dir=$base
        [ "$build" = new ] && dir=$new
        run="$out/${block}_${family}_${build}_$i"
        LD_LIBRARY_PATH=$dir "$dir/lme-mpm" "$here/$block.prm" --threads 1 \
          --set "Shape functions/Type=$family" --set "Output/Directory=$run" > "$run.log" 2>&1
        s="$run/summary.json"
        echo "$i $block $family $build" \
          "$(grep -o 'Finished: [0-9]* steps in [0-9.]*' "$run.log" | awk '{print $5}')" \
          "$(grep -o '"particle_steps_per_second": [0-9.e+]*' "$s" | awk '{print $2}')" \
          "$(grep -o '"state_checksum": "[0-9a-f]*' "$s" | cut -d'"' -f4)" \
          "$(grep -o '"peak_resident_megabytes": [0-9.]*' "$s" | awk '{print $2}')"
      done
    done
  done
done
