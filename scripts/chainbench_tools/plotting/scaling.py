# SPDX-License-Identifier: MIT
"""The scaling plot: time per step against body count, from chainbench_bench's Google Benchmark
JSON, one line per scene family and engine, with guides of constant cost per body and step.
"""
import math
import statistics

from .common import InputError, load_json, number, pyplot, save, styles

TIME_UNIT_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def load_bench(path):
    """(context, {(scene family, engine): sorted [(bodies, ms per step)]}) from Google Benchmark
    JSON: per benchmark, its median aggregate if repeated, else the median of its iterations."""
    data = load_json(path)
    if not isinstance(data.get("benchmarks"), list):
        raise InputError(f"{path}: not Google Benchmark JSON (no \"benchmarks\" list)")
    runs = {}  # run name -> {"aggregate": [(bodies, ms)], "iteration": [(bodies, ms)]}
    for b in data["benchmarks"]:
        name, kind, run_name = str(b["name"]), b.get("run_type"), str(b.get("run_name", b["name"]))
        bodies, ms = number(b.get("bodies")), number(b.get("real_time"))
        unit = TIME_UNIT_MS.get(b.get("time_unit", "ns"))
        if not (name.endswith(("_BigO", "_RMS")) or run_name.startswith("harness/")
                or "/" not in run_name or b.get("error_occurred") or not unit or ms is None
                or not bodies or bodies <= 0
                or (kind == "aggregate" and b.get("aggregate_name") != "median")):
            runs.setdefault(run_name, {"aggregate": [], "iteration": []})[
                "aggregate" if kind == "aggregate" else "iteration"].append((bodies, ms * unit))
    series = {}
    for run_name, entries in runs.items():
        chosen = entries["aggregate"] or entries["iteration"]
        series.setdefault(tuple(run_name.split("/")[:2]), []).append(
            (chosen[0][0], statistics.median(ms for _, ms in chosen)))
    if not series:
        raise InputError(f"{path}: no benchmark with a \"bodies\" counter and a time")
    return data.get("context") or {}, {k: sorted(v) for k, v in series.items()}


def plot_scaling(path, bench, out_dir, svg):
    """Time per step against body count, log-log: a line per (scene family, engine) for families
    measured at several sizes, a lone marker for the others; colour is the engine, marker the
    scene. Dotted guides are constant costs per body and step."""
    plt = pyplot()
    from matplotlib.lines import Line2D
    context, series = bench
    scenes = list(dict.fromkeys(scene for scene, _ in series))
    marker = {s: "osD^vPX*<>ph"[i % 12] for i, s in enumerate(scenes)}
    multi = {s for (s, _), pts in series.items() if len({b for b, _ in pts}) > 1}
    engines = styles(e for _, e in series)  # benchmark names carry the engines' labels
    fig, ax = plt.subplots(figsize=(10, 6.5))
    fig.subplots_adjust(left=0.09, right=0.74, top=0.88, bottom=0.12)
    for (scene, engine), pts in series.items():
        ax.plot(*zip(*pts), marker=marker[scene], color=engines[engine][1], ms=6, lw=1.3,
                ls="-" if scene in multi else "none")
    ax.set(xscale="log", yscale="log")
    xlim, ylim = ax.get_xlim(), ax.get_ylim()
    for ns in (10, 100, 1000, 10000):
        k = ns * 1e-6  # ms per body and step
        x0, x1 = max(xlim[0], ylim[0] / k), min(xlim[1], ylim[1] / k)
        if x0 < x1:
            ax.plot([x0, x1], [x0 * k, x1 * k], color="0.6", ls=":", lw=0.8, zorder=0)
            (ax0, ay0), (ax1, ay1) = ax.transData.transform([(x0, x0 * k), (x1, x1 * k)])
            ax.annotate(f"{ns:g} ns per body-step", (x1, x1 * k), xytext=(-4, -2),
                        textcoords="offset points", ha="right", va="top", fontsize=7,
                        color="0.45", rotation=math.degrees(math.atan2(ay1 - ay0, ax1 - ax0)),
                        rotation_mode="anchor")
    ax.set(xlim=xlim, ylim=ylim, xlabel="bodies in the scene (log scale)",
           ylabel="time per step (ms, real time, log scale)")
    ax.grid(True, alpha=0.3)
    context = context if isinstance(context, dict) else {}
    date, cpus, mhz = (context.get(k) for k in ("date", "num_cpus", "mhz_per_cpu"))
    where = ([str(date)[:10]] * bool(date) + [f"{cpus} CPUs"] * (cpus is not None)
             + [f"{mhz} MHz"] * (mhz is not None))  # only the parts that are known
    ax.set_title("Time per step against body count (Google Benchmark)"
                 + ("\n" + ", ".join(where) if where else ""), fontsize=11)
    ax.add_artist(ax.legend(handles=[Line2D([], [], color=c, lw=2, label=e)
                                     for e, (_, c) in engines.items()],
                            title="engine", loc="upper left", bbox_to_anchor=(1.02, 1), fontsize=8))
    ax.legend(handles=[Line2D([], [], color="0.3", marker=marker[s], ls="-" if s in multi else "",
                              label=s if s in multi else f"{s} (one size)") for s in scenes],
              title="scene", loc="upper left", bbox_to_anchor=(1.02, 0.62), fontsize=8)
    save(fig, out_dir, "scaling", svg)
