"""The states plot: the final boxes of every engine in a chainbench.run/1 JSON (and of its
reference run) drawn over each other, so that where the engines disagree shows at a glance.
"""
import math

from .common import (LINE_STYLES, InputError, file_stem, load_json, note_below, number, pyplot,
                     save, styles)


def load_run(path):
    """(scene, [(engine, is reference, [(x, y)] with None where not finite, [angle] or None)])
    of a chainbench.run/1 JSON; the reference run, if the file has one, comes last."""
    data = load_json(path, "chainbench.run/1")
    scene = dict(data["scene"], half_extents=[(float(hx), float(hy))
                                              for hx, hy in data["scene"]["half_extents"]])
    n = len(scene["half_extents"])
    if len(scene["kinds"]) != n:
        raise InputError(f"{path}: scene.kinds and scene.half_extents differ in length")
    runs = [(r, False) for r in data["runs"]]
    if isinstance(data.get("reference_run"), dict):
        runs.append((data["reference_run"], True))
    out = []
    for r, is_ref in runs:
        pos, angles = r["final_positions"], r.get("final_angles")
        if len(pos) != n or (angles is not None and len(angles) != n):
            raise InputError(f"{path}: {r['engine']}: not one final position (angle) per body")
        out.append((str(r.get("label") or r["engine"]), is_ref, [(number(x), number(y)) for x, y in pos],
                    None if angles is None else [number(a) for a in angles]))
    if not out:
        raise InputError(f"{path}: no runs")
    return scene, out


def box_corners(centre, half, angle):
    """The four corners of a box of half extents half at centre, turned by angle (radians)."""
    c, s = math.cos(angle), math.sin(angle)
    return [(centre[0] + c * hx - s * hy, centre[1] + s * hx + c * hy)
            for hx, hy in ((-half[0], -half[1]), (half[0], -half[1]), half, (-half[0], half[1]))]


def plot_states(path, run, out_dir, svg):
    """The final boxes of every engine (and of the reference run) drawn over each other: one colour
    and line style per engine, each outline thinner than the one below so that equal boxes still
    show every engine; static and kinematic bodies once, in grey, from the first run. The view is
    the dynamic bodies' bounding box (all bodies' if none is dynamic) plus a margin, with equal
    scales."""
    plt = pyplot()
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Patch
    scene, runs = run
    halves, kinds = scene["half_extents"], scene["kinds"]
    dynamic = [i for i, k in enumerate(kinds) if k == "dynamic"]
    polys, dropped = [], 0
    for _, _, pos, angles in runs:
        ok = [i for i in dynamic
              if None not in pos[i] and (angles is None or angles[i] is not None)]
        dropped += len(dynamic) - len(ok)
        polys.append([box_corners(pos[i], halves[i], angles[i] if angles else 0.0) for i in ok])
    _, _, pos, angles = runs[0]
    fixed = [box_corners(pos[i], halves[i], angles[i] if angles and angles[i] else 0.0)
             for i, k in enumerate(kinds) if k != "dynamic" and None not in pos[i]]
    corners = [pt for boxes in (polys if dynamic else [fixed]) for box in boxes for pt in box]
    if not corners:
        raise InputError(f"{path}: no body has a finite final position")
    (x0, y0), (x1, y1) = map(min, zip(*corners)), map(max, zip(*corners))
    margin = max(0.08 * max(x1 - x0, y1 - y0), 0.25)
    x0, x1, y0, y1 = x0 - margin, x1 + margin, y0 - margin, y1 + margin
    fig, ax = plt.subplots(figsize=(11, 1.8 + min(max(8.5 * (y1 - y0) / (x1 - x0), 3.0), 8.5)))
    ax.add_collection(PolyCollection(fixed, facecolors="0.88", edgecolors="0.4", lw=1))
    handles = [Patch(facecolor="0.88", edgecolor="0.4", label="static / kinematic")] * bool(fixed)
    colours = styles([engine for engine, *_ in runs])
    for z, ((engine, is_ref, _, _), boxes) in enumerate(zip(runs, polys)):
        c, ls = colours[engine][1], LINE_STYLES[z % 4]
        lw = (0.4 if len(dynamic) > 300 else 1.2) * (1 + 0.8 * (len(runs) - 1 - z))
        ax.add_collection(PolyCollection(boxes, facecolors=to_rgba(c, 0.1), edgecolors=c, lw=lw,
                                         linestyles=ls, zorder=2 + z))
        handles.append(Patch(facecolor=to_rgba(c, 0.1), edgecolor=c, lw=1.5, ls=ls,
                             label=engine + " (reference)" * is_ref))
    ax.set(xlim=(x0, x1), ylim=(y0, y1), xlabel="x (m)", ylabel="y (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.2)
    steps, dt = scene.get("steps", "?"), number(scene.get("dt"))
    duration = f" ({steps * dt:.3g} s)" if dt and isinstance(steps, int) else ""
    ax.set_title(f"{scene.get('name', '?')}: final boxes after {steps} steps{duration}, "
                 f"{len(kinds)} bodies", fontsize=11)
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8,
              title="engine", handlelength=3)
    note_below(ax, [f"{dropped} box(es) with a non-finite position not drawn"] * bool(dropped)
               + ["no dynamic body: only the static and kinematic ones are drawn"] * (not dynamic))
    save(fig, out_dir, f"states_{file_stem(scene.get('name', 'unnamed'))}", svg)
