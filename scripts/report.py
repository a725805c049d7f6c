#!/usr/bin/env python3
"""Writes RESULTS/report.md from what scripts/run.sh left in RESULTS/: the run JSON of every
scene, the sweep JSON, the benchmark JSON and the plots. One page, tables and plots inline.

    scripts/report.py results
"""
import datetime
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_table  # noqa: E402  (the README's results tables, reused)

ORDER = ["stack", "pyramid", "many_pyramids", "mass_ratio_stack", "heavy_on_light", "overlap_recovery",
         "random_pile", "push_row", "push_into_wall", "push_stack", "squeeze", "seed_stack", "seed_squeeze",
         "seed_falling_row"]


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
    """pass, or FAIL with the largest distance from an expected centre."""
    if not expect:
        return "-"
    return f"pass ({g(expect['max_error'])} m)" if expect["pass"] else f"**FAIL** ({g(expect['max_error'])} m)"


def scene_section(run, plots_dir):
    scene = run["scene"]
    name = scene["name"]
    lines = [f"### {name}", ""]
    if scene.get("description"):
        lines += [scene["description"] + f"; {scene['bodies']} bodies, {scene['steps']} steps.", ""]
    errors = {c["engine"]: c["final_position_error"] for c in run.get("comparison", [])}
    speedups = {c["engine"]: c.get("speedup") for c in run.get("comparison", [])}
    runs = run["runs"] + ([run["reference_run"]] if "reference_run" in run else [])
    has_expect = any(r.get("expect") for r in runs)
    lines += ["| engine | ms/step | x ref | err max m | err rms m | EFD/body-step m | max pen m | stable | "
              "resolves/step | depth | budget hits | crushes |" + (" expect |" if has_expect else ""),
              "|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|" + ("---|" if has_expect else "")]
    for r in runs:
        m, c = r.get("metrics", {}), r.get("chain_stats")
        e = errors.get(r["engine"])
        is_ref = r["engine"] == run.get("reference")
        efd = m.get("energy_free_displacement", {}).get("per_body_step")
        lines.append(
            f"| {r['label']}{' (ref)' if is_ref else ''} | {g(r['ms_per_step']['median'], 4)} | "
            f"{g(speedups.get(r['engine']) or (1.0 if is_ref else None))} | "
            f"{g(e['max']) if e else ('0' if is_ref else '-')} | {g(e['rms']) if e else ('0' if is_ref else '-')} | "
            f"{g(efd)} | {g(m.get('max_penetration'))} | {g(m.get('stable'))} | "
            f"{g(c['resolve_calls'], 4) if c else '-'} | {c['max_depth'] if c else '-'} | "
            f"{c['budget_hits'] if c else '-'} | {c['crush_events'] if c else '-'} |" +
            (f" {expect_cell(r.get('expect'))} |" if has_expect else ""))
    lines.append("")
    for plot, caption in ((f"states_{name}.png", "final states of every engine, drawn over each other"),
                          (f"trace_{name}.png", "energy-free displacement and penetration over time")):
        if os.path.exists(os.path.join(plots_dir, plot)):
            lines += [f"![{name}: {caption}](plots/{plot})", ""]
    return lines


def summary(runs):
    lines = ["| scene | bodies | chain ms/step | box2d ms/step | box2d / chain | chain err m | seed2014 err m | "
             "max pen m (chain / seed2014 / box2d) | stable (chain / seed2014 / box2d) |",
             "|---|---:|---:|---:|---:|---:|---:|---|---|"]
    for run in runs:
        by_name = {}
        for r in run["runs"] + ([run["reference_run"]] if "reference_run" in run else []):
            by_name.setdefault(r["label"], r)
        chain, seed = by_name.get("chain"), by_name.get("chain:variant=seed2014")
        box2d = by_name.get("box2d")
        errors = {c["engine"]: c["final_position_error"]["max"] for c in run.get("comparison", [])}
        t = lambda r: r["ms_per_step"]["median"] if r else None  # noqa: E731
        ratio = f"{t(box2d) / t(chain):.1f}x" if chain and box2d and t(chain) else "-"
        pen = " / ".join(g(r["metrics"].get("max_penetration")) if r else "-" for r in (chain, seed, box2d))
        stable = " / ".join(g(r["metrics"].get("stable")) if r else "-" for r in (chain, seed, box2d))
        lines.append(f"| [{run['scene']['name']}](#{run['scene']['name']}) | {run['scene']['bodies']} | "
                     f"{g(t(chain), 4)} | {g(t(box2d), 4)} | {ratio} | "
                     f"{g(errors.get(chain['engine'])) if chain else '-'} | "
                     f"{g(errors.get(seed['engine'])) if seed else '-'} | {pen} | {stable} |")
    return lines


