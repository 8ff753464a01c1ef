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
# --thesis: the thesis's resolution (thesis 6.1; configs/scenes/tyre_torque_snow_thesis.textproto):
# 10 mm particles in a 2.9 x 0.6 x 0.09 m block, the full block tyre with 12 mm
# elements and 60 pitches, its two steel belts (and nothing else) mass-scaled
# from 1.37 us to 1.65 us (under 1 % added mass, printed), the same for both
# schemes: seven sub-steps fill the terrain's 11.2 us window instead of nine.
# What a torque point costs is its pace in contact: the tyre starts 0.5 mm above
# the snow with its load ramped over 2 ms, touches it about 7 ms in, and the pace
# is measured from 1 ms after the first contact to the end of --sim-ms (default 11)
# from the coupler's pace.csv (wall time against simulated time). The pace before
# contact (the first 1 ms) is printed too: it is what earlier versions of this
# bench projected from, and it is 2-3 times faster.
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
    --thesis) THESIS=1; SIM_MS=11.0; SCENE=configs/scenes/tyre_torque_snow_thesis.textproto
              SETS=(--set tyre.rim.load_ramp_time_s=0.002 --set coupling.initial_gap_m=0.0005); shift ;;
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
import csv
def pace(d):
    """Wall ms per simulated ms before contact (the first 1 ms) and in contact
    (1 ms after the first contacted window to the end), from coupler/pace.csv."""
    rows = [[float(v) for v in r] for r in list(csv.reader(open(d + "/coupler/pace.csv")))[1:]]
    forces = list(csv.reader(open(d + "/coupler/forces.csv")))
    area = forces[0].index("contact_area_m2")
    touch = next((float(r[0]) for r in forces[1:] if float(r[area]) > 0), None)
    def rate(t0, t1):
        sel = [r for r in rows if t0 <= r[0] <= t1]
        if len(sel) < 2 or sel[-1][0] <= sel[0][0]: return None
        return (sel[-1][2] - sel[0][2]) / ((sel[-1][0] - sel[0][0]) * 1e3)
    start = rows[0][0] if rows else 0.0
    before = rate(start, start + 1e-3)
    contact = rate(touch + 1e-3, 1e9) if touch is not None else None
    return before, contact, touch
def load(d):
    t = json.load(open(d + "/tyre/summary.json"))
    s = json.load(open(d + "/terrain/summary.json"))
    tp, sp = t["performance"], s["performance"]
    sim_s = tp["coupled_steps"] * t["dt_s"]
    wall = tp["coupled_wall_s"]
    windows = tp["coupling_windows"]
    before, contact, touch = pace(d)
    # The projection is the pace in contact when the run reached it, else the whole run's.
    ms = contact if contact is not None else wall / (sim_s * 1e3)
    return {"ms_per_sim_ms": ms, "projected_hours_0p4s": ms * 0.4 / 3.6,
            "ms_per_sim_ms_in_contact": contact, "ms_per_sim_ms_before_contact": before,
            "first_contact_s": touch, "ms_per_sim_ms_whole_run": wall / (sim_s * 1e3),
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
print("%-12s %12s %9s %12s %14s %14s %16s %14s %12s" % ("scheme", "window s", "sub-steps", "active share",
      "ms/sim ms", "(no contact)", "hours for 0.4 s", "tyre ms/win", "terrain ms/win"))
fmt = lambda v: "%.1f" % v if v is not None else "-"
for name, r in res["schemes"].items():
    print("%-12s %12.4g %9d %12.3f %14.1f %14s %16.2f %14.2f %12.2f" % (name, r["coupling_window_s"], r["tyre_substeps"],
          r["active_particle_share"], r["ms_per_sim_ms"], fmt(r["ms_per_sim_ms_before_contact"]),
          r["projected_hours_0p4s"], 1e3 * r["tyre_compute_s_per_window"], 1e3 * r["terrain_compute_s_per_window"]))
    if r["ms_per_sim_ms_in_contact"] is None:
        print("  (%s: no contact within the run: its pace is the whole run's; give --sim-ms more)" % name)
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
