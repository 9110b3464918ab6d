#!/usr/bin/env bash
# Convergence study of the start-up channel flows (docs/validation.md): runs couette and
# poiseuille at 20, 40 and 80 particles across, to an early time and to the end time, and
# prints the L2 profile errors (fluid particles against the series solution, % of the peak speed).
set -euo pipefail
bin=${PARTICULA:-build/release/particula}
out=${OUT:-runs/convergence}
mkdir -p "$out"
printf "%-11s %-6s %-9s %-14s %-10s\n" case across t_end error_percent steps
for case in couette poiseuille; do
  for n in 20 40 80; do
    d0=$(python3 -c "print(1e-3/$n)")
    for tend in 0.1125 1.5; do
      dir="$out/${case}_${n}_${tend}"
      "$bin" run "cases/$case.toml" --out "$dir" --overwrite --quiet --no-plots \
        --set resolution.d0="$d0" --set time.end="$tend" --set output.snapshots=false >/dev/null
      err=$(python3 -c "import json; print('%.5f' % (100 * json.load(open('$dir/summary.json'))['profile_error']))")
      steps=$(python3 -c "import json; print(json.load(open('$dir/summary.json'))['steps'])")
      printf "%-11s %-6s %-9s %-14s %-10s\n" "$case" "$n" "$tend" "$err" "$steps"
    done
  done
done
