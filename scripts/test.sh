#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is missing, builds with a CMake preset (release unless named) and runs every
# test with ctest, printing the output of any test that fails.
#   scripts/test.sh          release preset, build/
#   scripts/test.sh asan     AddressSanitizer + UBSan (clang), build-asan/, the fuzz targets too
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
case "$preset" in release|ci|debug|asan) ;; *) echo "usage: $0 [release|ci|debug|asan]" >&2; exit 2 ;; esac

if [[ "$preset" == asan ]]; then scripts/deps.sh asan; else scripts/deps.sh build; fi
# CI builds with warnings as errors; a user's build only shows them.
werror=()
if [[ "${CI:-}" == true ]]; then werror=(-DCMAKE_COMPILE_WARNING_AS_ERROR=ON); fi
cmake --preset "$preset" "${werror[@]}"
cmake --build --preset "$preset"
ctest --preset "$preset"
