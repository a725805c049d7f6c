#!/usr/bin/env python3
"""Turns chainbench_bench's JSON (--benchmark_format=json) into the README's results tables.

    scripts/bench_table.py results/bench.json                 print the tables
    scripts/bench_table.py results/bench.json --readme README.md
                                                              also replace the text between
                                                              <!-- results:begin --> and
                                                              <!-- results:end --> in README.md
    scripts/bench_table.py results/bench.json --accuracy build/bin/chainbench --runs DIR
                                                              first run each row's scene in every
                                                              engine it was timed in (chainbench
                                                              run), so that each row shows its
                                                              error beside its speed

A speed claim never stands without its accuracy: with --accuracy, each row gives the subject's
final-position error against the reference and which engines meet the scene's stated answer.
"""
import argparse
import json
import os
import re
import subprocess
import sys

BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"
# An accuracy run takes the scene's own steps unless the engines' timed steps say that would take
# longer than this; then fewer steps (the row says how many).
ACCURACY_BUDGET_S = 60.0


def load(path):
    """Benchmarks by (family, engine, size): one entry each, the median when repeated."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    runs = {}
    for b in data.get("benchmarks", []):
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        if b.get("error_occurred"):
            continue
        parts = b.get("run_name", b["name"]).split("/")
        if len(parts) < 3 or parts[-1] in ("BigO", "RMS") or "_BigO" in b["name"] or "_RMS" in b["name"]:
            continue
        size = next((p for p in parts[2:] if p.isdigit()), "")
        runs[(parts[0], parts[1], size)] = b
    return data.get("context", {}), runs


def family_recipes(context):
    """{family: (scene, size key or None, [KEY=VALUE...])}, as chainbench_bench records them."""
    out = {}
    for key, value in context.items():
        if key.startswith("chainbench_family_"):
            scene, size_key, *sets = value.split()
            out[key[len("chainbench_family_"):]] = (scene, None if size_key == "-" else size_key, sets)
    return out


def accuracy_runs(context, runs, exe, out_dir):
    """Runs every (family, size) row's scene once in each engine it was timed in, against the
    reference, and returns {(family, size): run JSON}. Steps are capped so that each run stays
    within ACCURACY_BUDGET_S by the benchmark's own times."""
    recipes = family_recipes(context)
    reference = context.get("chainbench_reference", "")
    os.makedirs(out_dir, exist_ok=True)
    results = {}
    groups = sorted({(f, size) for f, e, size in runs if f in recipes})
    for n, (family, size) in enumerate(groups, 1):
        scene, size_key, sets = recipes[family]
        engines = [e for (f, e, sz) in runs if f == family and sz == size]
        if reference and reference not in engines:
            continue  # no reference timed on this row: nothing to measure the error against
        per_step_s = sum(ms(runs[(family, e, size)]) for e in engines) / 1e3
        args = [exe, "run", "--scene", scene, "--metrics", "none",
                "--engines", ",".join(e for e in engines if e != reference), "--reference", reference]
        for kv in sets + ([f"{size_key}={size}"] if size_key and size else []):
            args += ["--set", kv]
        steps = None
        if per_step_s * 300 > ACCURACY_BUDGET_S:
            steps = max(30, int(ACCURACY_BUDGET_S / per_step_s))
            args += ["--steps", str(steps)]
        path = os.path.join(out_dir, f"{family}_{size or 'default'}.json")
        args += ["--json", path]
        print(f"bench_table.py: accuracy {n}/{len(groups)}: {family} {size}", file=sys.stderr)
        done = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if done.returncode not in (0, 3):
            sys.exit(f"bench_table.py: {' '.join(args)} failed:\n{done.stderr}")
        with open(path, encoding="utf-8") as f:
            results[(family, size)] = (json.load(f), steps)
    return results


def ms(b):
    """Real time per iteration in milliseconds, whatever unit the benchmark used."""
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
    return b["real_time"] * scale


def fmt_ms(v):
    return "-" if v is None else (f"{v:.3f}" if v < 10 else f"{v:.1f}")


def error_cells(accuracy, group, subject):
    """The subject's final-position error against the reference, and who meets the answer."""
    if group not in accuracy:
        return "-", "-"
    run, steps = accuracy[group]
    label_of = {r["engine"]: r["label"] for r in run["runs"]}
    error = "-"
    for c in run.get("comparison", []):
        if label_of.get(c["engine"]) == subject:
            error = f"{c['final_position_error']['max']:.2g}"
    everyone = run["runs"] + ([run["reference_run"]] if run.get("reference_run") else [])
    met = [r["label"] for r in everyone if r.get("expect") and r["expect"].get("pass")]
    answer = ", ".join(f"`{m}`" for m in met) if met else "none"
    if steps:
        error += f" ({steps} steps)"
    return error, answer


