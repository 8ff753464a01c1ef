#!/bin/bash
# tyre_fe's explicit step against CalculiX 2.20 (ccx, *DYNAMIC, EXPLICIT) on the peer
# block of ../shared/notes/peers.md: 0.2 x 0.2 x 0.05 m, one-point hexahedra (C3D8R),
# the tread's Yeoh rubber, bottom fixed, top pushed down at 0.5 m/s; each code at its
# own stable step. Prints us per element-step on 1 and 2 threads and the ratio.
#   bench/calculix_bench.sh [--json FILE] [--meshes "44x44x11:50:250 68x68x17:30:150"]
#                           [--repeats R] [--ccx-repeats R]
# A mesh is NXxNYxNZ:N1:N2. ccx runs N1 and N2 increments; its set-up (reading, mass
# matrix, structure) is removed by differencing: (t2 - t1) / (N2 - N1) / elements
# (wall time of the process). tyre_fe (build/bin/block_bench) times its stepping only,
# median of R runs (default 3), over the same simulated time as ccx's N2 run; the top
# reaction at that time is printed for both as a check that they solve the same problem.
# Per thread count ccx runs first, then tyre_fe. The "others" column is the CPU time
# other processes took meanwhile (/proc/stat), as a share of the machine: on a shared
# machine the 2-thread figures are only meaningful where it is near 0.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${COSIM_BIN_DIR:-build/bin}
MESHES="44x44x11:50:250 68x68x17:30:150"
REPEATS=3 CCX_REPEATS=1 JSON=""
while [ $# -gt 0 ]; do
  case $1 in
    --json) JSON=$2; shift 2 ;;
    --meshes) MESHES=$2; shift 2 ;;
    --repeats) REPEATS=$2; shift 2 ;;
    --ccx-repeats) CCX_REPEATS=$2; shift 2 ;;
    *) echo "calculix_bench: unknown option $1 (--json FILE, --meshes, --repeats, --ccx-repeats)" >&2; exit 2 ;;
  esac
done
fail() { echo "calculix_bench: error: $*" >&2; exit 1; }

