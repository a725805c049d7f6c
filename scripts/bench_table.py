#!/usr/bin/env python3
"""Turns chainbench_bench's JSON (--benchmark_format=json) into the README's results tables.

    scripts/bench_table.py results/bench.json                 print the tables
    scripts/bench_table.py results/bench.json --readme README.md
                                                              also replace the text between
                                                              <!-- results:begin --> and
                                                              <!-- results:end --> in README.md
"""
import argparse
import json
import re
import sys

# Row order, and the --set key that each scaled family's size is.
FAMILIES = {"stack": None, "pyramid": "base", "many_pyramids": None, "push_row": "n", "random_pile": "n"}
BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"


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


def ms(b):
    """Real time per iteration in milliseconds, whatever unit the benchmark used."""
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
    return b["real_time"] * scale


def fmt_ms(v):
    return "-" if v is None else (f"{v:.3f}" if v < 10 else f"{v:.1f}")


def tables(context, runs):
    """The results table (a column per engine label, in the order the benchmarks ran them), the
    ratio of the reference to the subject (the engines chainbench_bench names in its context),
    the subject's scaling on random_pile and the harness' cost."""
    out = []
    order = list(FAMILIES)
    engines = list(dict.fromkeys(engine for family, engine, size in runs if family != "harness"))
    subject = context.get("chainbench_subject", engines[0] if engines else "")
    reference = context.get("chainbench_reference", "")
    groups = sorted({(family, size) for family, engine, size in runs if family != "harness"},
                    key=lambda g: (order.index(g[0]) if g[0] in order else len(order), g[0], int(g[1] or 0)))
    ratio_title = f" {reference} / {subject} |" if reference and reference != subject else ""
    out.append("| scene | bodies | " + " | ".join(f"{e} ms/step" for e in engines) + " |" + ratio_title +
               f" {subject} ns/body/step |")
    out.append("|---|---:|" + "---:|" * len(engines) + ("---:|" if ratio_title else "") + "---:|")
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
        sub = row.get(subject)
        per_body = f"{sub['per_body'] * 1e9:.0f}" if sub and "per_body" in sub else "-"
        key = FAMILIES.get(family)
        label = f"`{family}` {key}={int(size):,}" if key and size else f"`{family}`"
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
    args = parser.parse_args()
    try:
        context, runs = load(args.json)
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"bench_table.py: cannot read {args.json}: {e}")
    if not runs:
        sys.exit(f"bench_table.py: {args.json} holds no benchmark results")
    text = tables(context, runs)
    print(text)
    if args.readme:
        replace_in_readme(args.readme, text)


if __name__ == "__main__":
    main()
