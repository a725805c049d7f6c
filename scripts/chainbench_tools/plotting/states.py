# SPDX-License-Identifier: MIT
"""The states plot: the final boxes of every engine in a chainbench.run/1 JSON (and of its
reference run) drawn over each other, so that where the engines disagree shows at a glance; the
expected centres and bounds of the scene's expectations; the bodies' names where they fit; and,
where the drawing cannot show them (below two pixels), each body's distance from the reference.
"""
import math

from .common import (LINE_STYLES, InputError, file_stem, load_json, note_below, number, pyplot,
                     save, styles)
from .expected import expected_marks


def load_run(path):
    """(scene, [(engine, is reference, [(x, y)] with None where not finite, [angle] or None)])
    of a chainbench.run/1 JSON; the reference run, if the file has one, comes last."""
    data = load_json(path, "chainbench.run/1")
    scene = dict(data["scene"], half_extents=[(float(hx), float(hy))
                                              for hx, hy in data["scene"]["half_extents"]])
    n = len(scene["half_extents"])
    if len(scene["kinds"]) != n:
        raise InputError(f"{path}: scene.kinds and scene.half_extents differ in length")
    runs = [(r, r["engine"] == data.get("reference")) for r in data["runs"]]
    if isinstance(data.get("reference_run"), dict):
        runs.append((data["reference_run"], True))
    out = []
    for r, is_ref in runs:
        pos, angles = r["final_positions"], r.get("final_angles")
        if len(pos) != n or (angles is not None and len(angles) != n):
            raise InputError(f"{path}: {r['engine']}: not one final position (angle) per body")
        # null: a body out of the world at the end (its scene's from_step/to_step), not drawn
        out.append((str(r.get("label") or r["engine"]), is_ref,
                    [(None, None) if p is None else (number(p[0]), number(p[1])) for p in pos],
                    None if angles is None else [number(a) for a in angles]))
    if not out:
        raise InputError(f"{path}: no runs")
    return scene, out


def box_corners(centre, half, angle):
    """The four corners of a box of half extents half at centre, turned by angle (radians)."""
    c, s = math.cos(angle), math.sin(angle)
    return [(centre[0] + c * hx - s * hy, centre[1] + s * hx + c * hy)
            for hx, hy in ((-half[0], -half[1]), (half[0], -half[1]), half, (-half[0], half[1]))]


def view_box(halves, kinds, runs):
    """(x0, y0, x1, y1) showing the whole scene: every dynamic and kinematic box of every run,
    and every static one, a side longer than three times theirs cut to a band around them (a
    floor 1 km wide shows as wide as they are, plus as much on each side); every body, whole,
    when none is dynamic."""
    if "dynamic" not in kinds:  # nothing the engines move: every body, whole
        return view_of([(p[0] - h[0], p[1] - h[1], p[0] + h[0], p[1] + h[1])
                        for p, h in zip(runs[0][2], halves) if None not in p])
    moving = [(p[0] - h[0], p[1] - h[1], p[0] + h[0], p[1] + h[1])
              for _, _, pos, _ in runs for p, h, k in zip(pos, halves, kinds)
              if k != "static" and None not in p]
    fixed = [(p[0] - h[0], p[1] - h[1], p[0] + h[0], p[1] + h[1])
             for p, h, k in zip(runs[0][2], halves, kinds) if k == "static" and None not in p]
    if not moving:
        return view_of(fixed)
    x0, y0 = min(b[0] for b in moving), min(b[1] for b in moving)
    x1, y1 = max(b[2] for b in moving), max(b[3] for b in moving)
    w, h = x1 - x0, y1 - y0

    def cut(lo, hi, a, b, size):  # a static box's side longer than 3 sizes: to a band around
        return (max(lo, a - size), min(hi, b + size)) if hi - lo > 3 * size else (lo, hi)

    boxes = list(moving)
    for b in fixed:
        (bx0, bx1), (by0, by1) = cut(b[0], b[2], x0, x1, w), cut(b[1], b[3], y0, y1, h)
        if bx0 < bx1 and by0 < by1:
            boxes.append((bx0, by0, bx1, by1))
    return view_of(boxes)


def view_of(boxes):
    """The boxes' bounding box with a margin, or None for no box."""
    if not boxes:
        return None
    x0, y0 = min(b[0] for b in boxes), min(b[1] for b in boxes)
    x1, y1 = max(b[2] for b in boxes), max(b[3] for b in boxes)
    margin = max(0.06 * max(x1 - x0, y1 - y0), 1e-6)
    return x0 - margin, y0 - margin, x1 + margin, y1 + margin


