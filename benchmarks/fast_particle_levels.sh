#!/usr/bin/env bash
# The levels of summary.json's max_fast_particle_cells at which linear and uGIMP shape
# functions change the energy by more than 1 % (doc/stability.md, "Fast particles on
# linear and uGIMP functions"): the vibrating bar, three periods, released so that its
# free end covers M cells per wave transit, at 40 and 160 cells. About 6 minutes on one
# core. Usage: benchmarks/fast_particle_levels.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
out=${2:-$root/output/fast_particle_levels}
mkdir -p "$out"
c=316.2277660168379 # sqrt(1e8 / 1000), the bar's wave speed
run() # family, cell size, M
{
  local cells v0 dir
  cells=$(python3 -c "print(round(1 / $2))")
  v0=$(python3 -c "print($3 / $cells * $c)")
  dir="$out/$1-$2-$3"
  "$build/lme-mpm" "$root/prm/vibrating_bar.prm" --threads 1 \
    --set "Shape functions/Type=$1" --set "Grid/Cell size=$2" \
    --set "Time/End time=0.03794733192202055" \
    --set "Body 1/Initial velocity/Function constants=v0=$v0, beta=1.5707963267948966" \
    --set "Output/Directory=$dir" --set "Output/Verbosity=0"
  python3 -c "import json; s = json.load(open('$dir/summary.json')); \
print('| $1 | $2 | $3 | %.3g | %.3g | %d | %d |' % (s['max_fast_particle_cells'], \
s['max_energy_drift'], s['steps'], len(s['warnings'])))"
}
echo "| family | h (m) | M set | max_fast_particle_cells | max_energy_drift | steps | warnings |"
echo "|---|---|---|---|---|---|---|"
for h in 0.025 0.00625; do
  for m in 0.2 0.3 0.4 0.8 1.6; do run linear $h $m; done
  for m in 0.4 1.6 3.2 6.4; do run ugimp $h $m; done
done
run ugimp 0.00625 12.8
