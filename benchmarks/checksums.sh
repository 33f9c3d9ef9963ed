#!/usr/bin/env bash
# Runs every scene in prm/ (shortened or coarsened where the scene is long, and a few
# variants that take other code paths) and benchmarks/throughput.prm, with each thread
# count in THREADS, and prints one line per run: case, threads, state_checksum,
# failed particles. Two builds that give the same lines compute the same bits: the
# check that a refactoring changed no physics.
#
#   benchmarks/checksums.sh BUILD_DIR OUTPUT_DIR > checksums.txt
#   THREADS="1 2" CASES="tension_bar two_discs" benchmarks/checksums.sh build out
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-output/checksums}
threads_list=${THREADS:-"1 2"}
coarse_dw=(--set "Grid/Step sizes x=92*0.005" --set "Grid/Step sizes y=37*0.005"
           --set "Scene/drop weight/Notch width=0.005" --set "Time/End time=3e-4")
declare -A sets
sets[brazilian]="prm/brazilian.prm|Grid/Cell size=0.005|Time/End time=2.4e-3"
sets[disc_drop]="prm/disc_drop.prm|Time/End time=0.01"
sets[drop_weight]="prm/drop_weight.prm|DW"
sets[drop_weight_single_field]="prm/drop_weight_single_field.prm|DW"
sets[mode_i_panel]="prm/mode_i_panel.prm|Time/End time=20"
sets[mode_i_panel_linear]="prm/mode_i_panel.prm|Time/End time=20|Shape functions/Type=linear"
sets[semicircular_bending]="prm/semicircular_bending.prm|Grid/Cell size=0.003|Scene/semicircular bending/Loading velocity=0.02|Time/End time=0.02"
sets[semicircular_bending_30]="prm/semicircular_bending.prm|Grid/Cell size=0.003|Scene/semicircular bending/Loading velocity=0.02|Time/End time=0.02|Scene/semicircular bending/Notch angle=30"
sets[sliding_block]="prm/sliding_block.prm"
sets[tension_bar]="prm/tension_bar.prm"
sets[tension_bar_lme]="prm/tension_bar.prm|Shape functions/Type=lme"
sets[two_discs]="prm/two_disk_collision.prm|Time/End time=1.5"
sets[two_discs_projected]="prm/two_disk_collision.prm|Time/End time=1.5|Contact/Type=multi-field"
sets[two_discs_nodal]="prm/two_disk_collision.prm|Time/End time=1.5|Contact/Type=multi-field|Contact/Exchange=nodal|Contact/Friction coefficient=0.3"
sets[vibrating_bar]="prm/vibrating_bar.prm"
sets[vibrating_bar_mass_corrections]="prm/vibrating_bar.prm|Shape functions/Type=lme|Time/Mass matrix corrections=2"
sets[vibrating_bar_3d]="prm/vibrating_bar_3d.prm"
sets[throughput_lme]="benchmarks/throughput.prm"
sets[throughput_linear]="benchmarks/throughput.prm|Shape functions/Type=linear"
default_cases="brazilian disc_drop drop_weight drop_weight_single_field mode_i_panel mode_i_panel_linear semicircular_bending semicircular_bending_30 sliding_block tension_bar tension_bar_lme two_discs two_discs_projected two_discs_nodal vibrating_bar vibrating_bar_mass_corrections vibrating_bar_3d throughput_lme throughput_linear"
mkdir -p "$out"
for c in ${CASES:-$default_cases}; do
  IFS='|' read -r -a parts <<<"${sets[$c]}"
  prm=${parts[0]}
  args=()
  for s in "${parts[@]:1}"; do
    if [ "$s" = DW ]; then args+=("${coarse_dw[@]}"); else args+=(--set "$s"); fi
  done
  for th in $threads_list; do
    dir="$out/$c-t$th"
    rm -rf "$dir"
    "$build/lme-mpm" "$prm" --threads "$th" --set "Output/Verbosity=0" \
      --set "Output/Write particle files=false" --set "Output/Directory=$dir" "${args[@]}" \
      >"$dir.log" 2>&1 || true
    python3 - "$dir/summary.json" "$c" "$th" <<'PY'
import json, sys
try:
    s = json.load(open(sys.argv[1]))
except Exception as e:
    print(sys.argv[2], sys.argv[3], "no-summary"); sys.exit()
v = s.get("results", s)
print(sys.argv[2], sys.argv[3], s.get("state_checksum", v.get("state_checksum")),
      s.get("status"), int(v.get("failed_particles", 0)), v.get("steps"))
PY
  done
done
