#!/bin/bash
# Vibrating-bar error and wall time per shape function, resolution and mass corrections.
# Usage: benchmarks/shape_function_table.sh [build dir] [output csv]
bin=${1:-build}/lme-mpm; out=${2:-shape_function_table.csv}; echo "shape_function,gamma,corrections,h,particles,steps,wall_seconds,error_displacement_l2,error_velocity_l2" > $out
for K in 0 2; do for sf in linear ugimp bspline lme; do for h in 0.05 0.025 0.0125 0.00625; do pl=gauss; [ $sf = ugimp ] && pl=uniform;
  $bin prm/vibrating_bar.prm --threads 1 --set "Output/Directory=output/shape_function_table" --set "Grid/Cell size=$h" --set "Shape functions/Type=$sf" --set "Output/Write particle files=false" --set "Output/Verbosity=0" --set "Time/Mass matrix corrections=$K" --set "Body 1/Particle placement=$pl" > /dev/null 2>&1 || echo "FAILED $sf $K $h"
  python3 -c "
import json; s=json.load(open('output/shape_function_table/summary.json')); g='1.8' if '$sf'=='lme' else ''
print('$sf,%s,$K,$h,%d,%d,%.4f,%.4e,%.4e'%(g,s['particles'],s['steps'],s['wall_seconds'],s['max_error_displacement_l2'],s['max_error_velocity_l2']))" >> $out
done; done; done
