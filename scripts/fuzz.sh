#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the libFuzzer targets (tests/fuzz/): world (the solver), scene_file (the scene loader),
# plugin (what a plugin hands back), each from its corpus in tests/fuzz/corpus/<target>/.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     each target for SECONDS (default 60), built with
#                                             ASan + UBSan (preset "asan"): what CI runs
#   scripts/fuzz.sh --runs N [--jobs J] [TARGET...]
#                                             a campaign: N executions per target, built for
#                                             coverage only (preset "fuzz-fast", several times the
#                                             throughput), in J processes sharing one corpus
#                                             (default 1), then every input the campaign kept
#                                             replayed once under ASan + UBSan
#
# Prints a table: executions, rate, coverage (libFuzzer's cov: edges), corpus, result. Exits 1 if
# a target found a crash, a hang or a leak: the reproducer is in build-*/artifacts/<target>/;
# add it to tests/fuzz/corpus/<target>/ with the fix, and every build replays it from then on.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
  echo "usage: $0 [SECONDS] [TARGET...]   or   $0 --runs N [--jobs J] [TARGET...]" >&2
  echo "  SECONDS, N, J: whole numbers from 1, without leading zeros; J at most N;" >&2
  echo "  TARGET: world, scene_file or plugin, each at most once (default: all three)" >&2
  exit 2
}
# --help / -h: the comment at the top of this file, on standard output, and exit 0.
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "$0"
  exit 0
fi
# A whole number from 1 to 999,999,999,999 written without a leading zero (which bash would read
# as octal) and short enough never to overflow.
whole() { [[ "$1" =~ ^[1-9][0-9]{0,11}$ ]]; }
runs=""
seconds=60
jobs=1
if [[ "${1:-}" == "--runs" ]]; then
  { [[ $# -ge 2 ]] && whole "$2"; } || usage
  runs=$2
  shift 2
  if [[ "${1:-}" == "--jobs" ]]; then
    { [[ $# -ge 2 ]] && whole "$2"; } || usage
    jobs=$2
    shift 2
    if (( jobs > runs )); then
      echo "fuzz.sh: --jobs $jobs is more than --runs $runs: each process needs a run" >&2
      usage
    fi
  fi
elif [[ "${1:-}" == "--jobs" ]]; then
  echo "fuzz.sh: --jobs follows --runs N" >&2
  usage
elif [[ "${1:-}" =~ ^[0-9] ]]; then
  whole "$1" || usage
  seconds=$1
  shift
fi
all=(world scene_file plugin)
targets=("$@")
[[ ${#targets[@]} -eq 0 ]] && targets=("${all[@]}")
seen=" "
for t in "${targets[@]}"; do
  # Matched against each name whole: "world scene_file" as one argument is no target.
  known=0
  for a in "${all[@]}"; do [[ "$t" == "$a" ]] && known=1; done
  (( known )) || { echo "fuzz.sh: no target \"$t\"" >&2; usage; }
  [[ "$seen" == *" $t "* ]] && { echo "fuzz.sh: target \"$t\" is given twice" >&2; usage; }
  seen+="$t "
done
fuzz_names=("${targets[@]/#/fuzz_}")

scripts/deps.sh asan
# The targets alone (in CI, scripts/test.sh asan has built them with the rest).
cmake --preset asan > /dev/null
cmake --build --preset asan --target "${fuzz_names[@]}"
if [[ -n "$runs" ]]; then
  cmake --preset fuzz-fast > /dev/null
  cmake --build --preset fuzz-fast --target "${fuzz_names[@]}"
  build=build-fuzz-fast
else
  build=build-asan
fi

status=0
summary=()
for target in "${targets[@]}"; do
  work=build-asan/corpus/$target
  artifacts=$build/artifacts/$target/
  mkdir -p "$work" "$artifacts" "build-asan/artifacts/$target"
  budget_text="$seconds s"
  [[ -n "$runs" ]] && budget_text="$runs executions in $jobs process(es)"
  echo "fuzz.sh: fuzz_$target, $budget_text (logs: $build/fuzz_$target.*.log)" >&2
  began=$SECONDS
  result=ok
  options=()
  [[ -f tests/fuzz/$target.dict ]] && options=(-dict="tests/fuzz/$target.dict")
  # The solver's loops run a number of times that varies with every input, so hit-count features
  # made libFuzzer keep a new input every few executions and spend 70% of its time ranking them:
  # edges alone for the world target (2.9x the executions, the same coverage after 30,000).
  [[ "$target" == world ]] && options+=(-use_counters=0)
  # New inputs go to the scratch corpus (first directory), which the processes of a campaign
  # share (libFuzzer reloads it every second); the checked-in seeds are only read.
  rm -f "$build"/fuzz_$target.*.log
  pids=()
  for (( j = 0; j < jobs; ++j )); do
    if [[ -n "$runs" ]]; then
      budget=(-runs=$(( runs / jobs + (j < runs % jobs ? 1 : 0) )) -seed=$(( j + 1 )))
    else
      budget=(-max_total_time="$seconds")
    fi
    "$build/bin/fuzz_$target" "${budget[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
      -print_final_stats=1 -artifact_prefix="$artifacts" "${options[@]}" \
      "$work" "tests/fuzz/corpus/$target" > "$build/fuzz_$target.$j.log" 2>&1 &
    pids+=($!)
  done
  for (( j = 0; j < jobs; ++j )); do
    if ! wait "${pids[$j]}"; then
      status=1
      result="FAILED: $(ls "$artifacts" | head -n 1)"
      echo "fuzz.sh: fuzz_$target FAILED; the end of its log:" >&2
      tail -n 30 "$build/fuzz_$target.$j.log" >&2
    fi
  done
  took=$(( SECONDS - began > 0 ? SECONDS - began : 1 ))
  execs=$(cat "$build"/fuzz_$target.*.log | sed -n 's/^stat::number_of_executed_units: *//p' |
    awk '{ n += $1 } END { print n + 0 }')
  cov=$(cat "$build"/fuzz_$target.*.log | grep -o 'cov: [0-9]*' | cut -d' ' -f2 | sort -n | tail -n 1)
  corpus=$(find "$work" -type f | wc -l)
  # A campaign's throughput build has no sanitizers: what it kept is replayed with them.
  if [[ -n "$runs" && "$result" == ok ]]; then
    replay_log=build-asan/replay_$target.log
    if ! build-asan/bin/fuzz_$target -runs=0 -timeout=10 -rss_limit_mb=2048 \
        -artifact_prefix="build-asan/artifacts/$target/" "$work" "tests/fuzz/corpus/$target" \
        > "$replay_log" 2>&1; then
      status=1
      result="FAILED under ASan + UBSan (log: $replay_log)"
      tail -n 30 "$replay_log" >&2
    else
      result="ok, and ok on replay under ASan + UBSan"
    fi
  fi
  summary+=("$(printf '%-16s %6d s %11d execs %7d execs/s %6s cov %6d corpus   %s' \
    "fuzz_$target" "$took" "$execs" "$(( execs / took ))" "${cov:-?}" "$corpus" "$result")")
done
printf '%s\n' "${summary[@]}"
exit $status
