#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Turns chainbench_bench's JSON (--benchmark_format=json) into the results tables.

    scripts/bench_table.py results/bench.json                 print the full tables
    scripts/bench_table.py results/bench.json --readme README.md --results docs/results.md
                                                              also write the compact headline
                                                              table between README.md's
                                                              <!-- results:begin --> and
                                                              <!-- results:end --> markers, and
                                                              the full tables between the same
                                                              markers in docs/results.md (a new
                                                              file is written whole)
    scripts/bench_table.py results/bench.json --accuracy build/bin/chainbench --runs DIR
                                                              first run each row's scene in every
                                                              engine it was timed in (chainbench
                                                              run), so that each row shows its
                                                              error beside its speed
    scripts/bench_table.py results/bench.json --reuse-runs --runs DIR
                                                              read those runs as an earlier
                                                              --accuracy left them in DIR instead
                                                              (with --accuracy too: run only the
                                                              ones DIR lacks)

A speed claim never stands without its accuracy: with accuracy runs, the headline gives every
engine's error against the moving scenes' stated answers beside its speed, each row of the results
table the subject's final-position error against the reference and which engines meet the answer,
and the compact table marks every engine that misses a row's answer.

The full tables, in order: the summary (the subject against every engine, sleeping on and off, and
every row where it loses), the headline (the moving scenes, where every engine works each step), the
results (time per step of every engine on every row), the work and memory behind them (contacts
per step and heap held per body), the worst frame (each engine's median and slowest
step), the subject's scaling per family, the harness' cost, and an
adapter's cost: an engine through chainbench beside the same scene built by hand in its own API
(plain/FAMILY/ENGINE/SIZE rows, such as the box2d3 pyramid's). The compact table (the README's) is
the moving scenes and the resting pyramid, the subject's time and how many times faster it steps
than each other engine, sleeping off and on.
"""
import argparse
import json
import os
import re
import subprocess
import sys

from .records import AccuracyRun, AccuracyStep, Loss

BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"
# An accuracy run takes the scene's own steps unless the engines' timed steps say that would take
# longer than this; then fewer steps (the row says how many).
ACCURACY_BUDGET_S = 20.0


# Benchmark name prefixes that are not a family's engine rows: the harness' cost and plain worlds.
EXTRA = ("harness", "plain")


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
        if parts[0] == "plain":  # plain/FAMILY/ENGINE/SIZE: keyed ("plain", FAMILY, "ENGINE/SIZE")
            size = f"{parts[2]}/{size}"
        if parts[0] == "harness":  # harness/FAMILY/SIZE/metrics:K: one entry per K
            flag = next((p for p in parts if p.startswith("metrics:")), None)
            if flag is None:
                continue
            size += "/" + flag[len("metrics:"):]
        runs[(parts[0], parts[1], size)] = b
    return data.get("context", {}), runs


def family_recipes(context):
    """{family: (scene, [size keys], [KEY=VALUE...])}, as chainbench_bench records them."""
    out = {}
    for key, value in context.items():
        if key.startswith("chainbench_family_"):
            scene, keys, *sets = value.split()
            out[key[len("chainbench_family_"):]] = (scene, [] if keys == "-" else keys.split(","), sets)
    return out


def listed(context, key):
    """A comma-separated context entry as a list ("a,b" -> ["a", "b"])."""
    return [item for item in context.get(key, "").split(",") if item]


def counterpart(context, subject, engine):
    """The subject's row `engine` is set against, like against like: the subject as it is for an
    engine that skips what rests (chainbench_sleeping: sleep=1), the subject solving every step
    (chainbench_subject_solving: skip_rest=0) for one that solves every body every step, and the
    subject itself for that solving row (what skipping buys)."""
    solving = context.get("chainbench_subject_solving", "")
    if not solving or engine == solving or engine in listed(context, "chainbench_sleeping"):
        return subject
    return solving


def accuracy_plan(context, runs, exe, out_dir):
    """Every (family, size) row's accuracy run: [AccuracyStep]. Steps are capped so that each run stays within ACCURACY_BUDGET_S by the
    benchmark's own times; a row whose reference was not timed has no run."""
    recipes = family_recipes(context)
    reference = context.get("chainbench_reference", "")
    plan = []
    for family, size in sorted({(f, size) for f, e, size in runs if f in recipes}):
        scene, keys, sets = recipes[family]
        engines = [e for (f, e, sz) in runs if f == family and sz == size]
        if reference and reference not in engines:
            continue  # no reference timed on this row: nothing to measure the error against
        per_step_s = sum(ms(runs[(family, e, size)]) for e in engines) / 1e3
        args = [exe, "run", "--scene", scene, "--metrics", "none",
                "--engines", ",".join(e for e in engines if e != reference), "--reference", reference]
        for kv in sets + ([f"{key}={size}" for key in keys] if size else []):
            args += ["--set", kv]
        # A family timed over a window of its run (a moving scene) is judged on that very run.
        steps = None
        if not any(kv.startswith("steps=") for kv in sets) and per_step_s * 300 > ACCURACY_BUDGET_S:
            steps = max(30, int(ACCURACY_BUDGET_S / per_step_s))
            args += ["--steps", str(steps)]
        path = os.path.join(out_dir, f"{family}_{size or 'default'}.json")
        args += ["--json", path]
        plan.append(AccuracyStep(family, size, args, path, steps))
    return plan


