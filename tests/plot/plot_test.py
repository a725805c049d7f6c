#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Tests scripts/plot.py (and its package, scripts/chainbench_tools/plotting/) on small synthetic inputs of each
format, without chainbench.

    python3 tests/plot/plot_test.py

Each subcommand runs once (with --svg) in a subprocess, the four at the same time; the checks are
that every expected PNG and SVG is written, valid and not tiny, that the paths are printed, and
that bad input exits with status 2 and a one-line message naming the file, without a traceback.
"""
import importlib
import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path
from unittest import mock

PLOT = Path(__file__).resolve().parent.parent.parent / "scripts" / "plot.py"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
MODERN = "chain:variant=modern,velocity=inelastic,passes=4,budget=64,depth=2048"
SEED = "chain:variant=seed2014,velocity=zero,passes=4,budget=64,depth=2048"
BOX2D = "box2d:vel_iters={},pos_iters=3,substeps={},skin=compensate,warm=1"
# The labels chainbench writes beside each spec: the plots read these, never the specs' defaults.
LABELS = {MODERN: "chain", SEED: "chain:variant=seed2014",
          MODERN.replace("passes=4", "passes=1"): "chain:passes=1"}


def label(spec):
    """The label chainbench writes for one of the specs above."""
    if spec in LABELS:
        return LABELS[spec]
    v, s = spec.split("vel_iters=")[1].split(",")[0], spec.split("substeps=")[1].split(",")[0]
    keys = ([f"vel_iters={v}"] if v != "8" else []) + ([f"substeps={s}"] if s != "1" else [])
    return "box2d" + (":" + ",".join(keys) if keys else "")


def sweep_point(engine, ms, rms, pareto=False, stable=True):
    return {"engine": engine, "label": label(engine), "ms_per_step": ms,
            "final_position_error": {"max": rms, "rms": rms}, "energy_free_displacement": 1e-6,
            "max_penetration": 1e-4, "stable": stable, "pareto": pareto}


def sweep_json():
    """Two scenes: one against an engine with a zero, a null error and an unstable point, one
    against the scene's expectations."""
    points = [sweep_point(MODERN, 0.001, 0.3, pareto=True), sweep_point(SEED, 0.002, 0.3),
              sweep_point(MODERN.replace("passes=4", "passes=1"), 0.0011, 0.3),
              sweep_point(BOX2D.format(1, 1), 0.003, 0.5, stable=False),
              sweep_point(BOX2D.format(8, 1), 0.005, 0.1, pareto=True),
              sweep_point(BOX2D.format(8, 8), 0.04, 0.0, pareto=True),
              sweep_point(BOX2D.format(8, 2), 0.01, None)]
    return {"schema": "chainbench.sweep/1", "scenes": [
        {"scene": {"name": "push_row", "bodies": 11, "steps": 120},
         "reference": BOX2D.format(20, 8), "reference_ms_per_step": 0.07, "interrupted": False,
         "points": points},
        {"scene": {"name": "my scene", "bodies": 3, "steps": 60}, "reference": "expect",
         "interrupted": True, "points": points[:3]}]}


