#!/bin/bash
# Separate machines (issue: co-simulation over DDS, item 4): tyre_fe and the
# coupler in one network namespace, snow_sph in another, joined only by a veth
# pair (two hosts on one link, unicast discovery with --interface/--peer), run
# the first steps of the coarse coupled scene; the forces must equal those of
# the same run on loopback. Then again on a lossy link (issue: runs that
# survive, item 7): 5 % of the UDP packets leaving each end dropped and 2 ms of
# delay with `tc netem` where the kernel has it, else the loss alone with an
# nftables rule (this project's build machines have no sch_netem); with RELIABLE
# QoS the forces must still equal the loopback run's. Needs root (network
# namespaces); skipped otherwise.
set -euo pipefail
BIN=${COSIM_BIN_DIR:-build/bin}
SRC=${COSIM_SOURCE_DIR:-.}
SCENE=$SRC/configs/scenes/tyre_torque_snow.textproto
STEPS=1200  # tyre steps: 8 sub-steps per coupling window, so about 140 windows
if [ "$(id -u)" != 0 ]; then echo "SKIPPED: needs root to create network namespaces"; exit 77; fi
if ! command -v ip >/dev/null; then echo "SKIPPED: the ip command (iproute2) is missing"; exit 77; fi

A=cosim_tyre_$$ B=cosim_snow_$$ VA=cva$$ VB=cvb$$
ADDR_A=10.231.$(( $$ % 200 )).1 ADDR_B=10.231.$(( $$ % 200 )).2
OUT=$(mktemp -d /tmp/cosim_netns.XXXXXX)
cleanup() {
  jobs -p | xargs -r kill 2>/dev/null || true
  ip netns del "$A" 2>/dev/null || true
  ip netns del "$B" 2>/dev/null || true
}
trap cleanup EXIT
# A container without CAP_SYS_ADMIN/CAP_NET_ADMIN cannot make namespaces even as root.
if ! ip netns add "$A" 2>/dev/null; then echo "SKIPPED: cannot create a network namespace here (no CAP_SYS_ADMIN?)"; exit 77; fi
ip netns add "$B"
if ! ip link add "$VA" type veth peer name "$VB" 2>/dev/null; then echo "SKIPPED: cannot create a veth pair here"; exit 77; fi
ip link set "$VA" netns "$A" && ip link set "$VB" netns "$B"
ip -n "$A" addr add "$ADDR_A/24" dev "$VA" && ip -n "$B" addr add "$ADDR_B/24" dev "$VB"
for ns in "$A" "$B"; do ip -n "$ns" link set lo up; done
ip -n "$A" link set "$VA" up && ip -n "$B" link set "$VB" up

# One run across the two namespaces into $OUT/$1 (coupler and tyre in A, terrain in B).
two_host_run() {
  local dir=$1
  local run
  run=$(printf '%x' $(( (RANDOM << 16) | RANDOM | 1 )))
  local common=(--run-id "$run" --domain 1 --set time.max_steps=$STEPS --quiet)
  echo "run $run ($dir): coupler (cyclone) + tyre_fe (fast) on $ADDR_A, snow_sph (cyclone) on $ADDR_B"
  ip netns exec "$A" "$BIN/coupler" "$SCENE" --out "$OUT/$dir/coupler" --dds cyclone "${common[@]}" \
    --interface "$ADDR_A" --peer "$ADDR_A" --peer "$ADDR_B" > "$OUT/$dir.coupler.log" 2>&1 &
  local coupler=$!
  ip netns exec "$A" "$BIN/tyre_fe" "$SCENE" --coupled --no-vtk --out "$OUT/$dir/tyre" --dds fast "${common[@]}" \
    --interface "$ADDR_A" --peer "$ADDR_A" --peer "$ADDR_B" > "$OUT/$dir.tyre.log" 2>&1 &
  local tyre=$!
  ip netns exec "$B" "$BIN/snow_sph" "$SCENE" --coupled --no-vtk --out "$OUT/$dir/terrain" --dds cyclone "${common[@]}" \
    --interface "$ADDR_B" --peer "$ADDR_A" --peer "$ADDR_B" > "$OUT/$dir.terrain.log" 2>&1 &
  local terrain=$!
  local status=0
  for p in $coupler $tyre $terrain; do wait $p || status=1; done
  if [ $status != 0 ]; then
    echo "FAILED: a process of the two-host run ($dir) failed"; tail -n 5 "$OUT/$dir".*.log; exit 1
  fi
}
SECONDS=0
two_host_run net
clean_s=$SECONDS
# The same run on loopback, through the launcher, same vendors.
"$BIN/cosim" run "$SCENE" --out "$OUT/lo" --dds tyre=fast,terrain=cyclone,coupler=cyclone --domain 2 \
  --no-vtk --quiet --set time.max_steps=$STEPS > "$OUT/lo.log" 2>&1 || { echo "FAILED: loopback run"; tail "$OUT/lo.log"; exit 1; }
rows=$(($(wc -l < "$OUT/net/coupler/forces.csv") - 1))
if [ "$rows" -lt 100 ]; then echo "FAILED: only $rows coupling windows over the veth link"; exit 1; fi
if ! cmp -s "$OUT/net/coupler/forces.csv" "$OUT/lo/coupler/forces.csv"; then
  echo "FAILED: forces differ between the two-host run and the loopback run"
  diff "$OUT/net/coupler/forces.csv" "$OUT/lo/coupler/forces.csv" | head -5; exit 1
fi
echo "PASSED: $rows coupling windows across two network namespaces, forces identical to loopback ($clean_s s)"

# The lossy link: both ends drop 5 % of the UDP packets they send.
lossy=""
if ip netns exec "$A" tc qdisc add dev "$VA" root netem loss 5% delay 2ms 2>/dev/null &&
   ip netns exec "$B" tc qdisc add dev "$VB" root netem loss 5% delay 2ms 2>/dev/null; then
  lossy="tc netem: 5 % loss, 2 ms delay each way"
elif command -v nft >/dev/null; then
  for pair in "$A:$VA" "$B:$VB"; do
    ns=${pair%%:*} dev=${pair#*:}
    ip netns exec "$ns" nft add table inet lossy
    ip netns exec "$ns" nft add chain inet lossy out '{ type filter hook output priority 0; }'
    ip netns exec "$ns" nft add rule inet lossy out oifname "$dev" meta l4proto udp numgen random mod 100 lt 5 counter drop
  done
  lossy="nftables: 5 % of UDP packets dropped each way (no netem in this kernel: no delay)"
else
  echo "PASSED (lossy link SKIPPED: neither tc netem nor nft is available)"; rm -rf "$OUT"; exit 0
fi
SECONDS=0
two_host_run lossy
lossy_s=$SECONDS
dropped=""
if [[ $lossy == nftables* ]]; then
  dropped=$(for ns in "$A" "$B"; do ip netns exec "$ns" nft list chain inet lossy out | grep -o 'packets [0-9]*' | cut -d' ' -f2; done | awk '{s += $1} END {print s}')
  dropped=", $dropped packets dropped"
fi
if ! cmp -s "$OUT/lossy/coupler/forces.csv" "$OUT/lo/coupler/forces.csv"; then
  echo "FAILED: forces differ between the lossy two-host run ($lossy) and the loopback run"
  diff "$OUT/lossy/coupler/forces.csv" "$OUT/lo/coupler/forces.csv" | head -5; exit 1
fi
echo "PASSED: lossy link ($lossy$dropped): forces identical to loopback, $lossy_s s against $clean_s s clean"
rm -rf "$OUT"
