#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (preset "fuzz": ASan + UBSan) and runs each for a fixed
# time, starting from tests/fuzz/corpus/<target>/. Prints executions per target; exits 1 if any
# target found a crash, a hang or a leak (the reproducer is in build-fuzz/artifacts/<target>/:
# add it to tests/fuzz/corpus/<target>/ with the fix, and every build replays it from then on).
#   scripts/fuzz.sh [SECONDS_PER_TARGET]      default 60
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [[ "$seconds" -lt 1 ]]; then
  echo "usage: $0 [SECONDS_PER_TARGET]   (a whole number of seconds, at least 1)" >&2
  exit 2
fi

scripts/deps.sh fuzz
cmake --preset fuzz
# The targets alone: the rest of the tree (the chainbench command, the plugins) is not fuzzed here.
cmake --build --preset fuzz --target fuzz_world fuzz_scene_file

status=0
summary=()
for target in world scene_file; do
  work=build-fuzz/corpus/$target
  artifacts=build-fuzz/artifacts/$target/
  mkdir -p "$work" "$artifacts"
  log=build-fuzz/fuzz_$target.log
  echo "fuzz.sh: fuzz_$target for $seconds s (log: $log)" >&2
  began=$SECONDS
  result=ok
  dict=()
  [[ -f tests/fuzz/$target.dict ]] && dict=(-dict="tests/fuzz/$target.dict")
  # New inputs go to the scratch corpus (first directory); the checked-in seeds are only read.
  if ! build-fuzz/bin/fuzz_$target -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -max_len=4096 -print_final_stats=1 -artifact_prefix="$artifacts" "${dict[@]}" \
      "$work" "tests/fuzz/corpus/$target" > "$log" 2>&1; then
    status=1
    result="FAILED: $(ls "$artifacts" | head -n 1)"
    echo "fuzz.sh: fuzz_$target FAILED; the end of its log:" >&2
    tail -n 30 "$log" >&2
  fi
  took=$(( SECONDS - began > 0 ? SECONDS - began : 1 ))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  execs=${execs:-0}
  corpus=$(find "$work" -type f | wc -l)
  summary+=("$(printf '%-16s %5d s %11d execs %9d execs/s %7d corpus inputs   %s' "fuzz_$target" \
    "$took" "$execs" "$(( execs / took ))" "$corpus" "$result")")
done
printf '%s\n' "${summary[@]}"
exit $status