if ! command -v ccx >/dev/null; then
  [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null ||
    fail "ccx not found and cannot be installed here (needs root and apt-get): install Debian's calculix-ccx (apt-get install calculix-ccx)"
  echo "calculix_bench: installing calculix-ccx with apt-get"
  DEBIAN_FRONTEND=noninteractive apt-get install -y calculix-ccx >/tmp/calculix_bench_apt.log 2>&1 ||
    fail "apt-get install calculix-ccx failed (log: /tmp/calculix_bench_apt.log)"
fi
CCX_VERSION=$(dpkg-query -W -f='${Version}' calculix-ccx 2>/dev/null || echo unknown)
if [ -z "${COSIM_BIN_DIR:-}" ]; then
  [ -f build/CMakeCache.txt ] || fail "no build/: cmake -S . -B build -DCMAKE_BUILD_TYPE=Release, then rerun"
  cmake --build build -j1 --target block_bench >/dev/null || fail "building block_bench failed (cmake --build build -j1 --target block_bench)"
fi
[ -x "$BIN/block_bench" ] || fail "$BIN/block_bench not found"
[ -x /usr/bin/time ] || fail "/usr/bin/time not found (apt-get install time): it gives ccx's peak memory"

WORK=$(mktemp -d /tmp/calculix_bench.XXXXXX)
trap 'rm -rf "$WORK"' EXIT
RESULTS=$WORK/results.tsv
TICK=$(getconf CLK_TCK)
busy() { awk -v t="$TICK" '/^cpu / {printf "%.2f\n", ($2 + $3 + $4 + $7 + $8 + $9) / t}' /proc/stat; }

# timed NAME CMD...: runs CMD in $WORK; writes "wall_s peak_KB user_s sys_s others_s" to NAME.t,
# others_s the CPU time the rest of the machine used meanwhile (from /proc/stat).
timed() {
  local name=$1 t0 t1 b0 b1; shift
  b0=$(busy) t0=$(date +%s.%N)
  (cd "$WORK" && /usr/bin/time -f "%M %U %S" -o "$name.time" "$@" >"$name.log" 2>&1) ||
    { tail -5 "$WORK/$name.log" >&2; return 1; }
  t1=$(date +%s.%N) b1=$(busy)
  read -r kb u s <"$WORK/$name.time"
  echo "$(python3 -c "print($t1 - $t0, $kb, $u, $s, round($b1 - $b0 - $u - $s, 2))")" >"$WORK/$name.t"
}
# ccx_run JOB THREADS: ccx on $WORK/JOB.inp, checked (threads used, finite result).
ccx_run() {
  OMP_NUM_THREADS=$2 timed "$1" ccx -i "$1" || return 1
  grep -q "Using up to $2 cpu(s) for the stress calculation" "$WORK/$1.log" || { echo "ccx did not use $2 threads" >&2; return 1; }
  ! grep -qi nan "$WORK/$1.dat" || { echo "ccx result is NaN ($1.dat)" >&2; return 1; }
}
deck() { python3 bench/calculix_block_deck.py "$@"; }
BLOCK_BENCH=$(cd "$BIN" && pwd)/block_bench

LOAD0=$(cut -d' ' -f1-3 /proc/loadavg)
echo "calculix_bench: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load average at start: $LOAD0"
awk '{exit !($1 > 0.5)}' /proc/loadavg && echo "calculix_bench: warning: the machine is busy; 2-thread figures will suffer"
for mesh in $MESHES; do
  IFS=':x' read -r nx ny nz n1 n2 <<<"$mesh"
  [ -n "$n2" ] && [ "$n2" -gt "$n1" ] || fail "mesh '$mesh': give NXxNYxNZ:N1:N2 with N2 > N1"
  ne=$((nx * ny * nz))
  # Probe: ccx's stable increment (its COURANT estimate), checked constant over 3 increments.
  probe_s=$(python3 -c "print(1.5 * 0.05 / $nz / 167.8)")  # about 4 increments
  deck "$nx" "$ny" "$nz" "$probe_s" --trace >"$WORK/probe.inp"
  ccx_run probe 1 || fail "ccx probe run failed ($mesh)"
  dt=$(python3 - "$WORK" <<'PY'
import re, sys
d = sys.argv[1]
dt = float(re.search(r"COURANT initial stable time increment:\s*(\S+)", open(d + "/probe.log").read()).group(1))
t = [float(x) for x in re.findall(r"for set PROBE and time\s+(\S+)", open(d + "/probe.dat").read())]
if len(t) < 3 or any(abs((b - a) - dt) > 1e-5 * dt for a, b in zip([0.0] + t[:-2], t[:-1])):
    sys.exit(f"ccx increments not at its stable step {dt}: {t}")
print(dt)
PY
) || fail "ccx probe ($mesh)"
  end_s=$(python3 -c "print(($n2 - 0.5) * $dt)")
  for n in "$n1" "$n2"; do
    deck "$nx" "$ny" "$nz" "$(python3 -c "print(($n - 0.5) * $dt)")" >"$WORK/run$n.inp"  # N increments, the last half
  done
  # Per thread count: ccx's run pairs, then tyre_fe, so that both meet the same machine.
  for threads in 1 2; do
    for r in $(seq "$CCX_REPEATS"); do
      ccx_run "run$n1" "$threads" || fail "ccx run failed ($mesh, $n1 increments)"
      ccx_run "run$n2" "$threads" || fail "ccx run failed ($mesh, $n2 increments)"
      f=$(grep -A2 "total force" "$WORK/run$n2.dat" | tail -1 | awk '{print $3}')
      read -r w1 _ u1 s1 o1 <"$WORK/run$n1.t"
      read -r w2 kb u2 s2 o2 <"$WORK/run$n2.t"
      python3 -c "d = ($n2 - $n1) * $ne / 1e6; print('ccx', $ne, $threads, $dt, ($w2 - $w1) / d, $f, $end_s, $kb,
        ($u2 + $s2 - $u1 - $s1) / d, ($o1 + $o2) / ($w1 + $w2) / $(nproc), sep='\t')" >>"$RESULTS"
    done
    timed block "$BLOCK_BENCH" --divisions "$nx" "$ny" "$nz" --end-time "$end_s" --repeats "$REPEATS" \
      --threads "$threads" || fail "block_bench failed ($mesh)"
    [ "$threads" = 1 ] && head -1 "$WORK/block.log"
    read -r w kb _ _ o <"$WORK/block.t"
    t_end=$(sed -n 's/.*end time \(\S*\) s.*/\1/p' "$WORK/block.log")
    # code elements threads dt us force time peak_KB cpu_us others | min max share
    awk -v ne="$ne" -v kb="$kb" -v t="$t_end" -v o="$(python3 -c "print($o / $w / $(nproc))")" '/^RESULT/ {
      print "tyre_fe\t" ne "\t" $3 "\t" $11 "\t" $5 "\t" $15 "\t" t "\t" kb "\t" $17 "\t" o "\t" $7 "\t" $9 "\t" $13}' \
      "$WORK/block.log" >>"$RESULTS"
  done