def accuracy_runs(context, runs, exe, out_dir, reuse=False):
    """Runs every (family, size) row's scene once in each engine it was timed in, against the
    reference, and returns {(family, size): AccuracyRun}. With reuse, a run whose
    JSON is already in out_dir is read as it is (without exe, a missing one is an error)."""
    os.makedirs(out_dir, exist_ok=True)
    results = {}
    plan = accuracy_plan(context, runs, exe or "chainbench", out_dir)
    for n, step in enumerate(plan, 1):
        group, args, path, steps = step.group, step.args, step.path, step.steps
        if not (reuse and os.path.exists(path)):
            if not exe:
                sys.exit(f"bench_table.py: {path}: no stored accuracy run of {group[0]} {group[1]} "
                         "(run with --accuracy CHAINBENCH to make it)")
            print(f"bench_table.py: accuracy {n}/{len(plan)}: {group[0]} {group[1]}", file=sys.stderr)
            done = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            if done.returncode not in (0, 3):
                sys.exit(f"bench_table.py: {' '.join(args)} failed:\n{done.stderr}")
        with open(path, encoding="utf-8") as f:
            run = json.load(f)
        if reuse:
            # A stored run stands for this row only if it ran the engines timed on it; its own
            # step count is the one its errors were measured over.
            labels = {r.get("label") for r in run.get("runs", []) + [run.get("reference_run", {})]}
            wanted = args[args.index("--engines") + 1].split(",") + [args[args.index("--reference") + 1]]
            missing = [e for e in wanted if e and e not in labels]
            if missing:
                sys.exit(f"bench_table.py: {path}: the stored run has no {', '.join(missing)} "
                         "(run with --accuracy CHAINBENCH to make it again)")
            if steps is not None:
                steps = run.get("scene", {}).get("steps", steps)
        results[group] = AccuracyRun(run, steps)
    return results


def ms(b):
    """Real time per iteration in milliseconds, whatever unit the benchmark used."""
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
    return b["real_time"] * scale


def fmt_ms(v):
    """Three decimals, or two significant digits below a microsecond-scale step: 0.00012."""
    if v is None:
        return "-"
    return f"{v:.2g}" if v < 0.001 else (f"{v:.3f}" if v < 10 else f"{v:.1f}")


def fmt_count(v):
    return "-" if v is None else (f"{v:,.0f}" if v >= 10 else f"{v:.2g}")


def row_label(recipes, family, size):
    """`scene` and the settings its family uses, the run length aside: `random_pile` n=1,000."""
    scene, keys, sets = recipes.get(family, (family, [], []))
    label = f"`{scene}`" + "".join(f" {kv}" for kv in sets if not kv.startswith("steps="))
    if keys and size:
        label += " " + "=".join(keys) + f"={int(size):,}"
    return label


def everyone(run):
    """Every engine's run in an accuracy run's JSON, the reference's included."""
    return run["runs"] + ([run["reference_run"]] if run.get("reference_run") else [])


def error_cells(accuracy, group, subject):
    """The subject's final-position error against the reference, and who meets the answer."""
    if group not in accuracy:
        return "-", "-"
    run, steps = accuracy[group].run, accuracy[group].steps
    label_of = {r["engine"]: r["label"] for r in run["runs"]}
    error = "-"
    for c in run.get("comparison", []):
        if label_of.get(c["engine"]) == subject:
            error = f"{c['final_position_error']['max']:.2g}"
    met = [r["label"] for r in everyone(run) if r.get("expect") and r["expect"].get("pass")]
    answer = ", ".join(f"`{m}`" for m in met) if met else "none"
    if steps:
        error += f" ({steps} steps)"
    return error, answer


