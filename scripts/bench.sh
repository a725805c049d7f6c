#!/usr/bin/env bash
# Runs the Google Benchmark suite (build/bin/chainbench_bench), keeps its JSON in
# results/bench.json and regenerates README.md's results tables from it. Extra arguments go to
# the benchmark, e.g. scripts/bench.sh --benchmark_filter='pyramid'. Takes about 10 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh run
cmake --preset release
cmake --build --preset release
mkdir -p results
build/bin/chainbench_bench --benchmark_out=results/bench.json --benchmark_out_format=json "$@"
/usr/bin/python3 scripts/bench_table.py results/bench.json --readme README.md
