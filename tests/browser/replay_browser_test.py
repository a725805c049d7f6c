#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The replay page in a real browser: chainbench runs a small scene in every default engine and
writes its run JSON, trace and replay page; headless Chromium opens the page, plays it to the
last step, and the page must then show, for named bodies, exactly the final centres the run JSON
holds, store every step's centres within half a quantum of the trace's, and have drawn every
engine's boxes on its canvas. The screenshot stays in OUT for a person to look at.

    replay_browser_test.py CHAINBENCH OUT_DIR

Exit status 77 (ctest: skipped) when Chromium is not installed, except in CI (CI=true), where
that is a failure: scripts/test.sh installs it there.
"""
import csv
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
sys.path.insert(0, HERE)
import replay_browser  # noqa: E402
from png import read_png  # noqa: E402

# Boxes created overlapping, pushed apart left, right and up and settling under gravity: centres
# move both ways along both axes, and the engines disagree by millimetres.
SCENE = ["--scene", "overlap_recovery", "--set", "base=3", "--steps", "60"]


def trace_positions(path):
    """{(engine label, body): {step: (x, y)}}; rows left out repeat the body's previous row."""
    rows = {}
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.reader(line for line in f if not line.startswith("#"))
        header = next(reader)
        ie, istep, ibody, ix, iy = (header.index(c) for c in ("engine", "step", "body", "x", "y"))
        for row in reader:
            rows.setdefault((row[ie], row[ibody]), {})[int(row[istep])] = (float(row[ix]),
                                                                            float(row[iy]))
    return rows


def at_step(series, step):
    return series[max(s for s in series if s <= step)]


def check(condition, message, failures):
    if not condition:
        failures.append(message)


def main():
    chainbench, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    if not os.access(replay_browser.CHROMIUM, os.X_OK):
        message = f"{replay_browser.CHROMIUM} is not installed"
        if os.environ.get("CI") == "true":
            print(f"FAIL: {message}, and CI must run this test (scripts/test.sh installs it)")
            return 1
        print(f"SKIP: {message} (scripts/deps.sh build installs Debian's chromium)")
        return 77
    page, run_json, trace = (os.path.join(out, name) for name in
                             ("replay.html", "replay.json", "replay.csv"))
    subprocess.run([chainbench, "run", *SCENE, "--json", run_json, "--trace", trace,
                    "--replay", page], check=True, stdout=subprocess.DEVNULL)
    with open(run_json, encoding="utf-8") as f:
        run = json.load(f)
    runs = run["runs"] + ([run["reference_run"]] if "reference_run" in run else [])
    names = run["scene"]["names"]
    steps = run["scene"]["steps"]
    traced = trace_positions(trace)
    failures = []
    start = time.monotonic()
    with replay_browser.Browser() as browser:
        shot = os.path.join(out, "replay.png")
        timing = replay_browser.play_page(browser, page, speed=8.0, shot=shot)
        b = browser.evaluate
        check(b("replay.step") == steps, f"played to step {b('replay.step')}, not {steps}", failures)
        labels = b("replay.engines")
        check(sorted(labels) == sorted(r["label"] for r in runs),
              f"the page shows engines {labels}, the run JSON {[r['label'] for r in runs]}", failures)
        quantum = b("replay.quantum")
        for r in runs:
            for name in names:  # every body, by name
                i = names.index(name)
                expected = r["final_positions"][i]
                shown = b(f"replay.positionOf({json.dumps(r['label'])}, {json.dumps(name)})")
                check(shown == expected, f"{r['label']} {name}: the page shows {shown} at the last "
                      f"step, the run JSON has {expected}", failures)
                # The stored (quantised) centres, decoded by the page's script, at every step.
                series = traced[(r["label"], name)]
                stored = b(f"Array.from({{length: {steps + 1}}}, (_, s) => replay.storedPositionOf("
                           f"{json.dumps(r['label'])}, {json.dumps(name)}, s))")
                for s in range(1, steps + 1):
                    want = at_step(series, s)
                    got = stored[s]
                    if got is None or max(abs(got[0] - want[0]), abs(got[1] - want[1])) > quantum / 2:
                        failures.append(f"{r['label']} {name} step {s}: stored {got}, trace {want}")
                        break
        rect = b("(() => { const r = document.getElementById('view').getBoundingClientRect();"
                 " return [r.left, r.top, r.width, r.height]; })()")
        colours = b("replay.colours")
    width, height, rows = read_png(shot)
    x0, y0, w, h = (int(v) for v in rect)
    drawn, seen = 0, {c: 0 for c in colours}
    wanted = {c: tuple(int(c[k:k + 2], 16) for k in (1, 3, 5)) for c in colours}
    for y in range(y0 + 2, min(y0 + h - 2, height)):
        row = rows[y]
        for x in range(x0 + 2, min(x0 + w - 2, width)):
            px = row[3 * x:3 * x + 3]
            if px != b"\xff\xff\xff":
                drawn += 1
            for c, rgb in wanted.items():
                if max(abs(px[k] - rgb[k]) for k in range(3)) <= 24:
                    seen[c] += 1
    check(drawn > 0.02 * w * h, f"only {drawn} of {w * h} canvas pixels are not background", failures)
    for label, c in zip(labels, colours):
        check(seen[c] >= 20, f"{label}'s colour {c} is on {seen[c]} pixels of the canvas", failures)
    print(f"page {os.path.getsize(page) / 1e3:.0f} kB, opened in {timing['open_s']:.2f} s, "
          f"played {steps} steps at 8x in {timing['play_s']:.2f} s; {drawn} canvas pixels drawn; "
          f"checked in {time.monotonic() - start:.1f} s; screenshot {shot}")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
