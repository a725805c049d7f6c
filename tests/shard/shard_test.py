#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Sharded runs join into what the unsharded command writes: a sweep of two scenes (one judged
by its expectations, one against a reference engine) run in 3 parts by GNU parallel and a quick
stress subset in 2 parts, each merged with `chainbench merge` and compared with the unsharded
run point by point. Timings (ms/step, its spread, wall time) differ from run to run, and a
sweep's Pareto marks follow them, so those are left out of the comparison; every other value
must be equal. Then merge must refuse a part missing, a part twice, a part of another grid.

    shard_test.py CHAINBENCH SCENE_FILE OUT_DIR

Exit status 77 (ctest: skipped) when GNU parallel is not installed, except in CI (CI=true).
"""
import json
import os
import shutil
import subprocess
import sys

TIMINGS = {"ms_per_step", "ms_spread", "pareto", "reference_ms_per_step", "wall_s"}


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k not in TIMINGS}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def differences(whole, merged, where=""):
    """Where two JSON values differ (timings aside), as paths; key order counts too."""
    if isinstance(whole, dict) and isinstance(merged, dict):
        if list(whole) != list(merged):
            return [f"{where}: keys {list(whole)} != {list(merged)}"]
        return [d for k in whole if k not in TIMINGS
                for d in differences(whole[k], merged[k], f"{where}.{k}")]
    if isinstance(whole, list) and isinstance(merged, list):
        if len(whole) != len(merged):
            return [f"{where}: {len(whole)} entries != {len(merged)}"]
        return [d for k, (a, b) in enumerate(zip(whole, merged))
                for d in differences(a, b, f"{where}[{k}]")]
    return [] if whole == merged else [f"{where}: {whole!r} != {merged!r}"]


def run(args, expect=0):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != expect:
        raise SystemExit(f"FAIL: {' '.join(args)} exited {r.returncode}, not {expect}:\n"
                         f"{r.stdout[-2000:]}{r.stderr[-2000:]}")
    return r


def main():
    chainbench, scene_file, out = sys.argv[1:4]
    parallel = shutil.which("parallel")
    if not parallel:
        if os.environ.get("CI") == "true":
            print("FAIL: GNU parallel is not installed, and CI must run this test "
                  "(scripts/deps.sh installs Debian's parallel)")
            return 1
        print("SKIP: GNU parallel is not installed (scripts/deps.sh build installs it)")
        return 77
    os.makedirs(out, exist_ok=True)
    failures = []

    sweep = ["sweep", "--scene", "stack", "--set", "n=4", "--steps", "60", "--scene-file", scene_file]
    parts = [os.path.join(out, f"sweep.part{k}.json") for k in (1, 2, 3)]
    # As docs/sharding.md shows it: one part per job, {} the part's number.
    run([parallel, "--will-cite", "--halt", "now,fail=1", "-j", "3", chainbench, *sweep,
         "--shard", "{}/3", "--json", os.path.join(out, "sweep.part{}.json"), ":::", "1", "2", "3"])
    whole, merged = os.path.join(out, "sweep.whole.json"), os.path.join(out, "sweep.merged.json")
    run([chainbench, *sweep, "--json", whole])
    run([chainbench, "merge", parts[2], parts[0], parts[1], "--json", merged])
    a, b = load(whole), load(merged)
    points = sum(len(s["points"]) for s in a["scenes"])
    if points < 20 or any(not s["points"] for s in a["scenes"]):
        failures.append(f"the sweep has too few points to say anything: {points}")
    if "reference_ms_per_step" not in a["scenes"][1]:
        failures.append("the scene file was not measured against a reference engine")
    failures += ["sweep" + d for d in differences(a, b)]
    sizes = [len(load(p)["shard"]["ran"]) for p in parts]
    if sorted(sizes) != sorted([points // 3 + (k < points % 3) for k in range(3)]):
        failures.append(f"parts of {sizes} points for {points} in all")

    stress = ["stress", "--quick", "--filter", "stack|squeeze"]
    halves = [os.path.join(out, f"stress.part{k}.json") for k in (1, 2)]
    for k, path in enumerate(halves, start=1):
        run([chainbench, *stress, "--shard", f"{k}/2", "--json", path])
    whole, merged = os.path.join(out, "stress.whole.json"), os.path.join(out, "stress.merged.json")
    run([chainbench, *stress, "--json", whole])
    run([chainbench, "merge", halves[1], halves[0], "--json", merged])
    failures += ["stress" + d for d in differences(load(whole), load(merged))]

    refused = {"missing": ([parts[0], parts[1]], "3/3 missing"),
               "twice": ([parts[0], parts[1], parts[1], parts[2]], "again"),
               "another command": ([parts[0], halves[1]], "a part of a stress"),
               "not a part": ([whole], "not a part of a sharded run")}
    for what, (files, message) in refused.items():
        r = run([chainbench, "merge", *files], expect=2)
        if message not in r.stderr:
            failures.append(f"merge of {what}: {r.stderr.strip()!r} does not say {message!r}")

    print(f"sweep: {points} points in 3 parts ({sizes}), stress: "
          f"{len(load(whole)['cases'])} runs in 2 parts; merged equal to the unsharded runs")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