def name_bodies(ax, scene, runs, limit=80):
    """Writes each body's name inside its box (the first run's, or the static one), at the top
    of the part in view, else at its bottom, where the box is wide and tall enough on the figure
    and the name covers no other name (nor, for a static or kinematic body, a dynamic box);
    returns how many were named."""
    from matplotlib.transforms import Bbox
    names = scene.get("names") or []
    renderer = ax.figure.canvas.get_renderer()
    per_metre = abs(ax.transData.transform((1, 0))[0] - ax.transData.transform((0, 0))[0])
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    pos = runs[0][2]
    dynamic_boxes = [Bbox(ax.transData.transform([(p[0] - h[0], p[1] - h[1]), (p[0] + h[0], p[1] + h[1])]))
                     for p, h, k in zip(pos, scene["half_extents"], scene["kinds"])
                     if k == "dynamic" and None not in p]
    taken = []
    for i, (name, half, kind) in enumerate(zip(names, scene["half_extents"], scene["kinds"])):
        p = pos[i]
        if None in p or len(taken) >= limit:
            continue
        left, right = max(p[0] - half[0], x0), min(p[0] + half[0], x1)
        bottom, top = max(p[1] - half[1], y0), min(p[1] + half[1], y1)
        if (right - left) * per_metre < 6.5 * len(str(name)) + 6 or (top - bottom) * per_metre < 14:
            continue
        obstacles = taken + (dynamic_boxes if kind != "dynamic" else [])
        for y, offset, align in ((top, -3, "top"), (bottom, 3, "bottom")):
            text = ax.annotate(name, (0.5 * (left + right), y), xytext=(0, offset),
                               textcoords="offset points", ha="center", va=align, fontsize=7,
                               zorder=20, color="0.2" if kind == "dynamic" else "0.4")
            box = text.get_window_extent(renderer)
            if not any(box.overlaps(t) for t in obstacles):
                taken.append(box)
                break
            text.remove()
    return len(taken)


def per_body(scene, runs):
    """Each dynamic body's distance, per engine: from the centre the scene expects it at after
    the last step when the scene states one for some body (an error; every engine, the
    reference too), else from the reference's final centre (a difference; the reference left
    out). ({engine: [metres or None]}, what it is measured from, the bodies)."""
    dynamic = [i for i, k in enumerate(scene["kinds"]) if k == "dynamic"]
    expected = {}
    for t in expected_marks(scene, limit=len(dynamic))[0]:
        if t["final"]:
            expected.setdefault(t["body"], (t["x"], t["y"]))
    def distance(p, q):
        return None if p is None or q is None or None in p or None in q else \
            math.hypot(p[0] - q[0], p[1] - q[1])
    if expected:
        values = {engine: [distance(pos[i], expected.get(i)) for i in dynamic]
                  for engine, _, pos, _ in runs}
        return values, "the expected centre", dynamic
    ref = next((r for r in runs if r[1]), runs[0])
    values = {engine: [distance(pos[i], ref[2][i]) for i in dynamic]
              for engine, _, pos, _ in runs if engine != ref[0]}
    return values, f"{ref[0]}'s centre", dynamic


def plot_per_body(ax, scene, values, origin, dynamic, colours):
    """Each body's distance, one hollow marker per engine (the later ones smaller, so that equal
    values still show every engine), bodies along x, log scale with zero at the bottom."""
    names = scene.get("names") or [str(i) for i in range(len(scene["kinds"]))]
    positive = [d for ds in values.values() for d in ds if d]
    floor = min(positive) / 10 if positive else 1e-12
    for z, (engine, ds) in enumerate(values.items()):
        marker, colour = colours[engine]
        ax.scatter(range(len(ds)), [max(d, floor) if d is not None else math.nan for d in ds],
                   s=max(44 - 10 * z, 10), marker=marker, facecolors="none", edgecolors=colour,
                   linewidths=1.1, label=engine, zorder=3 + z)
    ax.set_yscale("log")
    ax.set_ylim(floor * 0.6, max(positive) * 2 if positive else 1)
    ax.set_ylabel(f"from {origin} (m)", fontsize=9)
    if len(dynamic) <= 30:
        ax.set_xticks(range(len(dynamic)), [names[i] for i in dynamic], rotation=60, fontsize=7)
    else:
        ax.set_xlabel("dynamic bodies, in scene order")
    ax.grid(True, alpha=0.3)
    ax.set_title(f"(b) each body's final centre from {origin}: the millimetres the drawing "
                 "cannot show (0 at the bottom)", fontsize=9, loc="left")