done
echo "calculix_bench: load average at end: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$RESULTS" "$JSON" "$CCX_VERSION" "$(lscpu | sed -n 's/^Model name: *//p')" "$LOAD0" \
  "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, statistics, sys
out, ccx_version, cpu, load0, load1 = sys.argv[2:7]
keys = ("dt_s", "us_per_element_step", "top_reaction_N", "at_time_s", "peak_rss_MB", "cpu_us_per_element_step",
        "others_share")
res = {}
for line in open(sys.argv[1]):
    code, ne, th, *v = line.split()
    r = dict(zip(keys, map(float, v)))
    r["peak_rss_MB"] /= 1024
    if code == "tyre_fe":
        r.update(min=float(v[7]), max=float(v[8]), internal_forces_share=float(v[9]))
    res.setdefault((int(ne), int(th)), {}).setdefault(code, []).append(r)
print(f"{'elements':>8} {'thr':>3} | {'ccx dt s':>9} {'us':>6} {'cpu us':>6} {'MB':>5} {'others':>6} | {'ours dt s':>9}"
      f" {'us (min-max)':>21} {'cpu us':>6} {'MB':>4} {'others':>6} | {'ccx/ours':>8} {'per sim. s':>10}")
table = []
for (ne, th), v in sorted(res.items()):
    runs, t = v["ccx"], v["tyre_fe"][0]
    c = dict(runs[0], runs=len(runs), min=min(r["us_per_element_step"] for r in runs),
             max=max(r["us_per_element_step"] for r in runs))
    for k in ("us_per_element_step", "cpu_us_per_element_step", "others_share"):
        c[k] = statistics.median(r[k] for r in runs)
    ratio = c["us_per_element_step"] / t["us_per_element_step"]
    per_time = ratio * t["dt_s"] / c["dt_s"]
    print(f"{ne:>8} {th:>3} | {c['dt_s']:>9.4g} {c['us_per_element_step']:>6.3f} {c['cpu_us_per_element_step']:>6.3f}"
          f" {c['peak_rss_MB']:>5.0f} {100 * c['others_share']:>5.0f}% | {t['dt_s']:>9.4g} {t['us_per_element_step']:>6.3f}"
          f" ({t['min']:.4f}-{t['max']:.4f}) {t['cpu_us_per_element_step']:>6.3f} {t['peak_rss_MB']:>4.0f}"
          f" {100 * t['others_share']:>5.0f}% | {ratio:>7.1f}x {per_time:>9.1f}x")
    table.append(dict(elements=ne, threads=th, ratio_per_element_step=ratio, ratio_per_simulated_time=per_time,
                      ccx=c, tyre_fe=t))
print("us: wall time per element-step (ccx: median over its run pairs; ours: tyre_fe, median of its repeats);\n"
      "cpu us: the same in CPU time of all threads; others: CPU used by other processes meanwhile, share of the\n"
      "machine; ccx/ours: ratio of the wall figures, per element-step and per simulated second (own steps)")
print("tyre_fe's element kernels + gather take "
      + ", ".join(f"{100 * r['tyre_fe']['internal_forces_share']:.0f} %" for r in table) + " of its step")
print("top reaction z (both solve the same problem):")
for r in table:
    if r["threads"] == 1:
        print(f"  {r['elements']} elements: ccx {r['ccx']['top_reaction_N']:.1f} N at {r['ccx']['at_time_s']:.4g} s,"
              f" tyre_fe {r['tyre_fe']['top_reaction_N']:.1f} N at {r['tyre_fe']['at_time_s']:.4g} s")
if out:
    json.dump(dict(benchmark="bench/calculix_bench.sh", calculix_ccx=ccx_version, cpu=cpu, load_average_at_start=load0,
                   load_average_at_end=load1, results=table), open(out, "w"), indent=1)
    print(f"calculix_bench: wrote {out}")
PY
