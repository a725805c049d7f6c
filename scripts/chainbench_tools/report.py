#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes RESULTS/report.md from what scripts/run.sh left in RESULTS/: the run JSON of every
scene, the stress and sweep JSON, the benchmark JSON, the plots and the replay pages with their
screenshots. One page: a conclusion computed from the data, then tables and plots inline.

    scripts/report.py results
"""
import datetime
import json
import os
import subprocess
import sys

from . import bench_table  # docs/results.md's tables, reused
from . import report_conclusion  # the opening section
from . import stress_table  # docs/stress.md's stress results, reused


def suite_order(root):
    """The default suite's scenes in their order (RESULTS/suite.txt, which scripts/run.sh writes
    from `chainbench list --suite default`); other runs follow by name."""
    try:
        with open(os.path.join(root, "suite.txt"), encoding="utf-8") as f:
            return [line.strip() for line in f if line.strip()]
    except OSError:
        return []


COLUMNS = """What the columns say:

- *error m*: distance from the scene's expected answer (the largest error of any expectation entry:
  metres from an expected centre, or how far beyond a bound), else from the reference's final centres.
- *verdict*: `ok` (every check passed), `budget` (a step cut short by the chain solver's work budget),
  `penetrating` (two boxes overlapped deeper than the scene's tolerance, by default 5% of the smaller box),
  `wrong` (an expectation failed), `tunnelled` (a body passed through another), `escaped` (a body ended
  beyond where anything could send it), `unstable` (non-finite, or faster than gravity, drivers and initial
  speeds allow), `error`, `hang`, `crash`.
- *max ms*: the slowest step of the run (the worst frame a game budgets for; `-` for a file without it).
- *vs ref max/rms m*: distance between this engine's final centres and the reference's, worst and RMS.
- *EFD/body-step m*: energy-free displacement: the part of each step's move that the body's velocity does not
  explain, per body and step. *max pen m*: deepest overlap of two boxes after any step. *peak m/s*: the
  fastest any body moved in a step, measured from positions. *stable*: finite, nothing escaped or tunnelled,
  no blow-up and no step cut short."""


def g(value, digits=3):
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "**NO**"
    return f"{value:.{digits}g}"


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def expect_cell(expect):
    """pass, or FAIL (near: every failure within a tenth of its tolerance), with the largest error
    of the entries judged in metres and, apart, of the rest limits (m/s)."""
    if not expect:
        return "-"
    figures = f"{g(expect['max_error'])} m"
    if "max_speed_error" in expect:
        figures += f", rest {g(expect['max_speed_error'])} m/s"
    if expect["pass"]:
        return f"pass ({figures})"
    return f"**FAIL{' (near)' if expect.get('near_miss') else ''}** ({figures})"


def verdict_cell(run):
    verdict = run.get("verdict")
    if not verdict:
        return "-"
    return verdict["class"] if verdict["class"] == "ok" else f"**{verdict['class']}**"


def all_runs(run):
    return run["runs"] + ([run["reference_run"]] if "reference_run" in run else [])


def replay_lines(root, stem, name):
    """A link to the scene's replay page and its screenshot, where run.sh made them."""
    page, shot = f"replay/{stem}.html", f"replay/{stem}.png"
    if not os.path.exists(os.path.join(root, page)):
        return []
    lines = [f"[Replay: every engine's run of `{name}`, step by step]({page}) (one self-contained "
             "page: open it in a browser)", ""]
    if os.path.exists(os.path.join(root, shot)):
        lines += [f"[![{name}: the replay page at the last step]({shot})]({page})", ""]
    return lines


def replay_summary(root):
    """What the replay pages cost: their sizes and how long headless Chromium took."""
    path = os.path.join(root, "replay", "timings.json")
    if not os.path.exists(path):
        return []
    pages = load(path)
    if not pages:
        return []
    largest = max(pages, key=lambda p: p["bytes"])
    slowest = max(pages, key=lambda p: p["open_s"])
    return [f"Each scene below links a replay page: every engine's boxes step by step, the charts of "
            f"their distance from the reference, energy-free displacement and penetration, the "
            f"expectations and every failed check marked. The {len(pages)} pages take "
            f"{sum(p['bytes'] for p in pages) / 1e6:.1f} MB together, the largest "
            f"{largest['bytes'] / 1e6:.1f} MB (`{os.path.basename(largest['page'])}`); headless "
            f"Chromium opened each in at most {slowest['open_s']:.2f} s and played each to its "
            f"last step at {pages[0]['speed']:g}x in at most "
            f"{max(p['play_s'] for p in pages):.2f} s (`replay/timings.json`).", ""]


def scene_section(run, plots_dir, root=None, stem=None):
    scene = run["scene"]
    name = scene["name"]
    lines = [f"### {name}", ""]
    if scene.get("description"):
        lines += [scene["description"] + f"; {scene['bodies']} bodies, {scene['steps']} steps.", ""]
    if root:
        lines += replay_lines(root, stem or name, name)
    errors = {c["engine"]: c["final_position_error"] for c in run.get("comparison", [])}
    speedups = {c["engine"]: c.get("speedup") for c in run.get("comparison", [])}
    runs = all_runs(run)
    has_expect = any(r.get("expect") for r in runs)
    lines += ["| engine | ms/step | max ms | x ref |" + (" expect |" if has_expect else "") +
              " vs ref max m | vs ref rms m | EFD/body-step m | max pen m | peak m/s | stable | verdict | "
              "the engine's counters |",
              "|---|---:|---:|---:|" + ("---|" if has_expect else "") + "---:|---:|---:|---:|---:|---|---|---|"]
    for r in runs:
        m, c = r.get("metrics", {}), r.get("counters", {})
        e = errors.get(r["engine"])
        is_ref = r["engine"] == run.get("reference")
        efd = m.get("energy_free_displacement", {}).get("per_body_step")
        lines.append(
            f"| {r['label']}{' (ref)' if is_ref else ''} | {g(r['ms_per_step']['median'], 4)} | "
            f"{g(r['ms_per_step'].get('max'), 4)} | "
            f"{g(speedups.get(r['engine']) or (1.0 if is_ref else None))} |" +
            (f" {expect_cell(r.get('expect'))} |" if has_expect else "") +
            f" {g(e['max']) if e else ('0' if is_ref else '-')} | {g(e['rms']) if e else ('0' if is_ref else '-')} | "
            f"{g(efd)} | {g(m.get('max_penetration'))} | {g(m.get('peak_speed'))} | {g(m.get('stable'))} | "
            f"{verdict_cell(r)} | {', '.join(f'{k} {g(v, 4)}' for k, v in c.items()) or '-'} |")
    lines.append("")
    ref = next((r for r in runs if r["engine"] == run.get("reference")), None)
    if has_expect:
        met = [r["label"] for r in runs if r.get("expect", {}).get("pass")]
        missed = [r["label"] for r in runs if r.get("expect") and not r["expect"]["pass"]]
        lines += [f"Expectations ({len(scene.get('expect', []))}): met by {', '.join(met) or 'no engine'}" +
                  (f"; missed by {', '.join(missed)}" if missed else "") + ".", ""]
        if ref and ref.get("expect") and not ref["expect"]["pass"]:
            lines += [f"The reference {ref['label']} misses the expectations: the vs-ref columns measure the "
                      "distance from it, not an error.", ""]
    for r in runs:
        verdict = r.get("verdict")
        if verdict and verdict["class"] != "ok":
            lines.append(f"- {r['label']}: **{verdict['class']}**: {verdict['detail']}")
    if any(r.get("verdict", {}).get("class", "ok") != "ok" for r in runs):
        lines.append("")
    for plot, caption in ((f"states_{name}.png", "final states of every engine, drawn over each other"),
                          (f"trace_{name}.png", "energy-free displacement and penetration over time")):
        if os.path.exists(os.path.join(plots_dir, plot)):
            lines += [f"![{name}: {caption}](plots/{plot})", ""]
    return lines


def truth_error(run, r):
    """An engine's error against the most accurate reference the scene has: its expectations
    (the largest error of any entry), else the run's reference. (text, against)"""
    if r is None:
        return "-", None
    if r.get("expect"):
        mark = "" if r["expect"]["pass"] else " ✗"
        return g(r["expect"]["max_error"]) + mark, "expect"
    errors = {c["engine"]: c["final_position_error"]["max"] for c in run.get("comparison", [])}
    if r["engine"] == run.get("reference"):
        return "0", "ref"
    return g(errors.get(r["engine"])), "ref"


def summary(runs):
    """One row per scene: each engine's time, the reference's time over the engine under test's
    (the run marked "gate"), each engine's error against the scene's truth and its verdict. The
    engines are the runs' own labels, in the order they ran."""
    labels = list(dict.fromkeys(r["label"] for run in runs for r in all_runs(run)))
    subject = next((r["label"] for run in runs for r in all_runs(run) if r.get("gate")), labels[0])
    reference = next((r["label"] for run in runs for r in all_runs(run)
                      if r["engine"] == run.get("reference")), None)
    ratio_title = f" {reference} / {subject} |" if reference and reference != subject else ""
    lines = ["| scene | bodies | " + " | ".join(f"{lb} ms/step" for lb in labels) + " |" + ratio_title +
             " error against | error m (" + " / ".join(labels) + ") | verdict (" + " / ".join(labels) + ") |",
             "|---|---:|" + "---:|" * len(labels) + ("---:|" if ratio_title else "") + "---|---|---|"]
    for run in runs:
        by_label = {}
        for r in all_runs(run):
            by_label.setdefault(r["label"], r)
        row = [by_label.get(lb) for lb in labels]
        t = lambda r: r["ms_per_step"]["median"] if r else None  # noqa: E731
        ratio = ""
        if ratio_title:
            ref, sub = by_label.get(reference), by_label.get(subject)
            ratio = f" {t(ref) / t(sub):.1f}x |" if ref and sub and t(sub) else " - |"
        errors = [truth_error(run, r) for r in row]
        against = next((a for _, a in errors if a), "-")
        against = (f"expectations ({len(run['scene'].get('expect', []))})" if against == "expect"
                   else f"`{run.get('reference', '-')}`" if against == "ref" else "-")
        lines.append(f"| [{run['scene']['name']}](#{run['scene']['name']}) | {run['scene']['bodies']} | " +
                     " | ".join(g(t(r), 4) for r in row) + " |" + ratio + f" {against} | " +
                     " / ".join(e for e, _ in errors) + " | " +
                     " / ".join(verdict_cell(r) if r else "-" for r in row) + " |")
    return lines


def stress_section(stress):
    return (["## Stress: where each engine breaks", "",
             "`chainbench stress`: every case in every engine, each in a process of its own (a crash or a hang is "
             "a verdict), judged against the right answer its scene states. A *known* failure of the modern "
             "solver is listed, not hidden: it does not count in the exit status until its fix lands.", ""] +
            stress_table.grid(stress) + ["", "Where each engine is not ok, and why:", ""] +
            stress_table.breaks(stress) + [""])


def sweep_section(sweep, plots_dir):
    lines = ["## Error against run time", "",
             "Each point is one engine setting, its final positions measured against the reference named "
             "under each table; `*` marks the Pareto front (nothing is both faster and more accurate).", ""]
    for s in sweep["scenes"]:
        name = s["scene"]["name"]
        ref = "the scene's expectations" if s["reference"] == "expect" else f"`{s['reference_label']}`"
        lines += [f"### sweep: {name}", "", f"Error against {ref}.", "",
                  "| engine | ms/step | err max m | err rms m | EFD/body-step m | max pen m | stable | pareto |",
                  "|---|---:|---:|---:|---:|---:|---|---|"]
        for p in s["points"]:
            e = p["final_position_error"]
            lines.append(f"| {p['label']} | {g(p['ms_per_step'], 4)} | {g(e['max'])} | {g(e['rms'])} | "
                         f"{g(p['energy_free_displacement'])} | {g(p['max_penetration'])} | {g(p['stable'])} | "
                         f"{'*' if p['pareto'] else ''} |")
        lines.append("")
        if os.path.exists(os.path.join(plots_dir, f"sweep_{name}.png")):
            lines += [f"![{name}: error against ms/step](plots/sweep_{name}.png)", ""]
    return lines


def main():
    usage = "usage: scripts/report.py RESULTS_DIR (the folder scripts/run.sh writes: results)"
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip() + "\n\n" + usage)
        return
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        print(usage, file=sys.stderr)
        sys.exit(2)
    root = sys.argv[1]
    plots = os.path.join(root, "plots")
    runs_dir = os.path.join(root, "runs")
    order = suite_order(root)
    try:
        names = sorted((f[:-5] for f in os.listdir(runs_dir) if f.endswith(".json")),
                       key=lambda n: (order.index(n) if n in order else len(order), n))
        runs = [load(os.path.join(runs_dir, n + ".json")) for n in names]
    except (OSError, ValueError) as e:
        sys.exit(f"report.py: cannot read the runs in {runs_dir}: {e}")
    if not runs:
        sys.exit(f"report.py: {runs_dir} holds no run JSON")
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                                check=False).stdout.strip() or "unknown"
    except OSError:
        commit = "unknown"

    engines = list(dict.fromkeys(f"`{r['label']}`" for run in runs for r in all_runs(run)))
    reference = next((r["label"] for r in all_runs(runs[0]) if r["engine"] == runs[0].get("reference")), None)
    lines = ["# chainbench report", "",
             f"Generated {datetime.datetime.now().strftime('%Y-%m-%d %H:%M')} from commit {commit} by "
             f"`scripts/run.sh`. Every scene ran in {', '.join(engines)}"
             + (f"; `{reference}` is the reference of the vs-ref columns" if reference else "") +
             ". Each engine is judged against the right answer its scene states (its expectations); "
             "✗ marks an engine that misses them.", "",
             "## Summary", ""]
    stress_path, sweep_path = os.path.join(root, "stress.json"), os.path.join(root, "sweep.json")
    stress = load(stress_path) if os.path.exists(stress_path) else None
    sweep = load(sweep_path) if os.path.exists(sweep_path) else None
    lines[-2:-2] = report_conclusion.conclusion(runs, stress, sweep)
    lines += summary(runs) + ["", COLUMNS, "", "## Scenes", ""] + replay_summary(root)
    for stem, run in zip(names, runs):
        lines += scene_section(run, plots, root, stem)

    if stress:
        lines += stress_section(stress)

    if sweep:
        lines += sweep_section(sweep, plots)

    bench_path = os.path.join(root, "bench_quick.json")
    if os.path.exists(bench_path):
        context, bench_runs = bench_table.load(bench_path)
        lines += ["## Time per step and scaling", "",
                  "Google Benchmark, warmed-up worlds, one step per iteration (docs/results.md's tables come from "
                  "the full suite, `scripts/bench.sh`).", "", bench_table.tables(context, bench_runs), ""]
        if os.path.exists(os.path.join(plots, "scaling.png")):
            lines += ["![ms/step against bodies](plots/scaling.png)", ""]

    path = os.path.join(root, "report.md")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print(path)


if __name__ == "__main__":
    main()
