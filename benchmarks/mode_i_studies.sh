#!/usr/bin/env bash
# Runs the mode-I panel studies of doc/validation_mode_i.md and makes their figures
# and tables: the three shape functions, grid refinement and C_eps for LME, what the
# explicit crack and the release factor each contribute, and two loadings of the
# reference table that the scene does not use (plane stress; u_x = 0 on the edges).
# Two runs at a time (about 15 minutes on two cores, Release build).
#
#   bash benchmarks/mode_i_studies.sh [build-dir] [output-dir]
set -euo pipefail
build=${1:-build}
out=${2:-output/mode_i}
prm=prm/mode_i_panel.prm
mkdir -p "$out"

run() { # name, then --set overrides
  local name=$1
  shift
  "$build/lme-mpm" "$prm" --threads 1 --set "Output/Verbosity=0" \
    --set "Output/Write particle files=false" --set "Output/Directory=$out/$name" "$@" \
    >"$out/$name.log" 2>&1 || echo "$name: exit $? (see $out/$name.log)"
}

# Lane 1: the finest grid alone (8 times the work of the scene); FINEST=1 adds h =
# 0.00625 (64 times, about 45 minutes on one thread; past the peak by t = 22).
(
  run "h=0.0125" --set "Grid/Cell size=0.0125" --set "Body 1/Holes=slot(0, 0.5, 0.25, 0.00625, 0)"
  if [ "${FINEST:-0}" = 1 ]; then
    run "h=0.00625" --set "Grid/Cell size=0.00625" --set "Time/End time=22" \
      --set "Body 1/Holes=slot(0, 0.5, 0.25, 0.003125, 0)"
  fi
) &
# Lane 2: everything else.
(
  for sf in lme linear ugimp; do run "$sf" --set "Shape functions/Type=$sf"; done
  run "h=0.05" --set "Grid/Cell size=0.05" --set "Body 1/Holes=slot(0, 0.5, 0.25, 0.025, 0)"
  for c in 1 1.5 3; do run "C_eps=$c" --set "Material 1/Fracture/Epsilon factor=$c"; done
  run "no crack" --set "Cracks/Polylines="
  run "release factor 1" --set "Material 1/Fracture/Energy release factor=1" \
    --set "Time/End time=58"
  run "no face contact" --set "Cracks/Face contact=false"
  run "plane stress" --set "Problem/Plane assumption=plane stress" \
    --set "Material 1/Fracture/Energy release factor=6.28"
  run "u_x=0" --set "Boundary conditions/Constraint 1/Components=x,y" \
    --set "Boundary conditions/Constraint 2/Components=x,y"
) &
wait

py=${PYTHON:-/usr/bin/python3}
fig=doc/figures
$py scripts/plot_mode_i.py "$out/lme" "$out/linear" "$out/ugimp" \
  --out $fig/mode_i_panel.png --table $fig/mode_i_panel.csv
finest=()
[ -d "$out/h=0.00625" ] && finest=("$out/h=0.00625")
$py scripts/plot_mode_i.py "$out/h=0.05" "$out/lme" "$out/h=0.0125" "${finest[@]}" "$out/C_eps=1" \
  "$out/C_eps=1.5" "$out/C_eps=3" --out $fig/mode_i_convergence.png \
  --table $fig/mode_i_convergence.csv
$py scripts/plot_mode_i.py "$out/lme" "$out/no crack" "$out/release factor 1" \
  "$out/no face contact" --out $fig/mode_i_crack_and_factor.png \
  --table $fig/mode_i_crack_and_factor.csv
$py scripts/plot_mode_i.py "$out/plane stress" --stiffness 0.880 --delta-c 0.00690 \
  --out $fig/mode_i_plane_stress.png --table $fig/mode_i_plane_stress.csv
$py scripts/plot_mode_i.py "$out/u_x=0" --stiffness 1.082 --delta-c 0.00629 \
  --out $fig/mode_i_fixed_x.png --table $fig/mode_i_fixed_x.csv
