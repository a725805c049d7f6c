#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian packages chainbench needs, and only those that are missing.
#   scripts/deps.sh build   compilers, CMake, Ninja, Box2D, Chipmunk2D, GoogleTest, Google Benchmark,
#                           CLI11, JSON,
#                           python3-matplotlib (the plots, and their test),
#                           chromium (replay pages played headless: their test, the report's
#                           screenshots), parallel (GNU parallel: the sharded sweep's test)
#   scripts/deps.sh run     the same
#   scripts/deps.sh asan    build + clang and its sanitizer and libFuzzer runtimes (the asan
#                           preset, the fuzz targets)
set -euo pipefail

build=(cmake ninja-build g++ libbox2d-dev libchipmunk-dev libgtest-dev libgmock-dev libbenchmark-dev
       libcli11-dev nlohmann-json3-dev python3 python3-matplotlib chromium parallel)
case "${1:-build}" in
  build) wanted=("${build[@]}") ;;
  run) wanted=("${build[@]}") ;;
  asan) wanted=("${build[@]}" clang libclang-rt-14-dev) ;;
  *) echo "usage: $0 [build|run|asan]" >&2; exit 2 ;;
esac

missing=()
for pkg in "${wanted[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null; then
  sudo=(sudo)
else
  echo "deps.sh: missing packages (${missing[*]}) and no root or sudo to install them" >&2
  exit 1
fi
echo "deps.sh: installing ${missing[*]}" >&2
"${sudo[@]}" apt-get update -q
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
  "${missing[@]}"