def plot_states(path, run, out_dir, svg):
    """The final boxes of every engine (and of the reference run) drawn over each other: one colour
    and line style per engine, each outline thinner than the one below so that equal boxes still
    show every engine; static and kinematic bodies once, in light grey (kinematic hatched), from
    the first run. The view is the whole scene: every dynamic and kinematic box, and the static
    ones near them. Expected centres are crosses with a circle of their tolerance, bounds on
    centres dashed lines; bodies are named where their box has room. When some engine's bodies
    are off by less than two pixels of the drawing, a second panel plots each body's distance
    from its expected centre (or, in a scene that states none, from the reference's)."""
    plt = pyplot()
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import Circle, Patch
    scene, runs = run
    halves, kinds = scene["half_extents"], scene["kinds"]
    if not all(math.isfinite(v) and v > 0 for half in halves for v in half):
        raise ValueError("a half extent is not a finite size above 0")
    dynamic = [i for i, k in enumerate(kinds) if k == "dynamic"]
    polys, dropped = [], 0
    for _, _, pos, angles in runs:
        ok = [i for i in dynamic
              if None not in pos[i] and (angles is None or angles[i] is not None)]
        dropped += len(dynamic) - len(ok)
        polys.append([box_corners(pos[i], halves[i], angles[i] if angles else 0.0) for i in ok])
    view = view_box(halves, kinds, runs)
    if view is None:
        raise InputError(f"{path}: no body has a finite final position")
    x0, y0, x1, y1 = view
    values, origin, dyn = per_body(scene, runs) if dynamic else ({}, None, [])
    figure_width = 11
    px_per_m = 8.5 * 110 / max(x1 - x0, y1 - y0)  # about what the main panel shows
    small = [d for ds in values.values() for d in ds if d and d * px_per_m < 2]
    panel = bool(small) and len(dyn) <= 5000
    height = 1.8 + min(max(8.5 * (y1 - y0) / (x1 - x0), 3.0), 8.5)
    if panel:
        fig, (ax, bx) = plt.subplots(2, 1, figsize=(figure_width, height + 2.6),
                                     gridspec_kw={"height_ratios": [height, 2.2]})
    else:
        fig, ax = plt.subplots(figsize=(figure_width, height))
    _, _, pos0, angles0 = runs[0]
    handles = []
    for kind, fill, hatch in (("static", "0.93", None), ("kinematic", "0.86", "//")):
        fixed = [box_corners(pos0[i], halves[i], angles0[i] if angles0 and angles0[i] else 0.0)
                 for i, k in enumerate(kinds) if k == kind and None not in pos0[i]]
        if fixed:
            ax.add_collection(PolyCollection(fixed, facecolors=fill, edgecolors="0.45", lw=1,
                                             hatch=hatch, zorder=1))
            handles.append(Patch(facecolor=fill, edgecolor="0.45", hatch=hatch, label=kind))
    colours = styles([engine for engine, *_ in runs])
    for z, ((engine, is_ref, _, _), boxes) in enumerate(zip(runs, polys)):
        c, ls = colours[engine][1], LINE_STYLES[z % 4]
        lw = (0.4 if len(dynamic) > 300 else 1.2) * (1 + 0.8 * (len(runs) - 1 - z))
        ax.add_collection(PolyCollection(boxes, facecolors=to_rgba(c, 0.1), edgecolors=c, lw=lw,
                                         linestyles=ls, zorder=2 + z))
        handles.append(Patch(facecolor=to_rgba(c, 0.1), edgecolor=c, lw=1.5, ls=ls,
                             label=engine + " (reference)" * is_ref))
    targets, bounds, left_out = expected_marks(scene)
    for t in targets:
        ax.plot([t["x"]], [t["y"]], marker="x", color="black", ms=5, mew=1, zorder=30, ls="none")
        if t["tolerance"] > 0:
            ax.add_patch(Circle((t["x"], t["y"]), t["tolerance"], fill=False, ec="black", lw=0.6,
                                ls=":", zorder=30))
    for axis, value, text in bounds:
        line = ax.axvline if axis == 0 else ax.axhline
        line(value, color="black", lw=0.8, ls="--", zorder=29)
        if text:
            ax.annotate(text, (value, y1) if axis == 0 else (x0, value), fontsize=7, color="0.2",
                        xytext=(3, -10) if axis == 0 else (3, 3), textcoords="offset points")
    if targets:
        handles.append(Line2D([], [], marker="x", color="black", ls="none",
                              label="expected centre (tolerance circle)"))
    if bounds:
        handles.append(Line2D([], [], color="black", ls="--", lw=0.8, label="bound on a centre"))
    ax.set(xlim=(x0, x1), ylim=(y0, y1), xlabel="x (m)", ylabel="y (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.2)
    steps, dt = scene.get("steps", "?"), number(scene.get("dt"))
    duration = f" ({steps * dt:.3g} s)" if dt and isinstance(steps, int) else ""
    ax.set_title(f"{'(a) ' if panel else ''}{scene.get('name', '?')}: final boxes after {steps} "
                 f"steps{duration}, {len(kinds)} bodies", fontsize=11)
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8,
              title="engine", handlelength=3)
    notes = ([f"{dropped} box(es) with a non-finite position not drawn"] * bool(dropped)
             + ["no dynamic body: only the static and kinematic ones are drawn"] * (not dynamic)
             + [f"expected centres of {', '.join(left_out)} not crossed: too many" +
                (", see (b)" if panel else "")] * bool(left_out))
    if panel:
        plot_per_body(bx, scene, values, origin, dyn, colours)
    fig.tight_layout(h_pad=1.0 + 1.2 * len(notes))  # room for the notes between the panels
    fig.canvas.draw()  # the final layout, so that names are placed where they fit
    name_bodies(ax, scene, runs)
    note_below(ax, notes)
    save(fig, out_dir, f"states_{file_stem(scene.get('name', 'unnamed'))}", svg)
