# SPDX-License-Identifier: MIT
"""The trace plot: from a chainbench trace CSV, the energy-free displacement and the deepest
penetration of each step over simulated time, one line per engine.
"""
import csv
import math

from .common import LINE_STYLES, InputError, file_stem, note_below, pyplot, save, styles


class _EngineSteps:
    """One engine's bodies' latest displacement and penetration, and its steps summed so far."""

    def __init__(self):
        self.disp, self.pen, self.total, self.steps, self.last = {}, {}, 0.0, {}, 0

    def set(self, body, disp, pen):
        self.total += disp - self.disp.get(body, 0.0)
        self.disp[body], self.pen[body] = disp, pen

    def close(self, upto, time_of):
        """Sums every step after the last one closed, up to upto, with the values as they are:
        a step without rows repeats the rows before it."""
        deepest = max(self.pen.values(), default=0.0)
        for s in range(self.last + 1, upto + 1):
            self.steps[s] = [time_of(s), self.total, deepest]
        self.last = max(self.last, upto)


def load_trace(path):
    """({engine: {step: [time, displacement summed over bodies, max penetration]}}, number of
    rows with a non-finite value, left out), streamed from a trace CSV without keeping rows.

    chainbench's trace (format 2) writes a body's row only when it changed: a missing row repeats
    the body's previous one, so every step counts every body seen so far, up to the "# steps"
    line's count; time is step * dt from the "# dt" line. Where bodies come and go, a row with
    empty values says the body left: it adds nothing from then on. A file with a time column and
    a row per body and step (format 1) reads as before."""
    needed = ("engine", "step", "body", "displacement", "penetration")
    per_engine, skipped, line, meta = {}, 0, 1, {}

    def rows_of(f):
        for text in f:
            if text.startswith("#"):  # the format, dt, steps, and each engine's full spec once
                words = text.split()
                if len(words) > 2 and words[1] in ("dt", "steps"):
                    meta[words[1]] = float(words[2])
                continue
            yield text

    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.reader(rows_of(f))
            header = next(reader, None)  # None if the file is empty, [] if its first line is blank
            if not header:
                raise InputError(f"{path}: " + ("empty file" if header is None else "no header "
                                                "line (the first line is blank)")
                                 + ", expected a trace CSV")
            missing = ", ".join(c for c in needed if c not in header)
            if missing:
                raise InputError(f"{path}: not a chainbench trace (no column {missing})")
            ie, istep, ibody, idisp, ipen = (header.index(c) for c in needed)
            itime = header.index("time") if "time" in header else None
            times = {}  # step -> time, from a time column

            def time_of(step):
                if itime is not None:
                    return times[step]
                if "dt" not in meta:
                    raise ValueError("no time column and no '# dt' line before the rows")
                return step * meta["dt"]

            current, step = None, None
            for line, row in enumerate(reader, start=2):
                if len(row) != len(header):
                    raise ValueError(f"{len(row)} fields, expected {len(header)}")
                row_step = int(row[istep])
                if current is None or row[ie] != current[0] or row_step != step:
                    if current is not None and row[ie] != current[0]:
                        current[1].close(step, time_of)  # rows come grouped by engine and step
                    current = (row[ie], per_engine.setdefault(row[ie], _EngineSteps()))
                    current[1].close(row_step - 1, time_of)
                    step = row_step
                if itime is not None:
                    times[row_step] = float(row[itime])
                if row[idisp] == "" and row[ipen] == "":  # the body left the world: it adds 0
                    current[1].set(row[ibody], 0.0, 0.0)
                    continue
                disp, pen = float(row[idisp]), float(row[ipen])
                if not (math.isfinite(disp) and math.isfinite(pen)):
                    skipped += 1
                    disp, pen = 0.0, 0.0
                current[1].set(row[ibody], disp, pen)
            if current is not None:
                current[1].close(step, time_of)
            for engine in per_engine.values():  # steps after an engine's last rows repeat them
                engine.close(int(meta.get("steps", 0)), time_of)
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}") from None
    except (ValueError, csv.Error) as e:  # UnicodeDecodeError is a ValueError
        raise InputError(f"{path}: line {line}: {e}") from None
    if not per_engine:
        raise InputError(f"{path}: no data rows (expected a chainbench trace CSV)")
    return {name: e.steps for name, e in per_engine.items()}, skipped


def plot_trace(path, trace, out_dir, svg, name):
    """Two panels against simulated time, one line per engine: (a) the energy-free displacement
    of each step summed over the bodies, (b) the deepest penetration after each step. A panel is
    log scale when its values are all positive and span more than two decades."""
    plt = pyplot()
    per_engine, skipped = trace
    colours = styles(per_engine)
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(10, 7.5))
    for k, (engine, steps) in enumerate(per_engine.items()):
        rows = [steps[s] for s in sorted(steps)]
        for ax, col in zip(axes, (1, 2)):
            ax.plot([r[0] for r in rows], [r[col] for r in rows], color=colours[engine][1],
                    ls=LINE_STYLES[k % 4], lw=1.4, label=engine)
    for ax, col in zip(axes, (1, 2)):
        values = [r[col] for steps in per_engine.values() for r in steps.values()]
        ax.set_yscale("log" if min(values) > 0 and max(values) > 100 * min(values) else "linear")
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("energy-free displacement\nper step, sum over bodies (m)")
    axes[1].set_ylabel("max penetration after\nthe step, over bodies (m)")
    axes[1].set_xlabel("simulated time (s)")
    axes[0].set_title("(a) displacement that the velocities do not explain", fontsize=9, loc="left")
    axes[1].set_title("(b) deepest overlap of any two boxes", fontsize=9, loc="left")
    fig.suptitle(f"{name}: energy-free displacement and penetration in each of "
                 f"{max(len(steps) for steps in per_engine.values())} steps", fontsize=11)
    axes[0].legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, title="engine",
                   handlelength=3)
    note_below(axes[1], [f"{skipped} row(s) with a non-finite value left out"] * bool(skipped))
    fig.tight_layout()
    save(fig, out_dir, f"trace_{file_stem(name)}", svg)
