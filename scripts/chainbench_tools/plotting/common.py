# SPDX-License-Identifier: MIT
"""What every plot of scripts/plot.py shares: the InputError that bad input raises, the late
matplotlib import, writing a figure, reading JSON and numbers, engine labels (as chainbench writes
them into its outputs: nothing here knows an engine's defaults), one marker and colour per engine,
and the notes and point labels written on the axes.
"""
import itertools
import json
import math
import re

# Markers and colours, handed out in the order engines first appear. No red among them: red
# crosses mark the unstable points of the sweep plots.
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*", "<", ">")
COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink", "tab:olive",
           "tab:cyan", "tab:gray", "black")
LINE_STYLES = ("-", "--", ":", "-.")


class InputError(Exception):
    """Bad input, "FILE: reason": main() prints it on one line and exits with status 2."""


def pyplot():
    """matplotlib.pyplot on the Agg backend (imported late, so that bad input is reported fast)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig, out_dir, stem, svg):
    """Writes fig as DIR/stem.png (and DIR/stem.svg), prints each path and closes the figure."""
    out_dir.mkdir(parents=True, exist_ok=True)
    for path in [out_dir / f"{stem}.png"] + ([out_dir / f"{stem}.svg"] if svg else []):
        fig.savefig(path, dpi=110, bbox_inches="tight")
        print(path)
    pyplot().close(fig)


def file_stem(name):
    """A scene or trace name made safe for a file name."""
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", str(name)).strip("._") or "unnamed"


def load_json(path, schema=None):
    """The JSON object in path; with schema, one whose "schema" field is that."""
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}") from None
    except ValueError as e:  # not UTF-8 text, or not JSON
        raise InputError(f"{path}: not valid JSON ({e})") from None
    if not isinstance(data, dict):
        raise InputError(f"{path}: not a JSON object")
    if schema and data.get("schema") != schema:
        raise InputError(f"{path}: schema is {data.get('schema')!r}, expected {schema!r}")
    return data


def number(value):
    """value as a finite float, or None (null, non-finite, not a number)."""
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    return float(value) if ok else None


def engine_of(label):
    """The engine a label names: "chain" of "chain:variant=seed2014"."""
    return str(label).partition(":")[0]


def point_label(label):
    """A sweep point's settings in few characters: the keys its label shows (those that differ
    from the engine's defaults), or "defaults"."""
    return str(label).partition(":")[2] or "defaults"


def styles(keys):
    """{key: (marker, colour)}: a marker and a colour of its own for every key, in order."""
    return {key: (MARKERS[k % len(MARKERS)], COLOURS[k % len(COLOURS)])
            for k, key in enumerate(dict.fromkeys(keys))}


def note_below(ax, lines):
    """Writes notes in small grey type under the x-axis label of ax."""
    if lines:
        ax.annotate("\n".join(lines), (0, 0), xycoords="axes fraction", xytext=(0, -38),
                    textcoords="offset points", va="top", fontsize=8, color="0.3")


def place_labels(ax, labels):
    """Writes each (x, y, text, colour) label in 7 pt beside its point, once the layout is final.
    Labels of one colour on points less than 3 pixels apart are merged. Each label takes the
    nearest of rings of offsets that covers no marker and no earlier label and stays in the axes
    (else the least bad one); a label set away from its point gets a thin leader line."""
    from matplotlib.transforms import Bbox
    renderer = ax.figure.canvas.get_renderer()
    merged = []  # [pixel x, pixel y, x, y, texts, colour]
    for x, y, text, colour in labels:
        px, py = ax.transData.transform((x, y))
        near = [m for m in merged if m[5] == colour and abs(m[0] - px) < 3 and abs(m[1] - py) < 3]
        if not near:
            merged.append([px, py, x, y, [text], colour])
        elif text not in near[0][4]:
            near[0][4].append(text)
    frame, taken = ax.get_window_extent(renderer), [Bbox.from_bounds(m[0] - 4, m[1] - 4, 8, 8)
                                                    for m in merged]

    def put(ann, r, dx, dy):  # moves the label, returns (how bad it is there, its box)
        ann.set_position((dx * r, dy * r))
        ann.set_horizontalalignment("left" if dx > 0 else "right" if dx < 0 else "center")
        ann.set_verticalalignment("bottom" if dy > 0 else "top" if dy < 0 else "center")
        box = ann.get_window_extent(renderer)
        hits = [h for h in (Bbox.intersection(box, t) for t in taken) if h is not None]
        outside = not (frame.x0 <= box.x0 <= box.x1 <= frame.x1
                       and frame.y0 <= box.y0 <= box.y1 <= frame.y1)
        return sum(h.width * h.height for h in hits) + 1e6 * outside, box

    ring = ((1, 1), (1, -1), (-1, 1), (-1, -1), (0, 1.2), (0, -1.2), (1.2, 0), (-1.2, 0))
    for _, _, x, y, texts, colour in merged:
        text = "\n".join(texts if len(texts) <= 6 else texts[:5] + [f"+{len(texts) - 5} more"])
        ann = ax.annotate(text, (x, y), xytext=(0, 0), textcoords="offset points", fontsize=7,
                          color=colour, linespacing=1.0)
        best = (math.inf,)
        for r, (dx, dy) in itertools.product((4, 12, 22, 34, 48), ring):
            best = min(best, (put(ann, r, dx, dy)[0], r, dx, dy))
            if best[0] == 0:
                break
        _, r, dx, dy = best
        taken.append(put(ann, r, dx, dy)[1])
        if r > 4:
            ax.annotate("", (x, y), xytext=(dx * r, dy * r), textcoords="offset points",
                        arrowprops=dict(arrowstyle="-", color=colour, lw=0.5, shrinkB=3))