def answer_error(accuracy, group, engine):
    """An engine's largest error against the scene's stated answer, and whether it meets it:
    "0.017 m", "0.07 m, misses", or "" without an accuracy run."""
    if group not in accuracy:
        return ""
    for r in everyone(accuracy[group].run):
        if r["label"] == engine and r.get("expect"):
            return f"{r['expect']['max_error']:.2g} m" + ("" if r["expect"]["pass"] else ", misses")
    return ""


def ordered(runs):
    """Families in the order the benchmark ran them, engines likewise, and the (family, size)
    rows in family order, then by size."""
    timed = [(family, engine, size) for family, engine, size in runs if family not in EXTRA]
    order = list(dict.fromkeys(family for family, engine, size in timed))
    engines = list(dict.fromkeys(engine for family, engine, size in timed))
    groups = sorted({(family, size) for family, engine, size in timed},
                    key=lambda g: (order.index(g[0]), int(g[1] or 0)))
    return engines, groups


def headline(context, runs, accuracy, subject):
    """The moving scenes, each at the largest size every engine ran: the subject's time, and how
    many times faster it steps than each other engine, each with its error beside it."""
    recipes = family_recipes(context)
    engines, groups = ordered(runs)
    others = [e for e in engines if e != subject]
    rows = []
    for family in listed(context, "chainbench_moving"):
        sizes = [size for f, size in groups
                 if f == family and all((f, e, size) in runs for e in engines)]
        if sizes and (family, subject, sizes[-1]) in runs:
            rows.append((family, sizes[-1]))
    if not rows:
        return []
    with_error = bool(accuracy)
    out = [f"The moving scenes, where every engine works each step and every engine is timed over "
           f"the same steps: how many times faster `{subject}` steps than each engine"
           + (", each with its largest error against the scene's stated answer" if with_error else "")
           + ".", "",
           f"| moving scene | bodies | `{subject}` ms/step |" + (" error |" if with_error else "")
           + "".join(f" `{e}` |" for e in others),
           "|---|---:|---:|" + ("---:|" if with_error else "") + "---|" * len(others)]
    for family, size in rows:
        sub = runs[(family, subject, size)]
        cells = []
        for e in others:
            error = answer_error(accuracy, (family, size), e)
            against = runs.get((family, counterpart(context, subject, e), size), sub)
            cells.append(f"{ms(runs[(family, e, size)]) / ms(against):.1f}x" + (f" ({error})" if error else ""))
        mine = f" {answer_error(accuracy, (family, size), subject) or '-'} |" if with_error else ""
        out.append(f"| {row_label(recipes, family, size)} | {int(sub.get('bodies', 0)):,} | "
                   f"{fmt_ms(ms(sub))} |{mine} " + " | ".join(cells) + " |")
    return out + [""]


MARKS = ("†", "‡", "§", "¶")


def caveat_marks(context, engines):
    """{label: mark} for the engines whose times carry a caveat (chainbench_caveat_NAME in the
    benchmark's context), and the notes that explain the marks."""
    notes, marks = {}, {}
    for e in engines:
        text = context.get(f"chainbench_caveat_{e.partition(':')[0]}")
        if text:
            marks[e] = notes.setdefault(text, MARKS[len(notes) % len(MARKS)])
    return marks, [f"{mark} {text}." for text, mark in notes.items()]


def times_faster(v):
    """"0.004x", "0.5x", "25.0x": two significant digits below 0.1, else one decimal."""
    return f"{v:.2g}x" if v < 0.1 else f"{v:.1f}x"


def times(b):
    return f"{fmt_ms(b[0])} against {fmt_ms(b[1])} ms"


def losses(context, runs, subject, groups, others):
    """[Loss]: every row where an engine steps faster than the subject's row it is set against
    (counterpart), the largest loss first."""
    return sorted((Loss(ms(runs[(f, counterpart(context, subject, e), sz)]) / ms(runs[(f, e, sz)]),
                        e, f, sz)
                   for f, sz in groups for e in others
                   if (f, e, sz) in runs and (f, counterpart(context, subject, e), sz) in runs
                   and ms(runs[(f, e, sz)]) < ms(runs[(f, counterpart(context, subject, e), sz)])),
                  reverse=True)


