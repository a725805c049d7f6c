# SPDX-License-Identifier: MIT
"""The sweep plot: for each scene of a chainbench.sweep/1 JSON, the final-position error of every
engine setting against its time per step, with the Pareto front and the reference engine's time.
"""
import math
import sys

from .common import (InputError, engine_of, file_stem, load_json, note_below, number, place_labels,
                     point_label, pyplot, save, styles)


def load_sweep(path):
    """The scenes of a chainbench.sweep/1 JSON, each a dict with name, bodies, steps, reference
    (its label, or "expect"), reference_ms, interrupted and points: dicts of label, ms, rms (None
    if not finite), stable and pareto."""
    data = load_json(path, "chainbench.sweep/1")
    if not isinstance(data.get("scenes"), list) or not data["scenes"]:
        raise InputError(f"{path}: no scenes")
    return [{"name": str(s["scene"]["name"]), "bodies": s["scene"].get("bodies", "?"),
             "vary": variant_of(s["scene"]),
             "steps": s["scene"].get("steps", "?"),
             "reference": s.get("reference_label") or s.get("reference"),
             "reference_ms": number(s.get("reference_ms_per_step")),
             "interrupted": s.get("interrupted") is True,
             "points": [{"label": str(p.get("label") or p["engine"]), "ms": number(p["ms_per_step"]),
                         "rms": number(p["final_position_error"]["rms"]),
                         "stable": p.get("stable"), "pareto": p.get("pareto") is True}
                        for p in s["points"]]}
            for s in data["scenes"]]


def variant_of(scene):
    """(key, text, value) of a scene built by `sweep --vary`, or None."""
    vary = scene.get("vary")
    if not isinstance(vary, dict):
        return None
    value = number(vary.get("value"))
    if value is None or not isinstance(vary.get("key"), str):
        return None
    return (vary["key"], str(vary.get("text", value)), value)


def scene_title(scene):
    """"stack", or "stack (dt=1/30)" for one value of `sweep --vary`."""
    vary = scene["vary"]
    return scene["name"] + (f" ({vary[0]}={vary[1]})" if vary else "")


def unique_stem(base, stems):
    """base, or base_2, base_3... the first not in stems (lower case: some file systems ignore
    case); added to stems."""
    stem, n = base, 1
    while stem.lower() in stems:
        n += 1
        stem = f"{base}_{n}"
    stems.add(stem.lower())
    return stem


def plot_sweep(path, scenes, out_dir, svg):
    """Per scene: final-position RMS error against ms/step, log-log, one series per engine, each
    point labelled with the settings its label shows, the Pareto front as a step line and the reference
    engine's time per step as a dotted vertical line. Unstable points are crossed in red. Scenes
    whose names make the same file stem are written as sweep_STEM, sweep_STEM_2, sweep_STEM_3..."""
    for scene in scenes:
        scene["usable"] = [p for p in scene["points"]
                           if p["ms"] and p["ms"] > 0 and p["rms"] is not None]
    if not any(scene["usable"] for scene in scenes):
        raise InputError(f"{path}: no scene has a point with both a time and an error")
    plt, stems = pyplot(), set()  # stems written, lower case (some file systems ignore case)
    for scene in scenes:
        usable, ref, ref_ms = (scene[k] for k in ("usable", "reference", "reference_ms"))
        name = scene_title(scene)
        if not usable:
            print(f"plot.py: {path}: scene {name!r} has no point with a time and an error; skipped",
                  file=sys.stderr)
            continue
        notes = ["point labels: the settings that differ from the engine's defaults"]
        if len(usable) < len(scene["points"]):
            notes.append("not drawn, no time or error: " + ", ".join(
                p["label"] for p in scene["points"] if p not in usable))
        positive = [p["rms"] for p in usable if p["rms"] > 0]
        floor = 10.0 ** math.floor(math.log10(min(positive) / 10)) if positive else 1e-12
        if len(positive) < len(usable):
            notes.append(f"hollow markers: error 0, drawn at {floor:g} m (a log axis has no 0)")
        for p in usable:
            p["y"] = max(p["rms"], floor)
        fig, ax = plt.subplots(figsize=(10, 6.5))
        fig.subplots_adjust(left=0.09, right=0.74, top=0.88, bottom=0.16)
        families, labels = {}, []
        for p in usable:
            families.setdefault(engine_of(p["label"]), []).append(p)
        for fam, (marker, colour) in styles(families).items():
            pts = families[fam]
            ax.scatter([p["ms"] for p in pts], [p["y"] for p in pts], marker=marker, s=36, zorder=3,
                       facecolors=[colour if p["rms"] > 0 else "none" for p in pts],
                       edgecolors=colour, label=f"{fam} ({len(pts)})")
            labels += [(p["ms"], p["y"], point_label(p["label"]), colour) for p in pts]
        unstable = [(p["ms"], p["y"]) for p in usable if p["stable"] is False]
        if unstable:
            ax.scatter(*zip(*unstable), marker="x", s=70, color="red", zorder=4,
                       label="unstable (blow-up or budget hits)")
        front = sorted((p["ms"], p["y"]) for p in usable if p["pareto"])
        if front:
            ax.step(*zip(*front), where="post", color="0.2", lw=1, alpha=0.7, zorder=2,
                    label="Pareto front")
        if ref_ms and ref_ms > 0:
            ax.axvline(ref_ms, color="0.5", ls=":", lw=1, label=f"reference: {ref_ms:.3g} ms/step")
        ax.set(xscale="log", yscale="log", xlabel="time per step (ms, median, log scale)",
               ylabel="final-position error, RMS over dynamic bodies (m, log scale)")
        ax.grid(True, alpha=0.3)
        against = ("the scene's expected final centres" if ref == "expect"
                   else f"reference {ref}" if ref else "an unnamed reference")
        ax.set_title(f"{name}: {scene['bodies']} bodies, {scene['steps']} steps"
                     f"{' (interrupted)' * scene['interrupted']}\nerror against {against}",
                     fontsize=11)
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1), fontsize=8, title="engine (points)")
        note_below(ax, notes)
        place_labels(ax, sorted(labels))
        save(fig, out_dir, unique_stem(f"sweep_{file_stem(name)}", stems), svg)
    plot_varied(scenes, out_dir, svg, stems)


