#!/bin/bash
# Soak of a coupled run (docs/reliability.md, "Soak"): a tiny coupled scene for
# 10^6 coupling windows with each process's resident memory sampled, while a
# monitor joins the run and leaves it 100 times; then the same scene again
# without monitors, whose forces must equal the soak's row for row.
#   bench/soak.sh [--windows N] [--monitors M] [--out DIR]
# The scene: the sliding rubber block of thesis 4.3 on the bare rigid road
# (5 mm elements; its 0.5 mm water particles a patch behind it, never touched),
# one tyre step per 3 us window, about 2,000 windows/s on the 2-core machine.
# It runs the block's stages (push, hold, speed ramp) and then slides for as
# long as the window count asks. Prints and writes (DIR/soak.csv, soak.png,
# soak_summary.txt): each process's resident memory after the warm-up (the first
# 10 % of the windows) at its start, its largest and its end, and the growth.
set -euo pipefail
BIN=${COSIM_BIN_DIR:-build/bin}
WINDOWS=1000000
MONITORS=100
OUT=/tmp/cosim_soak
while [ $# -gt 0 ]; do
  case $1 in
    --windows) WINDOWS=$2; shift 2 ;;
    --monitors) MONITORS=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    *) echo "bench/soak.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
SCENE=configs/scenes/block_friction.textproto
WINDOW_S=3.0000020437513923e-06  # the block's stable step at 5 mm (the coupler's window; checked below)
PRE_S=0.05                       # the push, hold and speed ramp before the slide
slide_s() { awk -v n="$1" -v w=$WINDOW_S -v p=$PRE_S 'BEGIN { printf "%.6f", n * w - p }'; }
SETS=(--set tread_block.element_size_m=0.005 --set sph.particle_spacing_m=0.0005
      --set tread_block.initial_gap_m=0 --set tread_block.hold_s=0.01 --set tread_block.slide_ramp_time_s=0.02
      --set tread_block.average_last_s=0.015 --set output.csv_interval_s=0.01
      --set sph.container.min.x=-0.2 --set sph.container.max.x=0.2 --set sph.container.min.z=-0.0005
      --set 'sph.blocks[0].region.min.x=-0.19' --set 'sph.blocks[0].region.max.x=-0.17'
      --set 'sph.blocks[0].region.min.y=-0.01' --set 'sph.blocks[0].region.max.y=0.01'
      --set 'sph.blocks[0].region.min.z=-0.0005')
rm -rf "$OUT" && mkdir -p "$OUT"
DOMAIN=37

echo "soak: $WINDOWS windows of the sliding block, $MONITORS monitor visits, in $OUT"
"$BIN/cosim" run "$SCENE" --out "$OUT/soak" --dds cyclone --domain $DOMAIN --no-vtk --quiet "${SETS[@]}" \
  --set tread_block.slide_s="$(slide_s "$WINDOWS")" > "$OUT/soak.log" 2>&1 &
LAUNCHER=$!
pid_of() { pgrep -f -- "[/]$1 .*--out $OUT/soak/$2 " | head -1; }
for _ in $(seq 1 600); do
  C=$(pid_of coupler coupler || true) S=$(pid_of snow_sph terrain || true) T=$(pid_of tyre_fe tyre || true)
  [ -n "$C" ] && [ -n "$S" ] && [ -n "$T" ] && break
  sleep 0.1
done
windows_now() { tail -n 1 "$OUT/soak/coupler/pace.csv" 2>/dev/null | cut -d, -f2 | grep -E '^[0-9]' || echo 0; }
rss_kB() { awk '/^VmRSS/ { print $2 }' "/proc/$1/status" 2>/dev/null || echo ""; }
# Resident memory every 2 s.
(
  echo "wall_s,windows,coupler_rss_kB,terrain_rss_kB,tyre_rss_kB"
  SECONDS=0
  while kill -0 "$LAUNCHER" 2>/dev/null; do
    c=$(rss_kB "$C") s=$(rss_kB "$S") t=$(rss_kB "$T")
    [ -n "$c" ] && [ -n "$s" ] && [ -n "$t" ] && echo "$SECONDS,$(windows_now),$c,$s,$t"
    sleep 2
  done
) > "$OUT/soak.csv" &
SAMPLER=$!
# The monitor visits, one after the other once the run is under way: each joins,
# takes 200 force samples and leaves.
while [ "$(windows_now)" -lt 20000 ] && kill -0 "$LAUNCHER" 2>/dev/null; do sleep 1; done
first_visit=$(windows_now)
for i in $(seq 1 "$MONITORS"); do
  kill -0 "$LAUNCHER" 2>/dev/null || break
  "$BIN/cosim" monitor --dds cyclone --domain $DOMAIN --max-samples 200 --idle-timeout 10 --refresh 100 \
    > "$OUT/monitor.log" 2>&1 || { echo "monitor visit $i failed:"; tail -n 3 "$OUT/monitor.log"; }