def tables(context, runs, accuracy=None):
    """The results table (a column per engine label, in the order the benchmarks ran them), the
    ratio of the reference to the subject (the engines chainbench_bench names in its context),
    the subject's scaling on random_pile and the harness' cost."""
    out = []
    accuracy = accuracy or {}
    recipes = family_recipes(context)
    order = list(dict.fromkeys(family for family, engine, size in runs))  # as the benchmark ran
    engines = list(dict.fromkeys(engine for family, engine, size in runs if family != "harness"))
    subject = context.get("chainbench_subject", engines[0] if engines else "")
    reference = context.get("chainbench_reference", "")
    groups = sorted({(family, size) for family, engine, size in runs if family != "harness"},
                    key=lambda g: (order.index(g[0]) if g[0] in order else len(order), g[0], int(g[1] or 0)))
    ratio_title = f" {reference} / {subject} |" if reference and reference != subject else ""
    error_title = (f" {subject} vs {reference} max m | meets the scene's answer |"
                   if accuracy and ratio_title else "")
    out.append("| scene | bodies | " + " | ".join(f"{e} ms/step" for e in engines) + " |" + ratio_title +
               error_title + f" {subject} ns/body/step |")
    out.append("|---|---:|" + "---:|" * len(engines) + ("---:|" if ratio_title else "") +
               ("---:|---|" if error_title else "") + "---:|")
    for family, size in groups:
        row = {e: runs.get((family, e, size)) for e in engines}
        any_run = next(b for b in row.values() if b)
        bodies = int(any_run.get("bodies", 0))
        t = {e: (ms(b) if b else None) for e, b in row.items()}
        cells = []
        for e in engines:
            degraded = row[e].get("degraded", 0) if row[e] else 0
            cells.append(fmt_ms(t[e]) + (f" ({degraded:.0%} of steps cut short)" if degraded else ""))
        ratio = ""
        if ratio_title:
            ratio = (f" {t[reference] / t[subject]:.1f}x |" if t.get(reference) and t.get(subject)
                     else " - |")
        if error_title:
            error, answer = error_cells(accuracy, (family, size), subject)
            ratio += f" {error} | {answer} |"
        sub = row.get(subject)
        per_body = f"{sub['per_body'] * 1e9:.0f}" if sub and "per_body" in sub else "-"
        scene, key, sets = recipes.get(family, (family, None, []))
        label = f"`{scene}`" + "".join(f" {kv}" for kv in sets)
        if key and size:
            label += f" {key}={int(size):,}"
        out.append(f"| {label} | {bodies:,} | " + " | ".join(cells) + " |" + ratio + f" {per_body} |")

    piles = sorted((int(size), b) for (family, engine, size), b in runs.items()
                   if family == "random_pile" and engine == subject and size)
    if piles:
        out.append("")
        out.append(f"Scaling of `{subject}` on `random_pile` (time per body per step):")
        out.append("")
        out.append("| bodies | ns/body/step | relative to 10k |")
        out.append("|---:|---:|---:|")
        base = next((b["per_body"] for n, b in piles if n == 10_000), None)
        for n, b in piles:
            rel = f"{b['per_body'] / base:.2f}x" if base else "-"
            out.append(f"| {n:,} | {b['per_body'] * 1e9:.0f} | {rel} |")

    bare, full = runs.get(("harness", "pyramid100", "0")), runs.get(("harness", "pyramid100", "1"))
    if bare and full:
        out.append("")
        out.append(f"Harness cost on `pyramid` base=100: a bare `{subject}` step {ms(bare):.3f} ms; step plus "
                   f"reading the state back and computing every metric {ms(full):.3f} ms "
                   f"({ms(full) / ms(bare):.2f}x).")

    cpus = context.get("num_cpus", "?")
    mhz = context.get("mhz_per_cpu", "?")
    out.append("")
    out.append(f"Measured {context.get('date', '?')} on {cpus} CPUs at {mhz} MHz, "
               f"one benchmark at a time; ratios are from the same run.")
    return "\n".join(out)


def replace_in_readme(path, text):
    with open(path, encoding="utf-8") as f:
        readme = f.read()
    pattern = re.compile(re.escape(BEGIN) + r".*?" + re.escape(END), re.S)
    if not pattern.search(readme):
        sys.exit(f"bench_table.py: {path} has no {BEGIN} ... {END} markers")
    readme = pattern.sub(lambda _: f"{BEGIN}\n{text}\n{END}", readme)
    with open(path, "w", encoding="utf-8") as f:
        f.write(readme)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("json", help="chainbench_bench --benchmark_out file")
    parser.add_argument("--readme", help="README to update between the results markers")
    parser.add_argument("--accuracy", metavar="CHAINBENCH",
                        help="run each row's scene with this chainbench to add its error")
    parser.add_argument("--runs", default="results/bench_runs",
                        help="where the accuracy runs' JSON goes (default results/bench_runs)")
    args = parser.parse_args()
    try:
        context, runs = load(args.json)
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"bench_table.py: cannot read {args.json}: {e}")
    if not runs:
        sys.exit(f"bench_table.py: {args.json} holds no benchmark results")
    accuracy = accuracy_runs(context, runs, args.accuracy, args.runs) if args.accuracy else {}
    text = tables(context, runs, accuracy)
    print(text)
    if args.readme:
        replace_in_readme(args.readme, text)


if __name__ == "__main__":
    main()