def bench_json():
    """Three scene families (one at a single size), a repeated benchmark with aggregates, and the
    entries that must be left out (BigO, RMS, harness, mean)."""
    out = []

    def add(name, ms, bodies, **extra):
        out.append(dict({"name": name, "run_name": name, "run_type": "iteration", "real_time": ms,
                         "cpu_time": ms, "time_unit": "ms", "bodies": bodies}, **extra))

    for engine, per_body in (("chain", 5e-5), ("seed2014", 2e-4), ("box2d", 1e-3)):
        for family, sizes in (("pyramid", (211, 5051)), ("random_pile", (1003, 10003, 100003))):
            for n in sizes:
                add(f"{family}/{engine}/{n}/min_time:0.500/real_time", n * per_body, n)
        add(f"stack/{engine}/0/min_time:0.500/real_time", 16 * per_body * 1000, 16)
        out.append({"name": f"pyramid/{engine}/min_time:0.500/real_time_BigO", "run_type":
                    "aggregate", "aggregate_name": "BigO", "real_coefficient": 44.0, "big_o": "N"})
        out.append({"name": f"pyramid/{engine}/min_time:0.500/real_time_RMS", "run_type":
                    "aggregate", "aggregate_name": "RMS", "rms": 0.01})
    name = "push_row/chain/100/repeats:3"
    for i, ms in enumerate((0.0020, 0.0022, 0.0100)):
        add(name, ms, 101, repetition_index=i)
    add(name + "_mean", 0.0047, 101, run_name=name, run_type="aggregate", aggregate_name="mean")
    add(name + "_median", 0.0022, 101, run_name=name, run_type="aggregate", aggregate_name="median")
    add("push_row/chain/10000/real_time", 1100.0, 10001, time_unit="us")
    add("harness/pyramid100/metrics/1/real_time", 0.4, 5051)
    return {"context": {"date": "2026-11-23T11:31:51+00:00", "num_cpus": 2, "mhz_per_cpu": 2096},
            "benchmarks": out}


def run_json():
    """A ground, a kinematic pusher and three boxes, two engines, a reference run and angles."""
    def run(engine, dx, angle):
        return {"engine": engine, "label": label(engine),
                "final_positions": [[0, -1], [-3, 0.5], [dx, 0.5], [dx + 1, 0.5],
                                                       [dx + 0.5, 1.5]],
                "final_angles": [0, 0, 0, angle, -angle], "ms_per_step": {"median": 0.01},
                "metrics": {"stable": True}}

    return {"schema": "chainbench.run/1",
            "scene": {"name": "push_stack", "bodies": 5, "steps": 120, "dt": 1 / 60,
                      "half_extents": [[100, 1], [0.5, 0.5], [0.5, 0.5], [0.5, 0.5], [0.5, 0.5]],
                      "kinds": ["static", "kinematic", "dynamic", "dynamic", "dynamic"]},
            "reference": BOX2D.format(20, 1),
            "runs": [run(MODERN, 0.0, 0.0), run(SEED, 0.2, 0.0), run(BOX2D.format(8, 1), 0.1, 0.3)],
            "reference_run": run(BOX2D.format(20, 1), 0.05, 0.2), "comparison": []}


def trace_csv(rows_left_out=True):
    """Two engines, each spec once on a comment line and its label on every row, 30 steps of three
    named bodies, 40 steps declared; the values span several decades (a log axis). As chainbench
    writes it, the first engine's rows after step 1 are left out where they would repeat (only
    "box 0" changes); rows_left_out=False writes the older format: a row per body and step and a
    time column."""
    columns = "engine,step,time,body" if not rows_left_out else "engine,step,body"
    lines = [columns + ",x,y,vx,vy,angle,displacement,penetration"]
    if rows_left_out:
        lines += ["# chainbench trace 2", "# dt 0.016666666666666666 s", "# steps 40"]
    for engine, scale in ((MODERN, 1e-3), (BOX2D.format(8, 1), 1.0)):
        lines.append(f"# engine {label(engine)} = {engine}")
        for step in range(1, 31):
            for body in range(3):
                if rows_left_out and engine == MODERN and step > 1 and body > 0:
                    continue
                time = "" if rows_left_out else f"{step / 60:.6g},"
                lines.append(f'"{label(engine)}",{step},{time}"box {body}",0,{body},0,0,0,'
                             f"{scale * 1e-3 / step},{scale * 10.0 ** -(step % 5)}")
    return "\n".join(lines) + "\n"


