#!/bin/bash
# Coupling cost of the coupled torque scene (issue: co-simulation over DDS, item 6).
#   bench/coupled_bench.sh [--thesis] [--steps N] [--pairs "fast:fast cyclone:cyclone fast:cyclone cyclone:fast"]
# For each vendor pair (tyre:terrain; the coupler takes the terrain's vendor)
# it runs N coupled steps of configs/scenes/tyre_torque_snow.textproto and
# prints, from the three processes' summaries:
#   - wall time per coupled step of the run,
#   - each solver's own compute time per step (time not spent waiting at the exchange),
#   - the coupling cost: wall per step minus the slower solver's compute per step,
#     as a share of the wall time (what the coupling adds to the slowest solver).
# Then exchange_bench gives the pure DDS lock-step cost (median, p99) of the
# run's payload (the surface nodes sent per step) on each pair.
# --thesis: the thesis's resolution (thesis 6.1): 10 mm particles in a
# 2.9 x 0.6 x 0.09 m block, the full block tyre with 12 mm elements and 60
# pitches (no mass scaling).
set -euo pipefail
BIN=${COSIM_BIN_DIR:-build/bin}
SCENE=configs/scenes/tyre_torque_snow.textproto
STEPS=300
PAIRS="fast:fast cyclone:cyclone fast:cyclone cyclone:fast"
SETS=()
while [ $# -gt 0 ]; do
  case $1 in
    --thesis) SETS=(--set sph.particle_spacing_m=0.01
                    --set sph.container.min.x=-0.4 --set sph.container.max.x=2.5
                    --set sph.container.min.y=-0.3 --set sph.container.max.y=0.3
                    --set sph.blocks[0].region.min.x=-0.4 --set sph.blocks[0].region.max.x=2.5
                    --set sph.blocks[0].region.min.y=-0.3 --set sph.blocks[0].region.max.y=0.3
                    --set tyre.mesh.element_size_m=0.012 --set tyre.tread.pitch_count=60
                    --set tyre.mass_scaling_target_dt_s=0); shift ;;
    --steps) STEPS=$2; shift 2 ;;
    --pairs) PAIRS=$2; shift 2 ;;
    *) echo "unknown option $1"; exit 2 ;;
  esac
done
OUT=$(mktemp -d /tmp/cosim_coupled_bench.XXXXXX)
printf "%-16s %10s %14s %14s %14s %14s %10s\n" "tyre:terrain" "steps" "wall ms/step" "tyre ms/step" "terrain ms/step" "coupling ms" "share"
domain=90
for pair in $PAIRS; do
  tyre=${pair%%:*} terrain=${pair##*:}
  dir=$OUT/$tyre-$terrain
  domain=$((domain + 1))
  "$BIN/cosim" run "$SCENE" --out "$dir" --dds "tyre=$tyre,terrain=$terrain,coupler=$terrain" --domain $domain \
    --no-vtk --quiet --set time.max_steps=$STEPS "${SETS[@]}" > "$dir.log" 2>&1 || { echo "run failed: $dir.log"; tail "$dir.log"; exit 1; }
  python3 - "$dir" "$pair" <<'PY'
import json, sys
d, pair = sys.argv[1], sys.argv[2]
t = json.load(open(d + "/tyre/summary.json"))["performance"]
s = json.load(open(d + "/terrain/summary.json"))
c = json.load(open(d + "/coupler/summary.json"))
steps = t["coupled_steps"]
wall = t["coupled_wall_s"] / steps
tyre = t["compute_s_per_step"]
terrain = s["performance"]["compute_s_per_step"]
cost = wall - max(tyre, terrain)
print("%-16s %10d %14.3f %14.3f %14.3f %14.3f %9.1f%%" % (pair, steps, 1e3 * wall, 1e3 * tyre, 1e3 * terrain,
      1e3 * cost, 100 * cost / wall))
json.dump({"pair": pair, "steps": steps, "wall_s_per_step": wall, "tyre_compute_s_per_step": tyre,
           "terrain_compute_s_per_step": terrain, "coupling_s_per_step": cost, "coupling_share": cost / wall,
           "particles": s["particles"], "tyre_elements": json.load(open(d + "/tyre/summary.json"))["elements"]},
          open(d + "/bench.json", "w"))
PY
done
python3 - "$OUT" <<'PY'
import json, glob, sys
rows = [json.load(open(f)) for f in sorted(glob.glob(sys.argv[1] + "/*/bench.json"))]
print("particles %d, tyre elements %d" % (rows[0]["particles"], rows[0]["tyre_elements"]))
PY
# Every pair ran the same steps: their forces must be bit-identical.
if [ "$(md5sum "$OUT"/*/coupler/forces.csv | awk '{print $1}' | sort -u | wc -l)" = 1 ]; then
  echo "forces.csv identical (bit for bit) on every pair: $PAIRS"
else
  echo "forces.csv DIFFER between pairs:"; md5sum "$OUT"/*/coupler/forces.csv
fi
# The run's payload: surface nodes listed per step (the coupler's kinematics), for the pure DDS cost.
nodes=$(python3 -c "
import json; s=json.load(open('$(ls -d $OUT/*/ | head -1)coupler/summary.json')); print(int(s['payload']['mean_surface_nodes_per_step']))")
echo "pure DDS lock-step cost of a $nodes-node payload (exchange_bench; per round trip, two per coupled step):"
"$BIN/exchange_bench" --nodes "$nodes" --steps 2000 --domain 120
echo "outputs in $OUT"
