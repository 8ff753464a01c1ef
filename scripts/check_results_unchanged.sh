#!/usr/bin/env bash
# Runs the main job and the 20 mm plate sinkage and compares them with the
# results recorded before a restructuring (docs/data/unchanged_results): the
# CSV series row by row and the summaries to the last bit. Exit 0: identical.
#   scripts/check_results_unchanged.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
REF=docs/data/unchanged_results
OUT=$(mktemp -d /tmp/results_unchanged.XXXXXX)
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}  # the results do not depend on it (README in $REF)
# The main job with the timing, the artificial viscosity and the box it had when
# the reference was recorded (a fixed 0.03 s of loading, 0.05 s of rolling
# averaged over 0.02 s; alpha = beta = 1; the floor at z = -0.09 m); the scene
# now loads to rest, with 0.1, on a floor at -0.08 m.
"$BUILD/bin/cosim" run configs/scenes/tyre_torque_snow.textproto --out "$OUT/main_job" --quiet \
  --set tyre.stages.loading_rest_tolerance=0 --set tyre.stages.loading_s=0.03 --set tyre.stages.rolling_s=0.05 \
  --set tyre.stages.average_last_s=0.02 --set coupling.average_last_s=0.02 \
  --set sph.artificial_viscosity.alpha=1 --set sph.artificial_viscosity.beta=1 \
  --set sph.container.min.z=-0.09 --set "sph.blocks[0].region.min.z=-0.09" >"$OUT/main_job.log" 2>&1 ||
  { echo "the main job failed: $OUT/main_job.log" >&2; exit 1; }
"$BUILD/bin/cosim" run configs/scenes/plate_sinkage.textproto --out "$OUT/plate_20mm" --quiet \
  --set sph.particle_spacing_m=0.02 >"$OUT/plate_20mm.log" 2>&1 ||
  { echo "the plate sinkage failed: $OUT/plate_20mm.log" >&2; exit 1; }
status=0
python3 scripts/compare_results.py "$REF/main_job" "$OUT/main_job" || status=1
python3 scripts/compare_results.py "$REF/plate_20mm" "$OUT/plate_20mm" || status=1
exit $status
