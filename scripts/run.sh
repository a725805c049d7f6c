#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is missing, builds, runs the default comparison suite and writes results/:
#   results/runs/<scene>.{json,csv}    chainbench run, every engine with sleeping off and on,
#                                      every default scene (the moving ones included) and
#                                      every example scene file in bench/examples/
#   results/stress.{json,txt}          chainbench stress, the full matrix
#   results/traces/<scene>.csv         per-step traces of a few small scenes
#   results/replay/<scene>.{html,png}  a replay page of every run above, and its last step as
#                                      headless Chromium shows it (timings.json: how long each
#                                      page took to open and play)
#   results/sweep.{json,csv}           a small error-against-run-time sweep
#   results/bench_quick.json           a quick Google Benchmark subset (scaling)
#   results/plots/*.png                the plots (scripts/plot.py)
#   results/report.md                  everything above in one page
# About three minutes once built, two of them the benchmark subset (the build itself takes a few
# minutes on a 2-core machine).
# Options: --no-bench skips the benchmark subset.
set -euo pipefail
cd "$(dirname "$0")/.."

bench=1
for arg in "$@"; do
  case "$arg" in
    --no-bench) bench=0 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "usage: $0 [--no-bench]" >&2; exit 2 ;;
  esac
done

scripts/deps.sh run
cmake --preset release
cmake --build --preset release

cb=build/bin/chainbench
out=results
rm -rf "$out/runs" "$out/traces" "$out/plots" "$out/replay" "$out/bench_quick.json" \
  "$out/bench_quick.txt"
mkdir -p "$out/runs" "$out/traces" "$out/plots" "$out/replay"
start=$SECONDS
say() { echo "run.sh: $* ($((SECONDS - start)) s)" >&2; }

# The default suite, as the command names it; the report lists the runs in this order.
mapfile -t scenes < <("$cb" list --suite default)
if [[ ${#scenes[@]} -eq 0 ]]; then
  echo "run.sh: $cb list --suite default named no scene" >&2
  exit 1
fi
printf '%s\n' "${scenes[@]}" > "$out/suite.txt"
traced=(stack overlap_recovery push_stack squeeze seed_squeeze)
# Every reference as games ship it and as it runs by default: sleeping on and off (and Box2D v3
# where it is built), so that the report's ratios answer against each.
engines=defaults,box2d:sleep=1,chipmunk:sleep=1
if "$cb" engines | grep -q '^box2d3:'; then
  engines+=,box2d3,box2d3:sleep=1
fi
for scene in "${scenes[@]}"; do
  say "run $scene"
  trace=()
  for t in "${traced[@]}"; do
    [[ "$t" == "$scene" ]] && trace=(--trace "$out/traces/$scene.csv")
  done
  replay=(--replay "$out/replay/$scene.html")
  "$cb" run --scene "$scene" --engines "$engines" --json "$out/runs/$scene.json" \
    --csv "$out/runs/$scene.csv" "${trace[@]}" "${replay[@]}" > "$out/runs/$scene.txt"
done

files=()
for file in bench/examples/*.json; do
  scene=$(basename "$file" .json)
  files+=("$scene")
  say "run $file"
  "$cb" run --scene-file "$file" --engines "$engines" --json "$out/runs/$scene.json" --csv "$out/runs/$scene.csv" \
    --replay "$out/replay/$scene.html" > "$out/runs/$scene.txt"
done

say "stress"
stress_status=0
"$cb" stress --json "$out/stress.json" > "$out/stress.txt" || stress_status=$?

say "sweep"
"$cb" sweep --scene stack --scene pyramid --scene heavy_on_light --scene push_row --scene push_stack \
  --json "$out/sweep.json" --csv "$out/sweep.csv" > "$out/sweep.txt"

if [[ $bench -eq 1 ]]; then
  say "benchmark subset"
  build/bin/chainbench_bench \
    --benchmark_filter='^(pyramid/|random_pile/[^/]+/(1000|10000|100000)/|harness/(pyramid|random_pile/(1000|10000))/)' \
    --benchmark_out="$out/bench_quick.json" --benchmark_out_format=json > "$out/bench_quick.txt"
fi

# The Python CMake found for the tests (tests/CMakeLists.txt), with matplotlib.
py=$(sed -n 's/^CHAINBENCH_PYTHON:INTERNAL=//p' build/CMakeCache.txt)
py=${py:-python3}
say "replay screenshots"
"$py" scripts/replay_browser.py "$out"/replay/*.html --speed 16 --json "$out/replay/timings.json" \
  > "$out/replay/timings.txt"

say "plots"
for scene in "${scenes[@]}" "${files[@]}"; do
  "$py" scripts/plot.py states "$out/runs/$scene.json" --out "$out/plots" > /dev/null
done
for scene in "${traced[@]}"; do
  "$py" scripts/plot.py trace "$out/traces/$scene.csv" --name "$scene" --out "$out/plots" > /dev/null
done
"$py" scripts/plot.py sweep "$out/sweep.json" --out "$out/plots" > /dev/null
[[ -f "$out/bench_quick.json" ]] && "$py" scripts/plot.py scaling "$out/bench_quick.json" --out "$out/plots" > /dev/null

"$py" scripts/report.py "$out"
say "done: $out/report.md"
if [[ $stress_status -ne 0 ]]; then
  echo "run.sh: chainbench stress failed (status $stress_status): see $out/stress.txt" >&2
  exit "$stress_status"
fi