def plotting(module):
    """scripts/chainbench_tools/plotting/MODULE imported (it imports matplotlib only when it
    draws)."""
    sys.dont_write_bytecode = True  # no __pycache__ in scripts/
    if str(PLOT.parent) not in sys.path:
        sys.path.insert(0, str(PLOT.parent))
    return importlib.import_module(f"chainbench_tools.plotting.{module}")


class Drawing:
    """For a TestCase with a scratch folder `self.dir`: write input files, and draw figures
    without saving them."""

    def write(self, name, text):
        (self.dir / name).write_text(text, encoding="utf-8")
        return self.dir / name

    def drawn(self, module, function, *args):
        """The figure that plotting.MODULE.FUNCTION(*args) draws last, not written to a file."""
        mod = plotting(module)
        with mock.patch.object(mod, "save") as save:
            getattr(mod, function)(*args)
        fig = save.call_args.args[0]
        self.addCleanup(plotting("common").pyplot().close, fig)
        return fig


class PlotTest(Drawing, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = Path(cls.tmp.name)
        inputs = {"sweep.json": json.dumps(sweep_json()), "bench.json": json.dumps(bench_json()),
                  "run.json": json.dumps(run_json()), "tr.csv": trace_csv()}
        for name, text in inputs.items():
            (cls.dir / name).write_text(text, encoding="utf-8")
        cls.out = cls.dir / "plots" / "new"  # plot.py must create it
        commands = {"sweep": ["sweep", "sweep.json"], "scaling": ["scaling", "bench.json"],
                    "states": ["states", "run.json"], "trace": ["trace", "tr.csv", "--name", "t1"]}
        procs = {k: subprocess.Popen([sys.executable, str(PLOT), c[0], str(cls.dir / c[1]), *c[2:],
                                      "--out", str(cls.out), "--svg"],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                 for k, c in commands.items()}
        cls.results = {k: (p.wait(timeout=120), p.stdout.read(), p.stderr.read())
                       for k, p in procs.items()}
        for p in procs.values():
            p.stdout.close()
            p.stderr.close()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def run_plot(self, *args):
        return subprocess.run([sys.executable, str(PLOT), *map(str, args)], capture_output=True,
                              text=True, timeout=120)

    def check_plots(self, command, stems):
        status, stdout, stderr = self.results[command]
        self.assertEqual(status, 0, stderr)
        self.assertNotIn("Traceback", stderr)
        expected = {str(self.out / f"{stem}.{ext}") for stem in stems for ext in ("png", "svg")}
        self.assertEqual(set(stdout.split()), expected)
        for stem in stems:
            png = (self.out / f"{stem}.png").read_bytes()
            self.assertTrue(png.startswith(PNG_SIGNATURE), stem)
            self.assertGreater(len(png), 10_000, stem)
            self.assertIn("<svg", (self.out / f"{stem}.svg").read_text(encoding="utf-8"), stem)

    def check_bad_input(self, command, path, reason=""):
        result = self.run_plot(command, path, "--out", self.dir / "bad")
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn(str(path), result.stderr)
        self.assertIn(reason, result.stderr)
        self.assertNotIn("Traceback", result.stderr)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
        self.assertEqual(result.stdout, "")

    def test_sweep(self):
        self.check_plots("sweep", ["sweep_push_row", "sweep_my_scene"])

    def test_sweep_same_stems(self):
        """Scenes whose names make the same file stem (also in another case, or the stem that a
        collision makes) each get a file of their own, and each path is printed once."""
        points = [sweep_point(MODERN, 0.001, 0.3), sweep_point(BOX2D.format(8, 1), 0.005, 0.1)]
        names = ["a b", "a/b", "a_b_2", "a_b", "A_B"]
        sweep = {"schema": "chainbench.sweep/1", "scenes": [
            {"scene": {"name": n, "bodies": 3, "steps": 60}, "reference": "expect",
             "points": points} for n in names]}
        out = self.dir / "same_stems"
        result = self.run_plot("sweep", self.write("same.json", json.dumps(sweep)), "--out", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        stems = ["sweep_a_b", "sweep_a_b_2", "sweep_a_b_2_2", "sweep_a_b_3", "sweep_A_B_4"]
        self.assertEqual(result.stdout.split(), [str(out / f"{s}.png") for s in stems])
        self.assertEqual(sorted(p.name for p in out.iterdir()), sorted(f"{s}.png" for s in stems))

    def test_sweep_vary(self):
        """A sweep --vary run gives one plot per value, titled with it, and one plot with every
        value's points, a legend entry per value, smallest value first."""
        points = [sweep_point(MODERN, 0.001, 0.3, pareto=True),
                  sweep_point(BOX2D.format(8, 1), 0.005, 0.1, pareto=True)]
        sweep = {"schema": "chainbench.sweep/1", "scenes": [
            {"scene": {"name": "stack", "bodies": 16, "steps": steps,
                       "vary": {"key": "dt", "text": text, "value": value}},
             "reference": "expect", "points": points}
            for text, value, steps in (("1/60", 1 / 60, 120), ("1/30", 1 / 30, 60))]}
        out = self.dir / "vary"
        path = self.write("vary.json", json.dumps(sweep))
        result = self.run_plot("sweep", path, "--out", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        stems = ["sweep_stack_dt_1_60", "sweep_stack_dt_1_30", "sweep_stack_by_dt"]
        self.assertEqual(result.stdout.split(), [str(out / f"{s}.png") for s in stems])
        sweep_module = plotting("sweep")
        scenes = sweep_module.load_sweep(path)
        for scene in scenes:
            scene["usable"] = scene["points"]
            for p in scene["usable"]:
                p["y"] = p["rms"]
        fig = self.drawn("sweep", "plot_varied", scenes, self.dir / "unused", False, set())
        legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        self.assertEqual(legend[:2], ["dt=1/60 (2 points)", "dt=1/30 (2 points)"])  # ascending
        self.assertIn("stack: error against time per step for each dt", fig.axes[0].get_title())

    def test_sweep_note(self):
        """Points are labelled with the settings their labels show, and the note says so."""
        sweep = {"schema": "chainbench.sweep/1", "scenes": [
            {"scene": {"name": "s", "bodies": 3, "steps": 60}, "reference": "expect",
             "points": [sweep_point(MODERN, 0.001, 0.3), sweep_point(SEED, 0.002, 0.2)]}]}
        path = self.write("chain_only.json", json.dumps(sweep))
        sweep_module = plotting("sweep")
        fig = self.drawn("sweep", "plot_sweep", path, sweep_module.load_sweep(path),
                         self.dir / "unused", False)
        text = "\n".join(t.get_text() for t in fig.axes[0].texts)
        self.assertIn("the settings that differ from the engine's defaults", text)
        self.assertIn("defaults", text)
        self.assertIn("variant=seed2014", text)
        self.assertNotIn("depth=2048", text)  # the spec's defaults are not restated

    def test_states_no_dynamic_body(self):
        """No dynamic body: each body is drawn once, in grey, and all of them are in view."""
        run = run_json()
        run["scene"]["kinds"] = ["static"] * 3 + ["kinematic"] * 2
        path = self.write("no_dynamic.json", json.dumps(run))
        fig = self.drawn("states", "plot_states", path, plotting("states").load_run(path),
                         self.dir / "unused", False)
        ax = fig.axes[0]
        # The static bodies, the kinematic ones, then each of the four runs' dynamic ones.
        self.assertEqual([len(c.get_paths()) for c in ax.collections], [3, 2, 0, 0, 0, 0])
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        self.assertTrue(x0 < -100 and x1 > 100 and y0 < -2 and y1 > 2, (x0, x1, y0, y1))

    def test_scaling_title(self):
        """The title has only the parts of the benchmark context that are known."""
        scaling = plotting("scaling")
        _, series = scaling.load_bench(self.dir / "bench.json")
        for context, expected in (({}, ""), ({"num_cpus": 2}, "\n2 CPUs"),
                                  (bench_json()["context"], "\n2026-11-23, 2 CPUs, 2096 MHz")):
            fig = self.drawn("scaling", "plot_scaling", "bench.json", (context, series),
                             self.dir / "unused", False)
            self.assertEqual(fig.axes[0].get_title(),
                             "Time per step against body count (Google Benchmark)" + expected)

    def test_scaling(self):
        self.check_plots("scaling", ["scaling"])

    def test_states(self):
        self.check_plots("states", ["states_push_stack"])

    def test_trace(self):
        self.check_plots("trace", ["trace_t1"])

    def test_bench_selection(self):
        context, series = plotting("scaling").load_bench(self.dir / "bench.json")
        self.assertEqual(context["num_cpus"], 2)
        self.assertNotIn(("harness", "pyramid100"), series)
        self.assertEqual(series[("push_row", "chain")], [(101, 0.0022), (10001, 1.1)])
        self.assertEqual([b for b, _ in series[("random_pile", "box2d")]], [1003, 10003, 100003])
        self.assertEqual(len(series), 10)  # 3 families x 3 engines + push_row/chain

    def test_trace_aggregation(self):
        per_engine, skipped = plotting("trace").load_trace(self.dir / "tr.csv")
        self.assertEqual(skipped, 0)
        self.assertEqual(list(per_engine), ["chain", "box2d"])
        time, displacement, penetration = per_engine["box2d"][2]
        self.assertAlmostEqual(time, 2 / 60, places=12)
        self.assertAlmostEqual(displacement, 3 * 1e-3 / 2)
        self.assertAlmostEqual(penetration, 1e-2)
        # Rows left out repeat the body's previous row: at step 2 "box 1" and "box 2" still hold
        # their step-1 values beside the new row of "box 0".
        _, displacement, penetration = per_engine["chain"][2]
        self.assertAlmostEqual(displacement, 1e-6 / 2 + 2 * 1e-6)
        self.assertAlmostEqual(penetration, 1e-4)
        # The 10 steps after the last rows (the file declares 40) repeat step 30.
        self.assertEqual(sorted(per_engine["chain"]), list(range(1, 41)))
        self.assertEqual(per_engine["box2d"][40][1:], per_engine["box2d"][30][1:])
        self.assertAlmostEqual(per_engine["box2d"][40][0], 40 / 60, places=12)

    def test_trace_with_a_row_per_body_and_step(self):
        """The first trace format: a time column, every row written."""
        path = self.write("old.csv", trace_csv(rows_left_out=False))
        per_engine, _ = plotting("trace").load_trace(path)
        time, displacement, _ = per_engine["chain"][2]
        self.assertAlmostEqual(time, 2 / 60, places=5)
        self.assertAlmostEqual(displacement, 3 * 1e-6 / 2)
        self.assertEqual(len(per_engine["chain"]), 30)

    def test_trace_with_bodies_that_come_and_go(self):
        """A body enters at its first row and leaves at a row with empty values: it adds its
        values only in between."""
        lines = ["engine,step,body,x,y,vx,vy,angle,displacement,penetration",
                 "# chainbench trace 2", "# dt 0.1 s", "# steps 8",
                 "# bodies come and go: ...", "# engine chain = chain",
                 "chain,1,a,0,0,0,0,0,0.5,0.01",
                 "chain,3,b,0,0,0,0,0,0.25,0.2",
                 "chain,6,b,,,,,,,"]
        path = self.write("lives.csv", "\n".join(lines) + "\n")
        per_engine, skipped = plotting("trace").load_trace(path)
        self.assertEqual(skipped, 0)
        steps = per_engine["chain"]
        self.assertAlmostEqual(steps[2][1], 0.5)
        self.assertAlmostEqual(steps[3][1], 0.75)
        self.assertAlmostEqual(steps[5][2], 0.2)
        self.assertAlmostEqual(steps[6][1], 0.5)
        self.assertAlmostEqual(steps[8][2], 0.01)

    def test_labels(self):
        """Labels come from chainbench's outputs; the plots only split them."""
        plot = plotting("common")
        self.assertEqual(plot.engine_of("chain:variant=seed2014"), "chain")
        self.assertEqual(plot.engine_of("plugin:path=librelaxation.so,iterations=4"), "plugin")
        self.assertEqual(plot.point_label("box2d:vel_iters=4,substeps=2"), "vel_iters=4,substeps=2")
        self.assertEqual(plot.point_label("box2d"), "defaults")

    def test_colours(self):
        """No engine is drawn in red, the colour of the sweep plots' unstable crosses."""
        colours = plotting("common").styles([f"engine{i}" for i in range(12)])
        self.assertFalse([c for _, c in colours.values() if "red" in c], colours)

    def test_help(self):
        for command in ("sweep", "scaling", "states", "trace"):
            result = self.run_plot(command, "--help")
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertIn("--out", result.stdout)

    def test_missing_file(self):
        for command in ("sweep", "scaling", "states", "trace"):
            self.check_bad_input(command, self.dir / "no_such_file.json", "cannot read")

    def test_invalid_json(self):
        path = self.write("broken.json", '{"schema": "chainbench.sweep/1", "scenes": [')
        for command in ("sweep", "scaling", "states"):
            self.check_bad_input(command, path, "not valid JSON")

    def test_wrong_schema(self):
        self.check_bad_input("sweep", self.dir / "run.json", "schema")
        self.check_bad_input("states", self.dir / "sweep.json", "schema")
        self.check_bad_input("scaling", self.dir / "sweep.json", "benchmarks")
        self.check_bad_input("trace", self.dir / "run.json", "no column")

    def test_wrong_structure(self):
        run = run_json()
        run["runs"][0]["final_positions"].pop()
        self.check_bad_input("states", self.write("short.json", json.dumps(run)))
        run["runs"] = "oops"
        self.check_bad_input("states", self.write("oops.json", json.dumps(run)))
        sweep = {"schema": "chainbench.sweep/1", "scenes": [{"scene": {"name": "x"}}]}
        self.check_bad_input("sweep", self.write("nopoints.json", json.dumps(sweep)), "points")
        run = run_json()
        run["scene"]["half_extents"][2] = ["nan", 0.5]  # loads, but cannot be drawn
        self.check_bad_input("states", self.write("nan_size.json", json.dumps(run)), "cannot plot")

    def test_no_usable_data(self):
        sweep = sweep_json()
        for point in sweep["scenes"][0]["points"]:
            point["final_position_error"]["rms"] = None
        sweep["scenes"].pop()
        self.check_bad_input("sweep", self.write("nulls.json", json.dumps(sweep)), "no scene")
        bench = {"context": {}, "benchmarks": bench_json()["benchmarks"][-1:]}  # harness only
        self.check_bad_input("scaling", self.write("harness.json", json.dumps(bench)), "no bench")

    def test_bad_trace(self):
        self.check_bad_input("trace", self.write("empty.csv", ""), "empty")
        self.check_bad_input("trace", self.write("blank.csv", "\n" + trace_csv()), "no header line")
        header = trace_csv().splitlines()[0]
        self.check_bad_input("trace", self.write("header.csv", header + "\n"), "no data")
        bad_row = '"chain",x,box,0,0,0,0,0,0,0'
        self.check_bad_input("trace", self.write("nan.csv", f"{header}\n{bad_row}\n"),
                             "line 2")
        binary = self.dir / "binary.csv"
        binary.write_bytes(b"\xff\xfe\x00garbage")
        self.check_bad_input("trace", binary)


if __name__ == "__main__":
    unittest.main()
