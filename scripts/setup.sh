#!/usr/bin/env bash
# One set-up step: installs the Debian 12 packages the project needs (when
# missing; needs root or sudo), among them both DDS vendors (Cyclone DDS 0.10,
# Fast DDS 2.9 with fastddsgen), and builds everything into build/ (Release).
# Safe to run again: it only installs what is missing and rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(cmake g++ make git pkg-config
  libeigen3-dev libprotobuf-dev protobuf-compiler
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev gnuplot-nox
  cyclonedds-dev cyclonedds-tools libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  iproute2   # ip netns: the two-host test (tests/integration/netns_coupled.sh)
  nftables   # its lossy link where the kernel has no netem
  openssl    # scripts/make_test_ca.sh: the certificates of a secured DDS domain
  chromium   # headless: the study report test opens report.html in a real browser
  clang-14 libclang-rt-14-dev libomp-14-dev  # the fuzz targets (libFuzzer, sanitizers): scripts/fuzz.sh
  clang-format-14)  # scripts/check_format.sh: the lines a change touches against .clang-format

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

JOBS=${JOBS:-$(nproc)}
# COSIM_WERROR=ON (CI): compiler warnings fail the build.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCOSIM_WERROR="${COSIM_WERROR:-OFF}" >/dev/null
cmake --build build -j "$JOBS"
