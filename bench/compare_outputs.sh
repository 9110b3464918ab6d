#!/usr/bin/env bash
# Whether two particula binaries compute the same thing: short runs of the paper cases and of
# cases with contacts, a kept or rebuilt load band and open boundaries, with each binary, their
# bodies.csv, walls.csv and open_boundaries.csv compared byte for byte and summary.json compared
# without its timings. For a change that must not change results (a refactoring), build both
# binaries with -DPARTICULA_NATIVE=OFF: with -march=native the compiler fuses multiply-adds where
# the code's shape lets it, and moving code between functions changes the last bits.
#
#   bench/compare_outputs.sh OLD_BINARY NEW_BINARY OUT_DIR
#
# Run from the repository root; a few minutes on 2 cores. Prints one line per case: same or
# DIFF(file), with each binary's wall time and exit code.
set -u
if [ $# -ne 3 ]; then
  echo "usage: $0 OLD_BINARY NEW_BINARY OUT_DIR" >&2
  exit 2
fi
A=$1 B=$2 OUT=$3
mkdir -p "$OUT"

same_summary() {
  python3 - "$1" "$2" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
def strip(d):
    return {k: strip(v) if isinstance(v, dict) else v for k, v in d.items()
            if k not in ('commit', 'version', 'wall_seconds') and 'second' not in k and 'phase' not in k}
sa, sb = strip(a), strip(b)
for k in sa:
    if sa.get(k) != sb.get(k):
        print('  summary differs:', k, sa.get(k), sb.get(k))
sys.exit(0 if sa == sb else 1)
PY
}

run() {  # NAME CASE END [--set ...]
  local name=$1 case=$2 end=$3
  shift 3
  local which bin verdict=same
  for which in A B; do
    bin=$A
    [ "$which" = B ] && bin=$B
    rm -rf "$OUT/$name.$which"
    /usr/bin/time -f "%e s" -o "$OUT/$name.$which.time" "$bin" run "$case" --out "$OUT/$name.$which" --quiet \
      --no-plots --threads 2 --set time.end="$end" --set output.snapshots=false "$@" > "$OUT/$name.$which.log" 2>&1
    echo "rc=$?" >> "$OUT/$name.$which.log"
  done
  for f in bodies.csv walls.csv open_boundaries.csv; do
    [ -f "$OUT/$name.A/$f" ] || continue
    cmp -s "$OUT/$name.A/$f" "$OUT/$name.B/$f" || verdict="DIFF($f)"
  done
  same_summary "$OUT/$name.A/summary.json" "$OUT/$name.B/summary.json" || verdict="DIFF(summary.json)"
  echo "$name: $verdict  A $(cat "$OUT/$name.A.time") $(tail -1 "$OUT/$name.A.log")  B $(cat "$OUT/$name.B.time") $(tail -1 "$OUT/$name.B.log")"
}

run falling_cylinder cases/falling_cylinder.toml 0.02 --set resolution.d0=2.5e-4
run dkt cases/dkt.toml 0.003 --set resolution.d0=2e-4
run two_cylinders cases/two_cylinders_shear.toml 0.02
run shear_migration cases/shear_migration.toml 0.02
run ellipse_obstacle cases/ellipse_obstacle.toml 0.005 --set resolution.d0=2e-4
run settling_pile cases/robustness/settling_pile.toml 0.03 --set resolution.d0=1e-4
run drop_rebound cases/robustness/drop_rebound.toml 0.03
run mixed_shapes cases/robustness/mixed_shapes.toml 0.03
run rotating_drum cases/robustness/rotating_drum.toml 0.03 --set resolution.d0=2e-4
run particle_channel cases/particle_channel.toml 0.02
run fluidized_bed cases/fluidized_bed.toml 0.02
run paper_loads cases/falling_cylinder.toml 0.01 --set resolution.d0=2.5e-4 --set numerics.force=paper \
  --set collision.model=paper
run band_every_step cases/robustness/settling_pile.toml 0.02 --set resolution.d0=1e-4 --set numerics.load_band_motion=0
