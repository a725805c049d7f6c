"""The trace plot: from a chainbench trace CSV, the energy-free displacement and the deepest
penetration of each step over simulated time, one line per engine.
"""
import csv
import math

from .common import LINE_STYLES, InputError, file_stem, note_below, pyplot, save, styles


def load_trace(path):
    """({engine: {step: [time, displacement summed over bodies, max penetration]}}, number of
    rows with a non-finite value, left out), streamed from a trace CSV without keeping rows."""
    needed = ("engine", "step", "time", "displacement", "penetration")
    per_engine, skipped, line, key, acc = {}, 0, 1, None, None
    try:
        with open(path, newline="", encoding="utf-8") as f:
            # Lines starting with # name each engine's full spec once; the rows carry its label.
            reader = csv.reader(line for line in f if not line.startswith("#"))
            header = next(reader, None)  # None if the file is empty, [] if its first line is blank
            if not header:
                raise InputError(f"{path}: " + ("empty file" if header is None else "no header "
                                                "line (the first line is blank)")
                                 + ", expected a trace CSV")
            missing = ", ".join(c for c in needed if c not in header)
            if missing:
                raise InputError(f"{path}: not a chainbench trace (no column {missing})")
            ie, istep, itime, idisp, ipen = (header.index(c) for c in needed)
            for line, row in enumerate(reader, start=2):
                if len(row) != len(header):
                    raise ValueError(f"{len(row)} fields, expected {len(header)}")
                if (row[ie], row[istep]) != key:  # rows come grouped by engine and step
                    key = (row[ie], row[istep])
                    acc = per_engine.setdefault(row[ie], {}).setdefault(
                        int(row[istep]), [float(row[itime]), 0.0, 0.0])
                disp, pen = float(row[idisp]), float(row[ipen])
                if math.isfinite(disp) and math.isfinite(pen):
                    acc[1], acc[2] = acc[1] + disp, max(acc[2], pen)
                else:
                    skipped += 1
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}") from None
    except (ValueError, csv.Error) as e:  # UnicodeDecodeError is a ValueError
        raise InputError(f"{path}: line {line}: {e}") from None
    if not per_engine:
        raise InputError(f"{path}: no data rows (expected a chainbench trace CSV)")
    return per_engine, skipped


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
