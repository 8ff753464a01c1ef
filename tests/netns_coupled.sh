#!/bin/bash
# Separate machines (issue: co-simulation over DDS, item 4): tyre_fe and the
# coupler in one network namespace, snow_sph in another, joined only by a veth
# pair (two hosts on one link, unicast discovery with --interface/--peer), run
# the first steps of the coarse coupled scene; the forces must equal those of
# the same run on loopback. Needs root (network namespaces); skipped otherwise.
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

RUN=$(printf '%x' $(( (RANDOM << 16) | RANDOM | 1 )))
COMMON=(--run-id "$RUN" --domain 1 --set time.max_steps=$STEPS --quiet)
echo "run $RUN: coupler (cyclone) + tyre_fe (fast) on $ADDR_A, snow_sph (cyclone) on $ADDR_B"
ip netns exec "$A" "$BIN/coupler" "$SCENE" --out "$OUT/net/coupler" --dds cyclone "${COMMON[@]}" \
  --interface "$ADDR_A" --peer "$ADDR_A" --peer "$ADDR_B" > "$OUT/coupler.log" 2>&1 &
COUPLER=$!
ip netns exec "$A" "$BIN/tyre_fe" "$SCENE" --coupled --no-vtk --out "$OUT/net/tyre" --dds fast "${COMMON[@]}" \
  --interface "$ADDR_A" --peer "$ADDR_A" --peer "$ADDR_B" > "$OUT/tyre.log" 2>&1 &
TYRE=$!
ip netns exec "$B" "$BIN/snow_sph" "$SCENE" --coupled --no-vtk --out "$OUT/net/terrain" --dds cyclone "${COMMON[@]}" \
  --interface "$ADDR_B" --peer "$ADDR_A" --peer "$ADDR_B" > "$OUT/terrain.log" 2>&1 &
TERRAIN=$!
status=0
for p in $COUPLER $TYRE $TERRAIN; do wait $p || status=1; done
if [ $status != 0 ]; then
  echo "FAILED: a process of the two-host run failed"; tail -n 5 "$OUT"/*.log; exit 1
fi
# The same run on loopback, through the launcher, same vendors.
"$BIN/cosim" run "$SCENE" --out "$OUT/lo" --dds tyre=fast,terrain=cyclone,coupler=cyclone --domain 2 \
  --no-vtk --quiet --set time.max_steps=$STEPS > "$OUT/lo.log" 2>&1 || { echo "FAILED: loopback run"; tail "$OUT/lo.log"; exit 1; }
rows=$(($(wc -l < "$OUT/net/coupler/forces.csv") - 1))
if [ "$rows" -lt 100 ]; then echo "FAILED: only $rows coupling windows over the veth link"; exit 1; fi
if ! cmp -s "$OUT/net/coupler/forces.csv" "$OUT/lo/coupler/forces.csv"; then
  echo "FAILED: forces differ between the two-host run and the loopback run"
  diff "$OUT/net/coupler/forces.csv" "$OUT/lo/coupler/forces.csv" | head -5; exit 1
fi
echo "PASSED: $rows coupling windows across two network namespaces, forces identical to loopback"
rm -rf "$OUT"
