#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# scripts/fuzz.sh's arguments, checked before it builds anything: --help and -h print the usage
# and exit 0; a target is matched whole (one argument holding two names is no target) and may be
# given once.
set -uo pipefail
fuzz=$1
fail=0
expect() {  # expect STATUS TEXT ARGS...: fuzz.sh ARGS exits STATUS and prints TEXT
  local want=$1 text=$2
  shift 2
  local out status
  out=$(bash "$fuzz" "$@" 2>&1)
  status=$?
  if [[ $status -ne $want || "$out" != *"$text"* ]]; then
    echo "FAIL: fuzz.sh $* exited $status (want $want), output: $out" >&2
    fail=1
  fi
}
expect 0 "Runs the libFuzzer targets" --help
expect 0 "scripts/fuzz.sh --runs N [--jobs J] [TARGET...]" -h
expect 2 'no target "world scene_file"' "world scene_file"
expect 2 'target "world" is given twice' world plugin world
expect 2 'no target "nope"' 5 nope
expect 2 "usage:" --runs 0
exit $fail
