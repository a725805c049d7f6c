# SPDX-License-Identifier: MIT
"""The conclusion that opens results/report.md, computed from the suite's results: which engine to
pick for what (speed, the scenes' stated right answers, where each breaks), each sentence with the
figures behind it. Engines are the labels chainbench wrote into its outputs; the engine under test
is the run marked "gate", nothing here knows an engine by name.
"""
import statistics


def all_runs(run):
    return run["runs"] + ([run["reference_run"]] if "reference_run" in run else [])


def fmt(value, digits=2):
    return "-" if value is None else f"{value:.{digits}g}"


def ratio(value):
    """"0.004x", "0.5x", "2.5x", "25x": two significant digits below 0.1, one decimal below 10."""
    if value < 0.1:
        return f"{value:.2g}x"
    return f"{value:.1f}x" if value < 10 else f"{value:.0f}x"


def plural(n, word):
    """"1 case", "2 cases"."""
    return f"{n} {word}" + ("" if n == 1 else "s")


def names(items, limit=4):
    """"`a`, `b` and 3 more" for a list of names."""
    shown = [f"`{n}`" for n in items[:limit]]
    return ", ".join(shown) + (f" and {len(items) - limit} more" if len(items) > limit else "")


MARKS = ("†", "‡", "§", "¶")


def caveats(runs):
    """{label: mark} for every engine whose runs carry a caveat, and the notes, one per caveat."""
    marks, notes = {}, {}
    for run in runs:
        for r in all_runs(run):
            if r.get("caveat"):
                mark = notes.setdefault(r["caveat"], MARKS[len(notes) % len(MARKS)])
                marks[r["label"]] = mark
    return marks, [f"{mark} {text}." for text, mark in notes.items()]


def moving(run):
    return run["scene"].get("family") == "moving"


def ratios_of(runs, labels, subject):
    """{label: [(its ms over the subject's, scene, its ms, the subject's ms)]}, over the scenes
    both ran."""
    out = {lb: [] for lb in labels if lb != subject}
    for run in runs:
        ms = {r["label"]: r["ms_per_step"]["median"] for r in all_runs(run)}
        for lb in out:
            if lb in ms and ms.get(subject):
                out[lb].append((ms[lb] / ms[subject], run["scene"]["name"], ms[lb], ms[subject]))
    return out


def ranges(ratios, marks):
    """"`b` 1.2x (`x`) to 9x (`y`), median 3x" for each engine."""
    parts = []
    for lb, values in ratios.items():
        if not values:
            continue
        low, high = min(values), max(values)
        if len(values) == 1:
            parts.append(f"`{lb}`{marks.get(lb, '')} {ratio(low[0])} (`{low[1]}`)")
            continue
        parts.append(f"`{lb}`{marks.get(lb, '')} {ratio(low[0])} (`{low[1]}`) to "
                     f"{ratio(high[0])} (`{high[1]}`), median "
                     f"{ratio(statistics.median(v for v, *_ in values))}")
    return "; ".join(parts)


def speed(runs, labels, subject):
    """The engine under test's time per step against each other engine's (sleeping or not, as
    the runs' labels say), on the resting and on the moving scenes, and where it loses."""
    fastest = {lb: 0 for lb in labels}
    for run in runs:
        ms = {r["label"]: r["ms_per_step"]["median"] for r in all_runs(run)}
        if ms:
            fastest[min(ms, key=ms.get)] += 1
    marks, notes = caveats(runs)
    top = max(fastest, key=fastest.get)
    text = (f"**Speed.** `{top}` takes the least time per step on {fastest[top]} of {len(runs)} "
            f"scenes. The others take, per step, this many times `{subject}`'s time")
    resting, motion = [r for r in runs if not moving(r)], [r for r in runs if moving(r)]
    if resting and motion:
        text += "." + "".join(
            f" {where}: {ranges(ratios_of(group, labels, subject), marks)}."
            for where, group in (("On the moving scene" + ("s" if len(motion) > 1 else "") +
                                  " (family `moving`, every body at work each step)", motion),
                                 (f"On the other {len(resting)}", resting)))
    else:
        text += f": {ranges(ratios_of(runs, labels, subject), marks)}."
    if notes:
        text += " " + " ".join(notes)
    return fastest, text


def losses(runs, labels, subject):
    """Every scene on which an engine steps faster than the engine under test, in as many
    words; the worst first."""
    marks, _ = caveats(runs)
    lost = sorted(((1 / v, lb, name, their, mine)
                   for lb, values in ratios_of(runs, labels, subject).items()
                   for v, name, their, mine in values if v < 1), reverse=True)
    if not lost:
        return (f"**Where `{subject}` loses.** Nowhere here: no engine steps any of these "
                f"scenes faster.")
    by_engine = {}
    for faster, lb, name, their, mine in lost:
        by_engine.setdefault(lb, []).append(
            f"`{name}` {ratio(faster)} faster ({fmt(their)} against {fmt(mine)} ms per step)")
    return (f"**Where `{subject}` loses.** " + "; ".join(
        f"`{lb}`{marks.get(lb, '')} steps " + names_of(parts) for lb, parts in by_engine.items())
        + ".")


def names_of(parts, limit=4):
    """"a, b and c", at most `limit` of them, then how many more."""
    shown = parts[:limit]
    more = len(parts) - len(shown)
    text = ", ".join(shown[:-1]) + (" and " if len(shown) > 1 else "") + shown[-1]
    return text + (f", and {more} more scenes" if more else "")