def stress_section(stress):
    lines = ["## Stress: where each engine breaks", "",
             "`chainbench stress`: every case in every engine, each in a process of its own (a crash or "
             "a hang is a verdict). *budget*: the chaining solver ran out of resolutions in some step and "
             "cut chains (reported, not fatal); *tunnelled*: the projectile crossed the stack untouched.", "",
             "| case | engine | verdict | max pen m | peak speed m/s | crushes | budget hits | tunnelled | "
             "ms/step |", "|---|---|---|---:|---:|---:|---:|---|---:|"]
    for c in stress["cases"]:
        done = c["finished"]
        lines.append(f"| {c['case']} | {c['label']} | "
                     f"{c['verdict'] if c['verdict'] in ('ok', 'budget') else '**' + c['verdict'] + '**'} | "
                     f"{g(c['max_penetration']) if done else '-'} | {g(c['peak_speed']) if done else '-'} | "
                     f"{c['crush_events'] if done else '-'} | {c['budget_hits'] if done else '-'} | "
                     f"{('yes' if c['tunnelled'] else '') if done else '-'} | "
                     f"{g(c['ms_per_step'], 4) if done else '-'} |")
    return lines + [""]


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
    if len(sys.argv) != 2:
        sys.exit("usage: scripts/report.py RESULTS_DIR")
    root = sys.argv[1]
    plots = os.path.join(root, "plots")
    runs_dir = os.path.join(root, "runs")
    try:
        names = sorted((f[:-5] for f in os.listdir(runs_dir) if f.endswith(".json")),
                       key=lambda n: (ORDER.index(n) if n in ORDER else len(ORDER), n))
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

    lines = ["# chainbench report", "",
             f"Generated {datetime.datetime.now().strftime('%Y-%m-%d %H:%M')} from commit {commit} by "
             "`scripts/run.sh`. Every scene ran in the modern chaining solver (`chain`), the 2014 variant "
             "(`chain:variant=seed2014`) and Box2D 2.4.1 at 8/3 iterations (`box2d`, the reference). "
             "The columns are defined in README.md, *Reading the table*.", "",
             "## Summary", ""]
    lines += summary(runs) + ["", "## Scenes", ""]
    for run in runs:
        lines += scene_section(run, plots)

    stress_path = os.path.join(root, "stress.json")
    if os.path.exists(stress_path):
        lines += stress_section(load(stress_path))

    sweep_path = os.path.join(root, "sweep.json")
    if os.path.exists(sweep_path):
        lines += sweep_section(load(sweep_path), plots)

    bench_path = os.path.join(root, "bench_quick.json")
    if os.path.exists(bench_path):
        context, bench_runs = bench_table.load(bench_path)
        lines += ["## Time per step and scaling", "",
                  "Google Benchmark, warmed-up worlds, one step per iteration (the README's table comes from "
                  "the full suite, `scripts/bench.sh`).", "", bench_table.tables(context, bench_runs), ""]
        if os.path.exists(os.path.join(plots, "scaling.png")):
            lines += ["![ms/step against bodies](plots/scaling.png)", ""]

    path = os.path.join(root, "report.md")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print(path)


if __name__ == "__main__":
    main()