def plot_varied(scenes, out_dir, svg, stems):
    """For each scene run with `sweep --vary KEY=...`: every value's points in one plot, error
    against ms/step, a colour per value and a marker per engine, each value's Pareto front as a
    line: how error and cost move with KEY (the time step first of all)."""
    groups = {}
    for scene in scenes:
        if scene["vary"] and scene["usable"]:
            groups.setdefault((scene["name"], scene["vary"][0]), []).append(scene)
    plt = pyplot()
    for (name, key), members in groups.items():
        members.sort(key=lambda s: s["vary"][2])
        # One floor for every value, so that errors of 0 line up (a log axis has no 0).
        positive = [p["rms"] for s in members for p in s["usable"] if p["rms"] > 0]
        floor = 10.0 ** math.floor(math.log10(min(positive) / 10)) if positive else 1e-12
        for s in members:
            for p in s["usable"]:
                p["y"] = max(p["rms"], floor)
        fig, ax = plt.subplots(figsize=(10, 6.5))
        fig.subplots_adjust(left=0.09, right=0.74, top=0.88, bottom=0.16)
        engines = styles(dict.fromkeys(engine_of(p["label"]) for s in members for p in s["usable"]))
        values = styles([s["vary"][1] for s in members])
        for scene in members:
            colour = values[scene["vary"][1]][1]
            for fam, (marker, _) in engines.items():
                pts = [p for p in scene["usable"] if engine_of(p["label"]) == fam]
                if pts:
                    ax.scatter([p["ms"] for p in pts], [p["y"] for p in pts], marker=marker, s=36,
                               facecolors=[colour if p["rms"] > 0 else "none" for p in pts],
                               edgecolors=colour, zorder=3)
            label = f"{key}={scene['vary'][1]} ({len(scene['usable'])} points)"
            front = sorted((p["ms"], p["y"]) for p in scene["usable"] if p["pareto"])
            if front:
                ax.step(*zip(*front), where="post", color=colour, lw=1.2, alpha=0.8, zorder=2,
                        label=label)
            else:
                ax.plot([], [], color=colour, label=label)
        for fam, (marker, _) in engines.items():
            ax.scatter([], [], marker=marker, color="0.3", label=fam)
        ax.set(xscale="log", yscale="log", xlabel="time per step (ms, median, log scale)",
               ylabel="final-position error, RMS over dynamic bodies (m, log scale)")
        ax.grid(True, alpha=0.3)
        ax.set_title(f"{name}: error against time per step for each {key}\n"
                     f"lines: each value's Pareto front; markers: engines", fontsize=11)
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1), fontsize=8, title=f"{key} / engine")
        notes = [f"{key} values: " + ", ".join(s["vary"][1] for s in members)]
        if len(positive) < sum(len(s["usable"]) for s in members):
            notes.append(f"hollow markers: error 0, drawn at {floor:g} m (a log axis has no 0)")
        note_below(ax, notes)
        save(fig, out_dir, unique_stem(f"sweep_{file_stem(name)}_by_{file_stem(key)}", stems), svg)
