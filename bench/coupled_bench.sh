#!/bin/bash
# Speed of the coupled run: the coupling schemes side by side, and the coupling
# cost per DDS vendor pair.
#   bench/coupled_bench.sh [--thesis] [--sim-ms T] [--json FILE] [--pairs "fast:cyclone ..."] [--margin M]
#                          [--set field=value ...]   (passed to both schemes' runs, after --thesis's)
# Schemes (docs/coupling.md): the same scene runs T simulated milliseconds of
# coupled stepping with the common step (the reference) and with the
# multi-rate scheme (one exchange per terrain step, the tyre sub-cycling, the
# active terrain domain of margin M), in this one invocation. For each it prints
# the wall time per simulated millisecond (coupled stepping only: the tyre's
# inflation and the model building are excluded) and the projection to 0.4 s,
# one torque-force point of thesis ch. 6 (one revolution at 600 N m, thesis 6.1).
# --json FILE writes {"schemes": {"common_step": {"ms_per_sim_ms": ...,
# "projected_hours_0p4s": ...}, "multirate": {...}}, ...}.
# Vendor pairs (tyre:terrain; the coupler takes the terrain's vendor): the
# multi-rate scheme on each pair, the coupling cost (wall per window minus the
# slower solver's compute per window) and a check that every pair gives the
# same forces bit for bit; then exchange_bench's pure DDS lock-step cost.
# --thesis: the thesis's resolution (thesis 6.1): 10 mm particles in a
# 2.9 x 0.6 x 0.09 m block, the full block tyre with 12 mm elements and 60
# pitches, its two steel belts (and nothing else) mass-scaled from 1.37 us to
# 1.65 us (under 1 % added mass, printed; 1.85 us would need 3.1 %), the same for
# both schemes: seven sub-steps fill the terrain's 11.2 us window instead of nine.
set -euo pipefail
BIN=${COSIM_BIN_DIR:-build/bin}
SCENE=configs/scenes/tyre_torque_snow.textproto
SIM_MS=1.0
PAIRS="cyclone:cyclone"
JSON=""
MARGIN=0.1
SETS=()
EXTRA=()
THESIS=0
while [ $# -gt 0 ]; do
  case $1 in
    --thesis) THESIS=1; SIM_MS=1.0
              SETS=(--set sph.particle_spacing_m=0.01
                    --set sph.container.min.x=-0.4 --set sph.container.max.x=2.5
                    --set sph.container.min.y=-0.3 --set sph.container.max.y=0.3
                    --set sph.blocks[0].region.min.x=-0.4 --set sph.blocks[0].region.max.x=2.5
                    --set sph.blocks[0].region.min.y=-0.3 --set sph.blocks[0].region.max.y=0.3
                    --set tyre.mesh.element_size_m=0.012 --set tyre.tread.pitch_count=60
                    --set tyre.mass_scaling_target_dt_s=1.65e-6); shift ;;
    --sim-ms) SIM_MS=$2; shift 2 ;;
    --json) JSON=$2; shift 2 ;;
    --pairs) PAIRS=$2; shift 2 ;;
    --margin) MARGIN=$2; shift 2 ;;
    --set) EXTRA+=(--set "$2"); shift 2 ;;
    *) echo "coupled_bench: unknown option $1" >&2; exit 2 ;;
  esac
