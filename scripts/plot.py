#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plots chainbench's results as PNG files (and SVG with --svg).

    plot.py sweep   SWEEP_JSON [--out DIR]   per scene, accuracy against cost of every engine setting
    plot.py scaling BENCH_JSON [--out DIR]   time per step against body count (Google Benchmark JSON)
    plot.py states  RUN_JSON   [--out DIR]   every engine's final boxes, drawn over each other
    plot.py trace   TRACE_CSV  [--out DIR]   displacement and penetration per step, over time

Each written file's path is printed on stdout. Bad input (a missing or unreadable file, a file that
is not what the subcommand reads, no usable data) is reported as one line on stderr naming the
file, with exit status 2. Needs only the standard library and matplotlib.
"""
import argparse
import inspect
import sys
from pathlib import Path

# The package lives next to this script, whose folder Python puts first on the path.
from chainbench_tools.plotting.common import InputError
from chainbench_tools.plotting.scaling import load_bench, plot_scaling
from chainbench_tools.plotting.states import load_run, plot_states
from chainbench_tools.plotting.sweep import load_sweep, plot_sweep
from chainbench_tools.plotting.trace import load_trace, plot_trace


def main(argv=None):
    """Parses the command line, loads the input, plots it; returns the exit status."""
    parser = argparse.ArgumentParser(description="\n\n".join(__doc__.split("\n\n")[:3:2]),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    commands = {  # name: (loader, plotter, input, made by, help)
        "sweep": (load_sweep, plot_sweep, "SWEEP_JSON", "chainbench sweep --json",
                  "sweep_<scene>.png: per scene, error against ms/step of every setting; "
                  "sweep_<scene>_by_<key>.png: every value of sweep --vary in one"),
        "scaling": (load_bench, plot_scaling, "BENCH_JSON", "chainbench_bench "
                    "--benchmark_format=json", "scaling.png: ms/step against body count"),
        "states": (load_run, plot_states, "RUN_JSON", "chainbench run --json",
                   "states_<scene>.png: every engine's final boxes over each other"),
        "trace": (load_trace, plot_trace, "TRACE_CSV", "chainbench run --trace",
                  "trace_<name>.png: displacement and penetration per step, over time"),
    }
    for command, (_, plot, metavar, source, text) in commands.items():
        p = sub.add_parser(command, help=text, formatter_class=argparse.RawDescriptionHelpFormatter,
                           description=f"{text}\n\n{inspect.cleandoc(plot.__doc__)}")
        p.add_argument("input", metavar=metavar, type=Path, help=f"file written by {source}")
        p.add_argument("--out", default=Path("."), type=Path, metavar="DIR",
                       help="directory for the plots (created if missing)")
        p.add_argument("--svg", action="store_true", help="also write an SVG of each plot")
    sub.choices["trace"].add_argument("--name", help="plot name (default: the CSV file's stem)")
    args = parser.parse_args(argv)
    load, plot = commands[args.command][:2]
    try:
        try:
            data = load(args.input)
        except (KeyError, TypeError, ValueError, IndexError, AttributeError) as e:
            what = f"no field {e}" if isinstance(e, KeyError) else f"unexpected content ({e})"
            raise InputError(f"{args.input}: not {args.command} input: {what}") from None
        try:
            plot(args.input, data, args.out, args.svg,
                 **({"name": args.name or args.input.stem} if args.command == "trace" else {}))
        except (KeyError, TypeError, ValueError) as e:  # bad data the loader let through (NaN size)
            raise InputError(f"{args.input}: cannot plot it ({type(e).__name__}: {e})") from None
        return 0
    except InputError as e:
        print(f"plot.py: {e}", file=sys.stderr)
    except OSError as e:
        print(f"plot.py: {e.filename or args.out}: cannot write: {e.strerror}", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