done
last_visit=$(windows_now)
echo "monitor visits: $MONITORS between windows $first_visit and $last_visit"
code=0
wait "$LAUNCHER" || code=$?
wait "$SAMPLER" || true
if [ $code != 0 ]; then echo "FAILED: the soak run ended with code $code"; tail -n 5 "$OUT/soak.log"; exit 1; fi
window=$(grep -o '"coupling_window_s": [0-9.e+-]*' "$OUT/soak/coupler/summary.json" | head -1 | awk '{print $2}')
done_windows=$(grep -o '"steps": [0-9]*' "$OUT/soak/coupler/summary.json" | awk '{print $2}')
wall=$(grep -o '"wall_time_s": [0-9.e+-]*' "$OUT/soak/coupler/summary.json" | awk '{print $2}')
echo "soak: $done_windows windows of $window s in $wall s"

# Memory after the warm-up: start, largest, end, growth.
awk -F, -v warm=$((WINDOWS / 10)) '
  NR > 1 && $2 >= warm {
    for (k = 3; k <= 5; ++k) { if (!(k in start)) start[k] = $k; if ($k > hi[k]) hi[k] = $k; end[k] = $k }
  }
  END {
    split("coupler terrain tyre", name, " ")
    printf "%-8s %12s %12s %12s %10s\n", "process", "start_MB", "largest_MB", "end_MB", "growth_%"
    for (k = 3; k <= 5; ++k)
      printf "%-8s %12.1f %12.1f %12.1f %10.2f\n", name[k - 2], start[k] / 1024, hi[k] / 1024, end[k] / 1024,
             100 * (hi[k] - start[k]) / start[k]
  }' "$OUT/soak.csv" | tee "$OUT/soak_summary.txt"
gnuplot <<EOF 2>/dev/null || true
set terminal pngcairo size 900,500 noenhanced
set output "$OUT/soak.png"
set datafile separator ","
set key bottom right
set yrange [0:*]
set xlabel "coupling windows"
set ylabel "resident memory [MB]"
set title "Soak: the sliding block, $done_windows windows, $MONITORS monitor visits (windows $first_visit-$last_visit)"
set arrow from $((WINDOWS / 10)), graph 0 to $((WINDOWS / 10)), graph 1 nohead dt 2 lc rgb "gray50"
plot "$OUT/soak.csv" using 2:(\$3/1024) with lines lw 2 title "coupler", \
     "" using 2:(\$4/1024) with lines lw 2 title "terrain (snow_sph)", \
     "" using 2:(\$5/1024) with lines lw 2 title "tyre_fe (the block)"
EOF

# The same scene without monitors, over the windows the visits spanned: the same forces.
ref_windows=$((last_visit + 20000))
[ "$ref_windows" -gt "$WINDOWS" ] && ref_windows=$WINDOWS
"$BIN/cosim" run "$SCENE" --out "$OUT/reference" --dds cyclone --domain $((DOMAIN + 1)) --no-vtk --quiet "${SETS[@]}" \
  --set tread_block.slide_s="$(slide_s "$ref_windows")" > "$OUT/reference.log" 2>&1
rows=$(($(wc -l < "$OUT/reference/coupler/forces.csv") - 2))  # the last row may be the end of the slide
if head -n $((rows + 1)) "$OUT/soak/coupler/forces.csv" | cmp -s - <(head -n $((rows + 1)) "$OUT/reference/coupler/forces.csv"); then
  echo "PASSED: forces of the $rows windows the monitor visits spanned equal the run without monitors, byte for byte"
else
  echo "FAILED: the forces of the run with monitor visits differ from those without"; exit 1
fi