def summary(context, runs, subject):
    """The sentences that open the results: on the rows both ran, how many times faster the
    subject steps than each engine (sleeping on and off alike, as the labels say), on the moving
    scenes and the others, and every row where an engine steps faster than the subject, in words."""
    recipes = family_recipes(context)
    engines, groups = ordered(runs)
    others = [e for e in engines if e != subject]
    if subject not in engines or not others:
        return []
    moving = set(listed(context, "chainbench_moving"))
    marks, notes = caveat_marks(context, others)

    def span(rows):
        parts = []
        for e in others:
            m = counterpart(context, subject, e)
            r = sorted((ms(runs[(f, e, sz)]) / ms(runs[(f, m, sz)]), f, sz) for f, sz in rows
                       if (f, e, sz) in runs and (f, m, sz) in runs)
            if not r:
                continue
            (low, lf, ls), (high, hf, hs) = r[0], r[-1]
            mid = r[len(r) // 2][0] if len(r) % 2 else (r[len(r) // 2 - 1][0] + r[len(r) // 2][0]) / 2
            parts.append(f"`{e}`{marks.get(e, '')} {times_faster(low)} ({row_label(recipes, lf, ls)}) "
                         f"to {times_faster(high)} ({row_label(recipes, hf, hs)}), median "
                         f"{times_faster(mid)}" if len(r) > 1 else
                         f"`{e}`{marks.get(e, '')} {times_faster(low)} ({row_label(recipes, lf, ls)})")
        return "; ".join(parts)

    solving = context.get("chainbench_subject_solving", "")
    out = [f"**`{subject}` against every engine, with sleeping off and on.** How many times faster "
           f"`{subject}` steps, on the rows of the table below that both ran"
           + (f" (like against like: an engine that sleeps against `{subject}`, which leaves "
              f"what rests out; one that solves every body every step against `{solving}`, "
              "which does too)" if solving else "")]
    moving_rows = [g for g in groups if g[0] in moving]
    other_rows = [g for g in groups if g[0] not in moving]
    if moving_rows and other_rows:
        out[0] += (f": on the moving scenes, {span(moving_rows)}; on the scenes that come to rest "
                   f"or are pushed, {span(other_rows)}.")
    else:
        out[0] += f": {span(groups)}."
    lost = losses(context, runs, subject, groups, others)
    if lost:
        def loss(faster, e, f, sz):
            m = counterpart(context, subject, e)
            return (f"`{e}`{marks.get(e, '')} steps {row_label(recipes, f, sz)} {faster:.1f}x faster"
                    + (f" than `{m}`" if m != subject else "")
                    + f" ({times((ms(runs[(f, e, sz)]), ms(runs[(f, m, sz)])))} per step)")

        out[0] += (f" **Where `{subject}` loses:** " + "; ".join(
            loss(x.faster, x.engine, x.family, x.size) for x in lost) + ".")
    else:
        out[0] += f" No engine steps any row faster than `{subject}`."
    if notes:
        out[0] += " " + " ".join(notes)
    return out + [""]


def results_table(context, runs, accuracy, subject, reference):
    """Time per step of every engine on every row, the reference over the subject, the subject's
    error and who meets the answer (with accuracy runs), and the subject's time per body."""
    recipes = family_recipes(context)
    engines, groups = ordered(runs)
    if not groups:  # a run of the harness rows alone, say
        return []
    against = counterpart(context, subject, reference)
    ratio_title = f" {reference} / {against} |" if reference and reference != subject else ""
    error_title = (f" {subject} vs {reference} max m | meets the scene's answer |"
                   if accuracy and ratio_title else "")
    out = ["| scene | bodies | " + " | ".join(f"{e} ms/step" for e in engines) + " |" + ratio_title +
           error_title + f" {subject} ns/body/step |",
           "|---|---:|" + "---:|" * len(engines) + ("---:|" if ratio_title else "") +
           ("---:|---|" if error_title else "") + "---:|"]
    for family, size in groups:
        row = {e: runs.get((family, e, size)) for e in engines}
        bodies = int(next(b for b in row.values() if b).get("bodies", 0))
        t = {e: (ms(b) if b else None) for e, b in row.items()}
        cells = []
        for e in engines:
            degraded = row[e].get("degraded", 0) if row[e] else 0
            cells.append(fmt_ms(t[e]) + (f" ({degraded:.0%} of steps cut short)" if degraded else ""))
        ratio = ""
        if ratio_title:
            ratio = (f" {t[reference] / t[against]:.1f}x |" if t.get(reference) and t.get(against)
                     else " - |")
        if error_title:
            error, answer = error_cells(accuracy, (family, size), subject)
            ratio += f" {error} | {answer} |"
        sub = row.get(subject)
        per_body = f"{sub['per_body'] * 1e9:.0f}" if sub and "per_body" in sub else "-"
        out.append(f"| {row_label(recipes, family, size)} | {bodies:,} | " + " | ".join(cells) + " |"
                   + ratio + f" {per_body} |")
    return out


def work_table(context, runs):
    """Per row and engine: contacts per step (each engine's own count) and heap held per body."""
    recipes = family_recipes(context)
    engines, groups = ordered(runs)
    if not any("bytes_per_body" in b or "contacts" in b for b in runs.values()):
        return []
    meanings = [f"`{name[len('chainbench_contacts_'):]}`: {text}" for name, text in context.items()
                if name.startswith("chainbench_contacts_")]
    counted = f" ({'; '.join(meanings)})" if meanings else ""
    out = ["", f"Contacts per step, as each engine counts them{counted}, and the heap a world holds per "
           "body once built and warmed up (bytes, from the allocator's books):", "",
           "| scene | " + " | ".join(f"{e} contacts · B/body" for e in engines) + " |",
           "|---|" + "---:|" * len(engines)]
    for family, size in groups:
        cells = []
        for e in engines:
            b = runs.get((family, e, size))
            if not b:
                cells.append("-")
                continue
            held = b.get("bytes_per_body")
            cells.append(f"{fmt_count(b.get('contacts'))} · " + ("-" if held is None else f"{held:,.0f}"))
        out.append(f"| {row_label(recipes, family, size)} | " + " | ".join(cells) + " |")
    return out


def worst_frame_table(context, runs):
    """Per row and engine: the median timed step and the slowest, ms. A game budgets for the
    slowest frame; with repetitions, each figure is the median over them."""
    recipes = family_recipes(context)
    engines, groups = ordered(runs)
    if not any("step_ms_max" in b for b in runs.values()):
        return []
    out = ["", "The worst frame: each engine's median timed step and its slowest, ms (median · max; "
           "on the moving scenes over the same 60 steps, on the others over every step timed):", "",
           "| scene | " + " | ".join(f"{e} median · max" for e in engines) + " |",
           "|---|" + "---:|" * len(engines)]
    for family, size in groups:
        cells = []
        for e in engines:
            b = runs.get((family, e, size))
            if not b or "step_ms_max" not in b:
                cells.append("-")
                continue
            cells.append(f"{fmt_ms(b.get('step_ms_median'))} · {fmt_ms(b['step_ms_max'])}")
        out.append(f"| {row_label(recipes, family, size)} | " + " | ".join(cells) + " |")
    return out


def scaling_tables(context, runs, subject):
    """Per scaling family: the subject's time per body per step at each size, and its ratio to the
    family's base size (about 5-10k bodies)."""
    recipes = family_recipes(context)
    out = []
    for entry in listed(context, "chainbench_scaling"):
        family, base = entry.split(":")
        points = sorted((int(size), b) for (f, e, size), b in runs.items()
                        if f == family and e == subject and size and "per_body" in b)
        if not points:
            continue
        scene, keys, sets = recipes.get(family, (family, [], []))
        key = "=".join(keys) or "size"
        base_run = next((b for size, b in points if size == int(base)), None)
        fixed = "".join(f" {kv}" for kv in sets if not kv.startswith("steps="))
        out += ["", f"Scaling of `{subject}` on `{scene}`{fixed} (time per body per step):", "",
                f"| {key} | bodies | ns/body/step | relative to {key}={int(base):,} |",
                "|---:|---:|---:|---:|"]
        for size, b in points:
            rel = f"{b['per_body'] / base_run['per_body']:.2f}x" if base_run else "-"
            out.append(f"| {size:,} | {int(b.get('bodies', 0)):,} | {b['per_body'] * 1e9:.0f} | {rel} |")
    return out


def harness_table(context, runs, subject):
    """Per family and size the subject was timed at: a bare step, a step with the state read
    back and every metric of `chainbench run` computed after it, and their ratio; on moving
    scenes also the least any such harness adds (metrics:2: reading the state back and judging
    the pairs with a moved body, nothing else)."""
    recipes = family_recipes(context)
    # Families in the order the benchmark ran them (their own rows come before the harness').
    order = list(dict.fromkeys(e if f == "harness" else f for f, e, _ in runs))
    rows = sorted({(family, key.split("/")[0]) for f, family, key in runs if f == "harness"},
                  key=lambda r: (order.index(r[0]), int(r[1] or 0)))
    out = []
    for family, size in rows:
        bare, full = runs.get(("harness", family, f"{size}/0")), runs.get(("harness", family, f"{size}/1"))
        if not bare or not full:
            continue
        least = runs.get(("harness", family, f"{size}/2"))
        floor = f"{ms(least) / ms(bare):.2f}x" if least else "-"
        out.append(f"| {row_label(recipes, family, size)} | {int(bare.get('bodies', 0)):,} | {fmt_ms(ms(bare))} | "
                   f"{fmt_ms(ms(full))} | {ms(full) / ms(bare):.2f}x | {floor} |")
    if not out:
        return []
    return ["", f"Harness cost: a bare `{subject}` step, and a step plus reading the state back and "
            "computing every metric of `chainbench run` after it (`harness/FAMILY/SIZE/metrics:0|1`); "
            "on moving scenes, \"least ratio\" is that of a step plus only reading the state back "
            "and judging the pairs with a moved body (`metrics:2`): the least that any harness "
            "judging them every step costs:",
            "", "| scene | bodies | bare ms/step | with metrics ms/step | ratio | least ratio |",
            "|---|---:|---:|---:|---:|---:|"] + out


def plain_table(context, runs):
    """Per plain/FAMILY/ENGINE/SIZE row (a world built by hand in the engine's own API): the
    engine's time through its adapter beside it, and their ratio."""
    recipes = family_recipes(context)
    out = []
    for (f, family, size), plain in runs.items():
        if f != "plain" or "/" not in size:
            continue
        engine, size = size.split("/", 1)
        adapted = runs.get((family, engine, size))
        if not adapted:
            continue
        out.append(f"| {row_label(recipes, family, size)} | `{engine}` | {fmt_ms(ms(adapted))} | "
                   f"{fmt_ms(ms(plain))} | {ms(adapted) / ms(plain):.2f}x |")
    if not out:
        return []
    return ["", "Adapter cost: the engine through chainbench's adapter, and the same scene as a world "
            "built by hand in the engine's own API at the same settings (`plain/FAMILY/ENGINE/SIZE`):",
            "", "| scene | engine | adapter ms/step | plain world ms/step | ratio |",
            "|---|---|---:|---:|---:|"] + out


def churn_table(context, runs):
    """Per engine and size: a step of the churn family (bodies created and destroyed each step)
    against the same world with nothing coming or going (churn_base), and their ratio."""
    recipes = family_recipes(context)
    engines, _ = ordered(runs)
    out = []
    churn_rows = sorted(((e, int(size or 0), size, b) for (f, e, size), b in runs.items() if f == "churn"),
                        key=lambda row: row[1])
    for engine in engines:
        for e, _, size, churning in churn_rows:
            still = runs.get(("churn_base", engine, size))
            if e != engine or not still:
                continue
            out.append(f"| {row_label(recipes, 'churn', size)} | `{engine}` | {fmt_ms(ms(churning))} | "
                       f"{fmt_ms(ms(still))} | {ms(churning) / ms(still):.2f}x |")
    if not out:
        return []
    return ["", "Bodies coming and going: a wall at rest while one box a step is created above it and "
            "destroyed the next (`churn`), against the same wall with nothing coming or going "
            "(`churn_base`), timed over the same 60 steps:",
            "", "| scene | engine | churning ms/step | still ms/step | ratio |",
            "|---|---|---:|---:|---:|"] + out


# The compact table's rows beside the moving scenes: families that come to rest, each at the largest
# size every engine ran; and its columns, first of all (the others follow in the benchmark's order).
COMPACT_RESTING = ("pyramid",)
COMPACT_FIRST = ("box2d3", "box2d", "chipmunk")


def compact_table(context, runs, accuracy=None, results_link="docs/results.md"):
    """The README's headline: the moving scenes and the resting pyramid, each at the largest size
    every engine ran; the subject's time per step (and its error against the scene's stated
    answer, with accuracy runs), and how many times faster it steps than each other engine with
    sleeping off and on, like against like; then where the subject loses, and when and where it
    was measured. The full tables are at results_link."""
    accuracy = accuracy or {}
    recipes = family_recipes(context)
    engines, groups = ordered(runs)
    subject = context.get("chainbench_subject", engines[0] if engines else "")
    if subject not in engines:
        return ""
    solving = context.get("chainbench_subject_solving", "")
    moving = listed(context, "chainbench_moving")
    rows = []
    for family in moving + [f for f in COMPACT_RESTING if f not in moving]:
        sizes = [size for f, size in groups
                 if f == family and all((f, e, size) in runs for e in engines)]
        if sizes:
            rows.append((family, sizes[-1]))
    if not rows:
        return ""
    # One column per other engine, its sleeping setting (NAME:sleep=1) beside it in the same cell;
    # the subject's own settings (chain:variant=..., chain:skip_rest=0) are in the full tables.
    bases = [e for e in engines if ":" not in e and e != subject]
    bases.sort(key=lambda e: COMPACT_FIRST.index(e) if e in COMPACT_FIRST else len(COMPACT_FIRST))
    sleeping = {e: f"{e}:sleep=1" if f"{e}:sleep=1" in engines else None for e in bases}
    compared = [e for e in engines if e.partition(":")[0] in bases]
    marks, notes = caveat_marks(context, compared)
    with_error = bool(accuracy)

    def misses(group, e):
        return with_error and answer_error(accuracy, group, e).endswith("misses")

    def ratio(family, size, e):
        against = runs.get((family, counterpart(context, subject, e), size))
        if not against or (family, e, size) not in runs:
            return "-"
        faster = ms(runs[(family, e, size)]) / ms(against)
        cell = f"{faster:,.0f}x" if faster >= 100 else times_faster(faster)
        return cell + (" (misses)" if misses((family, size), e) else "")

    solving_key = solving.partition(":")[2]
    like = (f", like against like (an engine that sleeps against `{subject}`, which leaves what rests "
            f"out; one that solves every body every step against `{solving}`, which does too)"
            if solving else "")
    out = [f"How many times faster `{subject}` steps than each engine, with sleeping off · on{like}, "
           "on the moving scenes and the resting pyramid, each at the largest size every engine ran"
           + ("; `(misses)`: that engine misses the scene's stated answer" if with_error else "")
           + f". Every row, engine and table: [{results_link}]({results_link}).", "",
           f"| scene | bodies | `{subject}` ms/step |" + (f" `{subject}` error |" if with_error else "")
           + "".join(f" vs `{e}`{marks.get(e, '')} (sleep off · on) |" if sleeping[e]
                     else f" vs `{e}`{marks.get(e, '')} |" for e in bases),
           "|---|---:|---:|" + ("---:|" if with_error else "") + "---|" * len(bases)]
    for family, size in rows:
        sub = runs[(family, subject, size)]
        mine = fmt_ms(ms(sub))
        if family not in moving and solving and (family, solving, size) in runs:
            mine += f" ({fmt_ms(ms(runs[(family, solving, size)]))} at `{solving_key}`)"
        error = f" {answer_error(accuracy, (family, size), subject) or '-'} |" if with_error else ""
        cells = [ratio(family, size, e) + (f" · {ratio(family, size, sleeping[e])}" if sleeping[e] else "")
                 for e in bases]
        out.append(f"| {row_label(recipes, family, size)} | {int(sub.get('bodies', 0)):,} | {mine} |"
                   f"{error} " + " | ".join(cells) + " |")
    lost = losses(context, runs, subject, groups, compared)
    timed = sum(1 for f, sz in groups for e in compared
                if (f, e, sz) in runs and (f, counterpart(context, subject, e), sz) in runs)
    out.append("")
    if lost:
        faster, e, f, sz = lost[0].faster, lost[0].engine, lost[0].family, lost[0].size
        m = counterpart(context, subject, e)
        out.append(f"Where `{subject}` loses: on {len(lost)} of the {timed} rows and engines set "
                   f"against it in the full tables; the most, `{e}`{marks.get(e, '')} steps "
                   f"{row_label(recipes, f, sz)} {faster:.1f}x faster "
                   f"({times((ms(runs[(f, e, sz)]), ms(runs[(f, m, sz)])))} per step).")
    else:
        out.append("No engine of this table steps any of its rows in the full tables faster than "
                   f"`{subject}`.")
    if notes:
        out[-1] += " " + " ".join(notes)
    out += ["", measured(context)]
    return "\n".join(out)


def measured(context):
    return (f"Measured {context.get('date', '?')} on {context.get('num_cpus', '?')} CPUs at "
            f"{context.get('mhz_per_cpu', '?')} MHz, one benchmark at a time; ratios are from the same run.")


def tables(context, runs, accuracy=None):
    """Every table, in the order the module docstring gives."""
    accuracy = accuracy or {}
    engines, _ = ordered(runs)
    subject = context.get("chainbench_subject", engines[0] if engines else "")
    reference = context.get("chainbench_reference", "")
    out = summary(context, runs, subject)
    out += headline(context, runs, accuracy, subject)
    out += results_table(context, runs, accuracy, subject, reference)
    out += work_table(context, runs)
    out += worst_frame_table(context, runs)
    out += scaling_tables(context, runs, subject)
    out += harness_table(context, runs, subject)
    out += plain_table(context, runs)
    out += churn_table(context, runs)
    out += ["", measured(context)]
    return "\n".join(out)


RESULTS_HEAD = """# Results: every benchmark table

Generated by `scripts/bench.sh` from `results/bench.json` (and the accuracy runs in
`results/bench_runs/`): `scripts/bench_table.py` rewrites what lies between the results markers on
every run and keeps the text around them. How the benchmark runs and what its rows and counters
are: [benchmarks.md](benchmarks.md). The README's headline table is the compact form of these.

"""


def replace_between_markers(path, text, new_file=None):
    """Rewrites what lies between the results markers of the file at path with text; a file that
    does not exist yet is written whole as new_file's head, the markers and text, when given."""
    if new_file is not None and not os.path.exists(path):
        document = f"{new_file}{BEGIN}\n{text}\n{END}\n"
    else:
        with open(path, encoding="utf-8") as f:
            document = f.read()
        pattern = re.compile(re.escape(BEGIN) + r".*?" + re.escape(END), re.S)
        if not pattern.search(document):
            sys.exit(f"bench_table.py: {path} has no {BEGIN} ... {END} markers")
        document = pattern.sub(lambda _: f"{BEGIN}\n{text}\n{END}", document)
    with open(path, "w", encoding="utf-8") as f:
        f.write(document)


def link_from(readme, results):
    """The results file's path as a link from the README's folder: docs/results.md."""
    folder = os.path.dirname(os.path.abspath(readme))
    return os.path.relpath(os.path.abspath(results), folder).replace(os.sep, "/")


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0].replace("\n", " "),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("json", help="chainbench_bench --benchmark_out file")
    parser.add_argument("--readme", help="README whose results markers get the compact headline table")
    parser.add_argument("--results", help="file whose results markers get the full tables "
                        "(docs/results.md; written whole when it does not exist)")
    parser.add_argument("--accuracy", metavar="CHAINBENCH",
                        help="run each row's scene with this chainbench to add its error")
    parser.add_argument("--runs", default="results/bench_runs",
                        help="where the accuracy runs' JSON goes (default results/bench_runs)")
    parser.add_argument("--reuse-runs", action="store_true",
                        help="read the accuracy runs already in --runs instead of running them again")
    args = parser.parse_args()
    try:
        context, runs = load(args.json)
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"bench_table.py: cannot read {args.json}: {e}")
    if not runs:
        sys.exit(f"bench_table.py: {args.json} holds no benchmark results")
    accuracy = (accuracy_runs(context, runs, args.accuracy, args.runs, reuse=args.reuse_runs)
                if args.accuracy or args.reuse_runs else {})
    text = tables(context, runs, accuracy)
    print(text)
    if args.results:
        replace_between_markers(args.results, text, new_file=RESULTS_HEAD)
    if args.readme:
        link = link_from(args.readme, args.results) if args.results else "docs/results.md"
        compact = compact_table(context, runs, accuracy, link)
        if not compact:
            sys.exit(f"bench_table.py: no headline for {args.readme}: no moving or resting row was "
                     "timed in every engine (its tables are left as they were)")
        replace_between_markers(args.readme, compact)


if __name__ == "__main__":
    main()