def accuracy(runs, labels):
    """Per engine, the scenes whose stated right answer it meets, and its largest miss."""
    table = {}
    for lb in labels:
        judged = [(run["scene"]["name"], r["expect"]) for run in runs for r in all_runs(run)
                  if r["label"] == lb and r.get("expect")]
        misses = sorted(((e["max_error"] or float("inf"), name) for name, e in judged
                         if not e["pass"]), reverse=True)
        table[lb] = (len(judged) - len(misses), len(judged), misses)
    parts = []
    for lb, (met, judged, misses) in table.items():
        text = f"`{lb}` on {met} of {judged}"
        if misses:
            text += (f" (misses {names([n for _, n in misses])}; largest {fmt(misses[0][0])} m "
                     f"on `{misses[0][1]}`)")
        parts.append(text)
    return table, ("**Right answers.** Each scene states where its bodies must end up; the "
                   "engines meet every one of a scene's expectations: " + "; ".join(parts) + ".")


def breaks(stress, labels):
    """Per engine, the stress cases it is ok on and, by kind of case, where it is not."""
    if not stress:
        return {}, None
    table, parts = {}, []
    for lb in [c["label"] for c in stress["cases"]]:
        table.setdefault(lb, [])
    for c in stress["cases"]:
        table[c["label"]].append(c)
    for lb, cases in table.items():
        bad = [c for c in cases if c["verdict"] not in ("ok", "skipped")]
        run = [c for c in cases if c["verdict"] != "skipped"]
        verdicts, groups = {}, {}
        for c in bad:
            # A near miss (every failed check within a tenth of its tolerance) is tallied apart.
            kind = c["verdict"] + (" (near miss)" if c.get("near_miss") else "")
            verdicts[kind] = verdicts.get(kind, 0) + 1
            groups[c["group"]] = groups.get(c["group"], 0) + 1
        text = f"`{lb}` is ok on {len(run) - len(bad)} of {len(run)}"
        if bad:
            worst = sorted(groups, key=lambda g: -groups[g])
            text += (" (elsewhere " + ", ".join(f"{n} {v}" for v, n in
                                                 sorted(verdicts.items(), key=lambda x: -x[1])) +
                     "; most in " + ", ".join(f"{g} ({groups[g]})" for g in worst[:3]) +
                     (f" and {len(worst) - 3} more kinds" if len(worst) > 3 else ""))
            known = sum(1 for c in bad if c.get("known_failure"))
            text += f"; {plural(known, 'listed known failure')})" if known else ")"
        parts.append(text)
    cases = len({c["case"] for c in stress["cases"]})
    return table, (f"**Where each breaks.** In the stress matrix ({cases} cases, each in its own "
                   "process): " + "; ".join(parts) + ".")


def pick(runs, subject, right, fastest, stress_table):
    """Which engine to pick on these scenes, and which one to turn to where it breaks."""
    best = max(right, key=lambda lb: (right[lb][0], fastest.get(lb, 0)))
    met, judged, _ = right[best]
    sentence = (f"**Pick.** For scenes like these, `{best}`: it meets the stated answer on {met} "
                f"of {judged} scenes and is the fastest on {fastest.get(best, 0)} of {len(runs)}.")
    own = [c for c in stress_table.get(best, []) if c["verdict"] not in ("ok", "budget", "skipped")]
    if own:
        others = []
        for lb, cases in stress_table.items():
            if lb == best:
                continue
            ok = [c for c in cases if c["case"] in {o["case"] for o in own} and c["verdict"] == "ok"]
            if ok:
                others.append((len(ok), lb, sorted({c["group"] for c in ok})))
        others.sort(reverse=True)
        sentence += (f" Where it breaks ({plural(len(own), 'stress case')}: "
                     f"{', '.join(sorted({c['group'] for c in own}))})")
        if others:
            n, lb, groups = others[0]
            sentence += f", `{lb}` is ok on {n} of them ({', '.join(groups)})."
        else:
            sentence += ", no other engine here is ok either."
    return sentence


def front(sweep):
    """The settings on the sweeps' Pareto fronts: those worth choosing."""
    if not sweep:
        return None
    parts = []
    for s in sweep["scenes"]:
        points = sorted((p for p in s["points"] if p.get("pareto")), key=lambda p: p["ms_per_step"])
        if points:
            parts.append(f"`{s['scene']['name']}`: " + ", ".join(
                f"`{p['label']}` ({fmt(p['ms_per_step'], 2)} ms/step, error "
                f"{fmt(p['final_position_error']['rms'])} m)" for p in points[:3]) +
                (f" and {len(points) - 3} more" if len(points) > 3 else ""))
    return ("**Settings worth choosing** (the sweeps' Pareto fronts: nothing else is both faster "
            "and at least as accurate): " + "; ".join(parts) + ".") if parts else None


def conclusion(runs, stress=None, sweep=None):
    """The report's opening section, as Markdown lines."""
    labels = list(dict.fromkeys(r["label"] for run in runs for r in all_runs(run)))
    subject = next((r["label"] for run in runs for r in all_runs(run) if r.get("gate")), labels[0])
    right, right_text = accuracy(runs, labels)
    fastest, speed_text = speed(runs, labels, subject)
    stress_table, stress_text = breaks(stress, labels)
    lines = ["## Conclusion", "", f"- {pick(runs, subject, right, fastest, stress_table)}",
             f"- {speed_text}", f"- {losses(runs, labels, subject)}", f"- {right_text}"]
    if stress_text:
        lines.append(f"- {stress_text}")
    sweep_text = front(sweep)
    if sweep_text:
        lines.append(f"- {sweep_text}")
    return lines + [""]
