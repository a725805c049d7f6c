#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the Google Benchmark suite (build/bin/chainbench_bench), keeps its JSON in
# results/bench.json and regenerates from it the full results tables in docs/results.md and the
# compact headline table in README.md, each row's error beside its speed (one accuracy run of each
# row's scene, results/bench_runs/). Takes about a quarter of an hour once built: the benchmark,
# then the accuracy runs.
# With arguments (they go to the benchmark, e.g. --benchmark_filter=pyramid) it runs that part
# only, into results/bench_part.json, and prints its tables instead of touching either file.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh run
cmake --preset release
cmake --build --preset release
mkdir -p results
py=$(sed -n 's/^CHAINBENCH_PYTHON:INTERNAL=//p' build/CMakeCache.txt)
py=${py:-python3}
if [[ $# -eq 0 ]]; then
  build/bin/chainbench_bench --benchmark_out=results/bench.json --benchmark_out_format=json
  "$py" scripts/bench_table.py results/bench.json --readme README.md --results docs/results.md \
    --accuracy build/bin/chainbench --runs results/bench_runs
else
  build/bin/chainbench_bench --benchmark_out=results/bench_part.json --benchmark_out_format=json "$@"
  "$py" scripts/bench_table.py results/bench_part.json
fi