done
command -v python3 >/dev/null || { echo "coupled_bench: needs python3" >&2; exit 2; }
OUT=$(mktemp -d /tmp/cosim_coupled_bench.XXXXXX)
domain=90
# run NAME VENDOR_PAIR EXTRA_SETS...: SIM_MS of coupled stepping (the tyre's
# stages are cut by time.max_steps, counted in tyre steps from the run's start).
run() {
  local name=$1 pair=$2; shift 2
  local tyre=${pair%%:*} terrain=${pair##*:} dir=$OUT/$name
  domain=$((domain + 1))
  # The tyre's step decides how many steps SIM_MS takes: ask it (mesh only).
  local probe=$OUT/$name.probe
  "$BIN/cosim" run "$SCENE" --out "$probe" --quiet --no-vtk --set coupling.terrain=rigid_road --set tyre.mesh_only=true \
    "${SETS[@]}" "${EXTRA[@]}" "$@" > "$probe.log" 2>&1 || { echo "coupled_bench: mesh probe failed: $probe.log" >&2; tail "$probe.log" >&2; exit 1; }
  local steps
  steps=$(python3 - "$probe" "$SIM_MS" "$@" <<'PY'
import json, math, sys
d, sim_ms = sys.argv[1], float(sys.argv[2])
dt = json.load(open(d + "/summary.json"))["time_step"]["stable_dt_s"]
print(int(math.ceil(sim_ms * 1e-3 / dt)))
PY
)
  # Enough tyre steps for SIM_MS of coupled stepping after the transfer check.
  "$BIN/cosim" run "$SCENE" --out "$dir" --dds "tyre=$tyre,terrain=$terrain,coupler=$terrain" --domain $domain \
    --no-vtk --quiet --set time.max_steps=$((steps + 200)) "${SETS[@]}" "${EXTRA[@]}" "$@" > "$dir.log" 2>&1 \
    || { echo "coupled_bench: run failed: $dir.log" >&2; tail "$dir.log" >&2; exit 1; }
}
run common_step cyclone:cyclone --set coupling.scheme=COMMON_STEP --set coupling.active_domain_margin_m=0
run multirate cyclone:cyclone --set coupling.scheme=MULTIRATE --set coupling.active_domain_margin_m=$MARGIN
for pair in $PAIRS; do
  [ "$pair" = cyclone:cyclone ] && continue
  run "multirate_${pair/:/_}" "$pair" --set coupling.scheme=MULTIRATE --set coupling.active_domain_margin_m=$MARGIN
done
python3 - "$OUT" "$JSON" "$THESIS" <<'PY'
import json, os, sys, glob
out, json_file, thesis = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
def load(d):
    t = json.load(open(d + "/tyre/summary.json"))
    s = json.load(open(d + "/terrain/summary.json"))
    tp, sp = t["performance"], s["performance"]
    sim_s = tp["coupled_steps"] * t["dt_s"]
    wall = tp["coupled_wall_s"]
    windows = tp["coupling_windows"]
    return {"ms_per_sim_ms": wall / (sim_s * 1e3), "projected_hours_0p4s": wall / sim_s * 0.4 / 3600.0,
            "coupled_sim_time_s": sim_s, "coupled_wall_s": wall, "coupling_window_s": tp["coupling_window_s"],
            "tyre_substeps": tp["tyre_substeps"], "windows": windows,
            "tyre_compute_s_per_window": tp["compute_s"] / max(windows, 1),
            "terrain_compute_s_per_window": sp["compute_s"] / max(s["steps"], 1),
            "active_particle_share": sp.get("active_particle_share", 1.0),
            "particles": s["particles"], "tyre_elements": t["elements"],
            "tyre_added_mass_percent": t["time_step"]["added_mass_percent"]}
res = {"machine": os.uname().nodename, "cores": os.cpu_count(), "thesis_resolution": thesis, "schemes": {}, "pairs": {}}
for name in ("common_step", "multirate"):
    res["schemes"][name] = load(out + "/" + name)
first = res["schemes"]["common_step"]
print("particles %d, tyre elements %d, tyre added mass %.2f %%" % (first["particles"], first["tyre_elements"],
      first["tyre_added_mass_percent"]))
print("%-12s %12s %9s %12s %14s %16s %14s %12s" % ("scheme", "window s", "sub-steps", "active share",
      "ms per sim ms", "hours for 0.4 s", "tyre ms/win", "terrain ms/win"))
for name, r in res["schemes"].items():
    print("%-12s %12.4g %9d %12.3f %14.1f %16.2f %14.2f %12.2f" % (name, r["coupling_window_s"], r["tyre_substeps"],
          r["active_particle_share"], r["ms_per_sim_ms"], r["projected_hours_0p4s"],
          1e3 * r["tyre_compute_s_per_window"], 1e3 * r["terrain_compute_s_per_window"]))
speedup = first["ms_per_sim_ms"] / res["schemes"]["multirate"]["ms_per_sim_ms"]
res["speedup_multirate_over_common_step"] = speedup
print("multi-rate is %.2fx faster than the common step per simulated time" % speedup)
for d in sorted(g for g in glob.glob(out + "/multirate*/") if not g.rstrip("/").endswith(".probe")):
    name = os.path.basename(d.rstrip("/"))
    r = load(d.rstrip("/"))
    wall_per_window = r["coupled_wall_s"] / max(r["windows"], 1)
    cost = wall_per_window - max(r["tyre_compute_s_per_window"], r["terrain_compute_s_per_window"])
    res["pairs"][name] = {"wall_s_per_window": wall_per_window, "coupling_s_per_window": cost,
                          "coupling_share": cost / wall_per_window}
    print("%-28s wall %.3f ms/window, coupling %.3f ms (%.1f %%)" % (name, 1e3 * wall_per_window, 1e3 * cost,
          100 * cost / wall_per_window))
if json_file:
    json.dump(res, open(json_file, "w"), indent=2)
    print("wrote " + json_file)
PY
# Every pair ran the same multi-rate windows: their forces must be bit-identical.
if [ "$(ls "$OUT"/multirate*/coupler/forces.csv | wc -l)" -gt 1 ]; then
  if [ "$(md5sum "$OUT"/multirate*/coupler/forces.csv | awk '{print $1}' | sort -u | wc -l)" = 1 ]; then
    echo "forces.csv identical (bit for bit) on every pair: $PAIRS"
  else
    echo "forces.csv DIFFER between pairs:"; md5sum "$OUT"/multirate*/coupler/forces.csv
  fi
fi
nodes=$(python3 -c "
import json; s=json.load(open('$OUT/multirate/coupler/summary.json')); print(int(s['payload']['mean_surface_nodes_per_step']))")
echo "pure DDS lock-step cost of a $nodes-node payload (exchange_bench; per round trip, two per window):"
"$BIN/exchange_bench" --nodes "$nodes" --steps 2000 --domain 120
echo "outputs in $OUT"
