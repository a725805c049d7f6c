#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Renders a chainbench.stress/1 JSON as Markdown: a grid of verdicts (case x engine) and, for each
engine, the cases where it is not ok and why. With --doc it rewrites docs/stress.md's stress results
between the <!-- stress:begin --> and <!-- stress:end --> markers; otherwise it prints them.

    scripts/stress_table.py results/stress.json [--doc docs/stress.md]
"""
import argparse
import json
import sys

BEGIN, END = "<!-- stress:begin -->", "<!-- stress:end -->"


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"stress_table.py: {path}: cannot read a stress JSON: {e}")
    if not isinstance(data, dict) or data.get("schema") != "chainbench.stress/1":
        sys.exit(f"stress_table.py: {path}: not a chainbench.stress/1 JSON")
    return data


def cell(case):
    verdict = case["verdict"]
    text = verdict if verdict in ("ok", "budget") else f"**{verdict}**"
    return text + (" (known)" if case.get("known_failure") else "")


def grid(stress):
    """The verdict of every case in every engine, one row per case."""
    engines, rows = [], {}
    for c in stress["cases"]:
        if c["label"] not in engines:
            engines.append(c["label"])
        rows.setdefault(c["case"], {})[c["label"]] = c
    lines = ["| case | " + " | ".join(f"`{e}`" for e in engines) + " |",
             "|---|" + "---|" * len(engines)]
    for case, by_engine in rows.items():
        lines.append(f"| {case} | " + " | ".join(cell(by_engine[e]) if e in by_engine else "-"
                                                  for e in engines) + " |")
    return lines


def breaks(stress):
    """Per engine, the cases it is not ok on, with what each verdict rests on."""
    lines, engines = [], []
    for c in stress["cases"]:
        if c["label"] not in engines:
            engines.append(c["label"])
    for engine in engines:
        bad = [c for c in stress["cases"] if c["label"] == engine and c["verdict"] != "ok"]
        total = sum(1 for c in stress["cases"] if c["label"] == engine)
        if not bad:
            lines.append(f"- `{engine}`: ok on all {total} cases.")
            continue
        lines.append(f"- `{engine}`: ok on {total - len(bad)} of {total} cases; elsewhere:")
        for c in bad:
            known = f" (known failure: {c['known_failure']})" if c.get("known_failure") else ""
            lines.append(f"  - {c['case']}: {c['verdict']}, {c['detail']}{known}")
    return lines


def render(stress):
    return "\n".join(grid(stress) + [""] + breaks(stress))


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0].replace("\n", " "),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("stress_json")
    parser.add_argument("--doc", "--readme", dest="doc",
                        help="rewrite this file's stress results in place (docs/stress.md)")
    args = parser.parse_args()
    text = render(load(args.stress_json))
    if not args.doc:
        print(text)
        return
    with open(args.doc, encoding="utf-8") as f:
        readme = f.read()
    if BEGIN not in readme or END not in readme:
        sys.exit(f"stress_table.py: {args.doc} has no {BEGIN} ... {END} markers")
    head, rest = readme.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    with open(args.doc, "w", encoding="utf-8") as f:
        f.write(head + BEGIN + "\n" + text + "\n" + END + tail)
    print(f"stress_table.py: rewrote the stress results in {args.doc}")


if __name__ == "__main__":
    main()
