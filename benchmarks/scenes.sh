#!/usr/bin/env bash
# Runs every scene in prm/ at its own resolution, REPEATS times with each thread count in
# THREADS, the repeats outermost so that runs of one scene are spread over the session
# (the machine's speed drifts). Records wall time, particle-steps per second and the time
# of the fracture and contact stages in a CSV, and prints the medians as a Markdown table
# (doc/performance.md, "Every scene").
#
#   benchmarks/scenes.sh [BUILD_DIR] [OUTPUT_DIR]
#   REPEATS=3 THREADS="1 2" SCENES="mode_i_panel brazilian" benchmarks/scenes.sh build
#
# Each run writes no particle or grid files (only history.csv and summary.json), so the
# times are those of the computation. The mode-I panel in prm/ is at the paper's own
# resolution (h = 0.025, four particles per cell, LME gamma 3.5).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-output/scene_benchmark}
repeats=${REPEATS:-3}
threads_list=${THREADS:-"1 2"}
python=/usr/bin/python3
[ -x "$python" ] || python=python3
if [ -n "${SCENES:-}" ]; then
  scenes=()
  for s in $SCENES; do scenes+=("prm/$s.prm"); done
else
  scenes=(prm/*.prm)
fi
mkdir -p "$out"
csv="$out/scenes.csv"
echo "scene,threads,repeat,process_seconds,wall_seconds,particles,steps,particle_steps_per_second,fracture_seconds,contact_seconds" >"$csv"

for r in $(seq "$repeats"); do
  for prm in "${scenes[@]}"; do
    scene=$(basename "$prm" .prm)
    for th in $threads_list; do
      dir="$out/runs/$scene-t$th"
      rm -rf "$dir"
      mkdir -p "$out/runs"
      start=$(date +%s.%N)
      "$build/lme-mpm" "$prm" --threads "$th" --set "Output/Verbosity=0" \
        --set "Output/Write particle files=false" --set "Output/Directory=$dir" \
        >"$dir.log" 2>&1 || { echo "$scene failed: $dir.log" >&2; exit 1; }
      end=$(date +%s.%N)
      "$python" - "$dir/summary.json" "$scene" "$th" "$r" "$start" "$end" >>"$csv" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
v = s.get("results", s)
def get(k):
    return v.get(k, 0.0)
print(",".join(str(x) for x in [
    sys.argv[2], sys.argv[3], sys.argv[4],
    round(float(sys.argv[6]) - float(sys.argv[5]), 3), get("wall_seconds"),
    int(get("particles")), int(get("steps")), get("particle_steps_per_second"),
    get("stage_seconds_fracture"), get("stage_seconds_contact_bodies_crack_faces")]))
EOF
      echo "run $r: $scene, $th thread(s): $(tail -n 1 "$csv" | cut -d, -f5) s" >&2
    done
  done
done

"$python" - "$csv" <<'EOF'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
keys = sorted({(r["scene"], int(r["threads"])) for r in rows})
print("| scene | particles | steps | threads | wall time (s) | particle-steps/s | fracture | contact |")
print("|---|---|---|---|---|---|---|---|")
for scene, th in keys:
    sel = [r for r in rows if r["scene"] == scene and int(r["threads"]) == th]
    wall = [float(r["wall_seconds"]) for r in sel]
    med = statistics.median(wall)
    pss = statistics.median(float(r["particle_steps_per_second"]) for r in sel)
    frac = statistics.median(float(r["fracture_seconds"]) for r in sel)
    cont = statistics.median(float(r["contact_seconds"]) for r in sel)
    share = lambda x: f"{100 * x / med:.1f} %" if x > 0 else "-"
    print(f"| {scene} | {sel[0]['particles']} | {sel[0]['steps']} | {th} | "
          f"{med:.3g} ({min(wall):.3g}-{max(wall):.3g}) | {pss:.3g} | {share(frac)} | {share(cont)} |")
EOF
