#!/usr/bin/env bash
# Installs what is missing, builds with a CMake preset (release unless named) and runs every
# test with ctest, printing the output of any test that fails.
#   scripts/test.sh          release preset, build/
#   scripts/test.sh asan     AddressSanitizer + UBSan, build-asan/
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
case "$preset" in release|debug|asan) ;; *) echo "usage: $0 [release|debug|asan]" >&2; exit 2 ;; esac

scripts/deps.sh build
cmake --preset "$preset"
cmake --build --preset "$preset"
ctest --preset "$preset"
