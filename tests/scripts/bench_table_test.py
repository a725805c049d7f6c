#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Tests scripts/bench_table.py on a synthetic Google Benchmark JSON: rows follow the benchmark's
order, scenes are named with the settings their family uses, the ratio is reference over subject
from the same run, and with accuracy runs each row carries its error and who meets the answer;
the headline gives the moving scenes' ratios with each engine's error, a table gives contacts and
heap per body, and each scaling family has its table relative to its base size; the compact
headline table (the moving scenes and the resting pyramid) goes between the README's markers, the
full tables between those of docs/results.md (written whole when new), the same bytes every time,
and stored accuracy runs are read back without running chainbench again.

    python3 tests/scripts/bench_table_test.py
"""
import json
import os
import stat
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SCRIPTS = Path(__file__).resolve().parent.parent.parent / "scripts"
SCRIPT = SCRIPTS / "bench_table.py"
sys.path.insert(0, str(SCRIPTS))  # the package beside the scripts, as they find it
from chainbench_tools import bench_table  # noqa: E402
from chainbench_tools.records import AccuracyRun  # noqa: E402

CONTEXT = {"chainbench_subject": "fast", "chainbench_reference": "ref",
           "chainbench_family_pile": "random_pile n layers=5 friction=0.5",
           "chainbench_family_stack": "stack -", "date": "today", "num_cpus": 2, "mhz_per_cpu": 1}


def bench(name, ms, bodies, per_body_ns):
    return {"name": name, "run_name": name, "run_type": "iteration", "real_time": ms,
            "time_unit": "ms", "bodies": bodies, "per_body": per_body_ns * 1e-9}


RUNS = {("stack", "fast", ""): bench("stack/fast", 0.001, 16, 60),
        ("stack", "ref", ""): bench("stack/ref", 0.010, 16, 600),
        ("pile", "fast", "1000"): bench("pile/fast/1000", 0.05, 1003, 50),
        ("pile", "ref", "1000"): bench("pile/ref/1000", 1.0, 1003, 1000)}


def moving_bench(name, ms, contacts, held, bodies=11910):
    b = bench(name, ms, bodies, ms * 1e6 / bodies)
    b.update(contacts=contacts, bytes_per_body=held)
    return b


MOVING_CONTEXT = {"chainbench_subject": "fast", "chainbench_reference": "ref",
                  "chainbench_family_rain": "rain cols steps=120",
                  "chainbench_family_pyr": "many_pyramids rows,cols",
                  "chainbench_moving": "rain", "chainbench_scaling": "pyr:10",
                  "chainbench_contacts_fast": "pairs it resolved", "chainbench_contacts_ref": "touching pairs",
                  "date": "today", "num_cpus": 2, "mhz_per_cpu": 1}
MOVING_RUNS = {("rain", "fast", "1000"): moving_bench("rain/fast/1000", 1.0, 3480, 668),
               ("rain", "fast", "10000"): moving_bench("rain/fast/10000", 14.0, 34800, 657, 119903),
               ("rain", "ref", "1000"): moving_bench("rain/ref/1000", 8.0, 7740, 1006),
               ("rain", "ref:sleep=1", "1000"): moving_bench("rain/ref:sleep=1/1000", 5.0, 7741, 1010),
               ("pyr", "fast", "10"): bench("pyr/fast/10", 0.3, 5510, 50),
               ("pyr", "fast", "100"): bench("pyr/fast/100", 50.0, 550100, 90),
               ("pyr", "ref", "10"): bench("pyr/ref/10", 3.0, 5510, 500)}


def run_json(error, passed):
    return {"runs": [{"engine": "FAST", "label": "fast", "expect": {"pass": passed[0]}}],
            "reference_run": {"engine": "REF", "label": "ref", "expect": {"pass": passed[1]}},
            "comparison": [{"engine": "FAST", "final_position_error": {"max": error}}]}


def tables_after_summary(*args):
    """The lines of bench_table.tables() after its opening summary (tested on its own below)."""
    lines = bench_table.tables(*args).splitlines()
    assert lines[0].startswith("**`fast` against every engine"), lines[0]
    return lines[2:]


class BenchTableTest(unittest.TestCase):
    def test_rows_follow_the_benchmark_and_name_their_settings(self):
        lines = tables_after_summary(CONTEXT, RUNS)
        self.assertIn("| scene | bodies | fast ms/step | ref ms/step | ref / fast | fast ns/body/step |",
                      lines[0])
        self.assertTrue(lines[2].startswith("| `stack` | 16 |"), lines[2])
        self.assertIn("| 10.0x |", lines[2])
        self.assertTrue(lines[3].startswith("| `random_pile` layers=5 friction=0.5 n=1,000 | 1,003 |"),
                        lines[3])
        self.assertIn("| 20.0x |", lines[3])

    def test_accuracy_sits_beside_the_speed(self):
        accuracy = {("stack", ""): AccuracyRun(run_json(0.0094, (True, True)), None),
                    ("pile", "1000"): AccuracyRun(run_json(0.09, (True, False)), 60)}
        lines = tables_after_summary(CONTEXT, RUNS, accuracy)
        self.assertIn("| ref / fast | fast vs ref max m | meets the scene's answer |", lines[0])
        self.assertIn("| 10.0x | 0.0094 | `fast`, `ref` |", lines[2])
        self.assertIn("| 20.0x | 0.09 (60 steps) | `fast` |", lines[3])


class MovingTablesTest(unittest.TestCase):
    def test_headline_is_the_moving_scenes_at_the_size_every_engine_ran(self):
        lines = tables_after_summary(MOVING_CONTEXT, MOVING_RUNS)
        self.assertTrue(lines[0].startswith("The moving scenes"), lines[0])
        self.assertEqual(lines[2], "| moving scene | bodies | `fast` ms/step | `ref` | `ref:sleep=1` |")
        # 10,000 columns ran in `fast` only: the headline takes the 1,000 the others ran too.
        self.assertEqual(lines[4], "| `rain` cols=1,000 | 11,910 | 1.000 | 8.0x | 5.0x |")

    def test_headline_gives_each_engine_its_error_against_the_answer(self):
        run = {"runs": [{"engine": "FAST", "label": "fast", "expect": {"pass": True, "max_error": 0.0}},
                        {"engine": "SLEEP", "label": "ref:sleep=1",
                         "expect": {"pass": False, "max_error": 0.071}}],
               "reference_run": {"engine": "REF", "label": "ref",
                                 "expect": {"pass": True, "max_error": 0.0168}},
               "comparison": [{"engine": "FAST", "final_position_error": {"max": 0.02}}]}
        lines = tables_after_summary(MOVING_CONTEXT, MOVING_RUNS, {("rain", "1000"): AccuracyRun(run, None)})
        self.assertIn("| error |", lines[2])
        self.assertEqual(lines[4], "| `rain` cols=1,000 | 11,910 | 1.000 | 0 m | 8.0x (0.017 m) | "
                                   "5.0x (0.071 m, misses) |")

    def test_summary_gives_every_engine_sleeping_or_not_and_where_the_subject_loses(self):
        runs = dict(MOVING_RUNS)
        runs[("pyr", "ref:sleep=1", "10")] = bench("pyr/ref:sleep=1/10", 0.1, 5510, 18)
        context = dict(MOVING_CONTEXT, chainbench_caveat_ref="ref is a debug build")
        summary = bench_table.tables(context, runs).splitlines()[0]
        self.assertEqual(
            summary,
            "**`fast` against every engine, with sleeping off and on.** How many times faster "
            "`fast` steps, on the rows of the table below that both ran: on the moving scenes, "
            "`ref`† 8.0x (`rain` cols=1,000); `ref:sleep=1`† 5.0x (`rain` cols=1,000); on the "
            "scenes that come to rest or are pushed, `ref`† 10.0x (`many_pyramids` rows=cols=10); "
            "`ref:sleep=1`† 0.3x (`many_pyramids` rows=cols=10). **Where `fast` loses:** "
            "`ref:sleep=1`† steps `many_pyramids` rows=cols=10 3.0x faster (0.100 against 0.300 "
            "ms per step). † ref is a debug build.")
        self.assertIn("No engine steps any row faster than `fast`.",
                      bench_table.tables(CONTEXT, RUNS).splitlines()[0])

    def test_sleep_settings_are_columns_of_their_own(self):
        lines = bench_table.tables(MOVING_CONTEXT, MOVING_RUNS).splitlines()
        start = next(i for i, line in enumerate(lines) if line.startswith("| scene | bodies |"))
        self.assertEqual(lines[start], "| scene | bodies | fast ms/step | ref ms/step | ref:sleep=1 ms/step "
                                       "| ref / fast | fast ns/body/step |")
        self.assertEqual(lines[start + 2], "| `rain` cols=1,000 | 11,910 | 1.000 | 8.000 | 5.000 | 8.0x | 84 |")
        self.assertEqual(lines[start + 3], "| `rain` cols=10,000 | 119,903 | 14.0 | - | - | - | 117 |")

    def test_contacts_and_heap_per_body_for_every_engine(self):
        lines = bench_table.tables(MOVING_CONTEXT, MOVING_RUNS).splitlines()
        self.assertIn("(`fast`: pairs it resolved; `ref`: touching pairs)", "\n".join(lines))
        row = next(line for line in lines if line.startswith("| `rain` cols=1,000 | 3,480"))
        self.assertEqual(row, "| `rain` cols=1,000 | 3,480 · 668 | 7,740 · 1,006 | 7,741 · 1,010 |")
        # A family without the counters shows dashes, not zeros.
        pyramids = next(line for line in lines if line.startswith("| `many_pyramids` rows=cols=10 | - ·"))
        self.assertEqual(pyramids, "| `many_pyramids` rows=cols=10 | - · - | - · - | - |")

    def test_worst_frame_gives_median_and_slowest_step_of_every_engine(self):
        runs = {k: dict(v) for k, v in MOVING_RUNS.items()}
        runs[("rain", "fast", "1000")].update(step_ms_median=0.9, step_ms_max=4.25)
        runs[("rain", "ref", "1000")].update(step_ms_median=7.5, step_ms_max=12.0)
        lines = bench_table.tables(MOVING_CONTEXT, runs).splitlines()
        header = next(i for i, line in enumerate(lines) if line.startswith("The worst frame"))
        self.assertEqual(lines[header + 2], "| scene | fast median · max | ref median · max | "
                         "ref:sleep=1 median · max |")
        row = next(line for line in lines[header:] if line.startswith("| `rain` cols=1,000 |"))
        # Both figures as measured; an engine whose run has no such counter shows a dash.
        self.assertEqual(row, "| `rain` cols=1,000 | 0.900 · 4.250 | 7.500 · 12.0 | - |")
        # Without any slowest-step counter (an older benchmark JSON), there is no such table.
        self.assertNotIn("The worst frame", bench_table.tables(MOVING_CONTEXT, MOVING_RUNS))

    def test_scaling_is_relative_to_the_family_base(self):
        lines = bench_table.tables(MOVING_CONTEXT, MOVING_RUNS).splitlines()
        start = lines.index("Scaling of `fast` on `many_pyramids` (time per body per step):")
        self.assertEqual(lines[start + 2], "| rows=cols | bodies | ns/body/step | relative to rows=cols=10 |")
        self.assertEqual(lines[start + 4], "| 10 | 5,510 | 50 | 1.00x |")
        self.assertEqual(lines[start + 5], "| 100 | 550,100 | 90 | 1.80x |")


class HarnessTableTest(unittest.TestCase):
    """The harness' cost per family and size: bare, with every metric, and the ratio."""

    def test_a_plain_world_sits_beside_its_adapter_and_is_no_column(self):
        data = {"context": MOVING_CONTEXT, "benchmarks": [
            MOVING_RUNS[("pyr", "fast", "10")], MOVING_RUNS[("pyr", "ref", "10")],
            bench("plain/pyr/ref/10/min_time:0.500/real_time", 2.5, 5510, 450)]}
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "bench.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(data, f)
            context, runs = bench_table.load(path)
        self.assertEqual(bench_table.ordered(runs)[0], ["fast", "ref"])
        lines = bench_table.tables(context, runs).splitlines()
        start = next(i for i, line in enumerate(lines) if line.startswith("Adapter cost:"))
        self.assertEqual(lines[start + 4], "| `many_pyramids` rows=cols=10 | `ref` | 3.000 | 2.500 | 1.20x |")

    def test_each_size_has_its_bare_and_metrics_times_and_their_ratio(self):
        def harness(family, size, k, ms, bodies):
            name = f"harness/{family}/{size}/metrics:{k}/min_time:0.500/real_time"
            return bench(name, ms, bodies, ms * 1e6 / bodies)
        def aggregate(run, kind):
            return dict(run, run_name=run["name"], name=run["name"] + "_" + kind,
                        run_type="aggregate", aggregate_name=kind)
        data = {"context": MOVING_CONTEXT, "benchmarks": [
            MOVING_RUNS[("pyr", "fast", "10")], MOVING_RUNS[("rain", "fast", "1000")],
            harness("rain", 1000, 0, 4.0, 11910), harness("rain", 1000, 1, 4.2, 11910),
            # Repeated runs report aggregates: the median is the one taken.
            aggregate(harness("rain", 1000, 2, 9.9, 11910), "mean"),
            aggregate(harness("rain", 1000, 2, 4.1, 11910), "median"),
            harness("pyr", 100, 0, 50.0, 550100), harness("pyr", 100, 1, 52.5, 550100),
            harness("pyr", 10, 0, 0.25, 5510), harness("pyr", 10, 1, 0.26, 5510),
            harness("pyr", 20, 0, 1.0, 22020)]}  # no metrics:1: no row
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "bench.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(data, f)
            context, runs = bench_table.load(path)
        self.assertEqual(runs[("harness", "pyr", "100/1")]["real_time"], 52.5)
        lines = bench_table.tables(context, runs).splitlines()
        start = next(i for i, line in enumerate(lines) if line.startswith("Harness cost: a bare `fast` step"))
        self.assertEqual(lines[start + 2],
                         "| scene | bodies | bare ms/step | with metrics ms/step | ratio | least ratio |")
        self.assertEqual(lines[start + 4:start + 7], [
            "| `many_pyramids` rows=cols=10 | 5,510 | 0.250 | 0.260 | 1.04x | - |",
            "| `many_pyramids` rows=cols=100 | 550,100 | 50.0 | 52.5 | 1.05x | - |",
            "| `rain` cols=1,000 | 11,910 | 4.000 | 4.200 | 1.05x | 1.02x |"])
        self.assertFalse(any("rows=cols=20 |" in line for line in lines[start:]))
        # The harness rows are not scenes of the results table.
        self.assertFalse(any(line.startswith("| `harness`") for line in lines))
        # With nothing but harness rows there is no results table, not an empty one.
        alone = {key: run for key, run in runs.items() if key[0] == "harness"}
        lines = bench_table.tables(context, alone).splitlines()
        self.assertFalse(any(line.startswith("| scene | bodies | ") and "bare ms/step" not in line
                             for line in lines))
        self.assertTrue(any(line.startswith("Harness cost") for line in lines))


class ChurnTableTest(unittest.TestCase):
    def test_each_engine_has_its_churning_step_over_its_still_one(self):
        context = {"chainbench_family_churn": "churn cols per_step=1",
                   "chainbench_family_churn_base": "churn cols per_step=0"}
        runs = {("churn", "fast", "1000"): bench("churn/fast/1000", 3.0, 10001, 300),
                ("churn_base", "fast", "1000"): bench("churn_base/fast/1000", 0.5, 10001, 50),
                ("churn", "ref", "1000"): bench("churn/ref/1000", 10.0, 10001, 1000),
                ("churn_base", "ref", "1000"): bench("churn_base/ref/1000", 8.0, 10001, 800),
                ("churn", "ref", "10000"): bench("churn/ref/10000", 90.0, 100001, 900)}
        lines = bench_table.churn_table(context, runs)
        self.assertIn("| `churn` per_step=1 cols=1,000 | `fast` | 3.000 | 0.500 | 6.00x |", lines)
        self.assertIn("| `churn` per_step=1 cols=1,000 | `ref` | 10.0 | 8.000 | 1.25x |", lines)
        # A size with no still row has no ratio to give.
        self.assertFalse(any("cols=10,000" in line for line in lines))
        self.assertEqual(bench_table.churn_table(CONTEXT, RUNS), [])


class AccuracyRunsTest(unittest.TestCase):
    """accuracy_runs against a stand-in for chainbench that records its arguments."""

    def run_rows(self, context, runs):
        with tempfile.TemporaryDirectory() as tmp:
            exe = os.path.join(tmp, "chainbench")
            log = os.path.join(tmp, "args.jsonl")
            with open(exe, "w", encoding="utf-8") as f:
                f.write("#!/usr/bin/env python3\nimport json, sys\n"
                        f"open({log!r}, 'a').write(json.dumps(sys.argv[1:]) + '\\n')\n"
                        "path = sys.argv[sys.argv.index('--json') + 1]\n"
                        "json.dump({'runs': [], 'comparison': []}, open(path, 'w'))\n")
            os.chmod(exe, os.stat(exe).st_mode | stat.S_IEXEC)
            bench_table.accuracy_runs(context, runs, exe, os.path.join(tmp, "runs"))
            with open(log, encoding="utf-8") as f:
                return [json.loads(line) for line in f]

    def test_each_size_key_is_set_and_a_slow_resting_row_runs_fewer_steps(self):
        context = {"chainbench_reference": "ref", "chainbench_family_pyr": "many_pyramids rows,cols"}
        runs = {("pyr", "fast", "50"): bench("pyr/fast/50", 50.0, 137550, 360),
                ("pyr", "ref", "50"): bench("pyr/ref/50", 350.0, 137550, 2500)}
        (args,) = self.run_rows(context, runs)
        self.assertIn("--set rows=50 --set cols=50", " ".join(args))
        # 0.4 s a step for both engines: 20 s buys 50 steps.
        self.assertEqual(args[args.index("--steps") + 1], "50")

    def test_a_moving_row_is_judged_on_the_run_it_was_timed_in(self):
        context = {"chainbench_reference": "ref", "chainbench_family_rain": "rain cols steps=120"}
        runs = {("rain", "fast", "1000"): moving_bench("rain/fast/1000", 100.0, 0, 0),
                ("rain", "ref", "1000"): moving_bench("rain/ref/1000", 900.0, 0, 0)}
        (args,) = self.run_rows(context, runs)
        self.assertIn("--set steps=120 --set cols=1000", " ".join(args))
        self.assertNotIn("--steps", args)


class LikeAgainstLikeTest(unittest.TestCase):
    """Where the subject skips a world at rest (chain, skip_rest=1) and a row of it solves every
    step (chainbench_subject_solving), an engine that sleeps is set against the subject and one
    that does not against the solving row, in the summary and the results table's ratio."""
    CONTEXT = {"chainbench_subject": "fast", "chainbench_reference": "ref",
               "chainbench_subject_solving": "fast:skip_rest=0", "chainbench_sleeping": "ref:sleep=1",
               "chainbench_family_stack": "stack -", "date": "today", "num_cpus": 2, "mhz_per_cpu": 1}
    RUNS = {("stack", "fast", ""): bench("stack/fast", 0.001, 16, 60),
            ("stack", "fast:skip_rest=0", ""): bench("stack/fast:skip_rest=0", 0.1, 16, 6000),
            ("stack", "ref", ""): bench("stack/ref", 1.0, 16, 60000),
            ("stack", "ref:sleep=1", ""): bench("stack/ref:sleep=1", 0.0005, 16, 30)}

    def test_each_engine_is_set_against_its_like(self):
        text = bench_table.tables(self.CONTEXT, self.RUNS)
        summary = text.splitlines()[0]
        # ref solves every step: 1.0 / 0.1; ref:sleep=1 skips too: 0.0005 / 0.001, and wins.
        self.assertIn("`ref` 10.0x (`stack`)", summary)
        self.assertIn("`ref:sleep=1` 0.5x (`stack`)", summary)
        self.assertIn("`fast:skip_rest=0` 100.0x (`stack`)", summary)
        self.assertIn("**Where `fast` loses:** `ref:sleep=1` steps `stack` 2.0x faster (", summary)
        self.assertIn("like against like", summary)
        header = next(line for line in text.splitlines() if line.startswith("| scene | bodies |"))
        self.assertIn("| ref / fast:skip_rest=0 |", header)
        row = next(line for line in text.splitlines() if line.startswith("| `stack` |"))
        self.assertIn("| 10.0x |", row)


COMPACT_CONTEXT = {"chainbench_subject": "fast", "chainbench_reference": "ref",
                   "chainbench_subject_solving": "fast:skip_rest=0", "chainbench_sleeping": "ref:sleep=1",
                   "chainbench_family_rain": "rain cols steps=120", "chainbench_family_pyramid": "pyramid base",
                   "chainbench_moving": "rain", "chainbench_caveat_ref": "ref is a debug build",
                   "date": "today", "num_cpus": 2, "mhz_per_cpu": 1}
COMPACT_RUNS = {("rain", "fast", "1000"): bench("rain/fast/1000", 1.0, 11910, 84),
                ("rain", "fast:skip_rest=0", "1000"): bench("rain/fast:skip_rest=0/1000", 1.0, 11910, 84),
                ("rain", "ref", "1000"): bench("rain/ref/1000", 8.0, 11910, 672),
                ("rain", "ref:sleep=1", "1000"): bench("rain/ref:sleep=1/1000", 5.0, 11910, 420),
                ("rain", "box2d3", "1000"): bench("rain/box2d3/1000", 4.0, 11910, 336),
                ("rain", "fast", "10000"): bench("rain/fast/10000", 14.0, 119903, 117),
                ("pyramid", "fast", "100"): bench("pyramid/fast/100", 0.001, 5051, 0.2),
                ("pyramid", "fast:skip_rest=0", "100"): bench("pyramid/fast:skip_rest=0/100", 0.2, 5051, 40),
                ("pyramid", "ref", "100"): bench("pyramid/ref/100", 30.0, 5051, 6000),
                ("pyramid", "ref:sleep=1", "100"): bench("pyramid/ref:sleep=1/100", 0.0005, 5051, 0.1),
                ("pyramid", "box2d3", "100"): bench("pyramid/box2d3/100", 5.0, 5051, 1000)}


class CompactTableTest(unittest.TestCase):
    """The README's headline: a few rows, the subject's time, each other engine's ratio with
    sleeping off and on in one cell, like against like."""

    def test_moving_scenes_and_the_resting_pyramid_at_the_size_every_engine_ran(self):
        lines = bench_table.compact_table(COMPACT_CONTEXT, COMPACT_RUNS).splitlines()
        self.assertTrue(lines[0].startswith("How many times faster `fast` steps than each engine"), lines[0])
        self.assertIn("[docs/results.md](docs/results.md)", lines[0])
        # box2d3 comes first, ref with its sleeping setting beside it; fast's own settings are not columns.
        self.assertEqual(lines[2], "| scene | bodies | `fast` ms/step | vs `box2d3` | "
                                   "vs `ref`† (sleep off · on) |")
        # rain at 10,000 ran in fast only: the row is the 1,000 every engine ran. An engine that
        # does not sleep is set against fast:skip_rest=0, a sleeping one against fast.
        self.assertEqual(lines[4:6], [
            "| `rain` cols=1,000 | 11,910 | 1.000 | 4.0x | 8.0x · 5.0x |",
            "| `pyramid` base=100 | 5,051 | 0.001 (0.200 at `skip_rest=0`) | 25.0x | 150x · 0.5x |"])
        self.assertEqual(len(lines), 10)
        self.assertEqual(lines[7], "Where `fast` loses: on 1 of the 6 rows and engines set against it in the "
                                   "full tables; the most, `ref:sleep=1`† steps `pyramid` base=100 2.0x "
                                   "faster (0.0005 against 0.001 ms per step). † ref is a debug build.")
        self.assertEqual(lines[9], "Measured today on 2 CPUs at 1 MHz, one benchmark at a time; ratios "
                                   "are from the same run.")

    def test_with_accuracy_the_subject_has_its_error_and_a_miss_is_marked(self):
        run = {"runs": [{"engine": "FAST", "label": "fast", "expect": {"pass": True, "max_error": 0.0}},
                        {"engine": "B3", "label": "box2d3", "expect": {"pass": False, "max_error": 0.11}}],
               "reference_run": {"engine": "REF", "label": "ref", "expect": {"pass": True, "max_error": 0.02}},
               "comparison": []}
        lines = bench_table.compact_table(COMPACT_CONTEXT, COMPACT_RUNS,
                                          {("rain", "1000"): AccuracyRun(run, None)}).splitlines()
        self.assertIn("`(misses)`: that engine misses the scene's stated answer", lines[0])
        self.assertEqual(lines[2], "| scene | bodies | `fast` ms/step | `fast` error | vs `box2d3` | "
                                   "vs `ref`† (sleep off · on) |")
        self.assertEqual(lines[4], "| `rain` cols=1,000 | 11,910 | 1.000 | 0 m | 4.0x (misses) | 8.0x · 5.0x |")
        self.assertTrue(lines[5].startswith("| `pyramid` base=100 | 5,051 | 0.001 (0.200 at `skip_rest=0`) | - |"))

    def test_no_engine_faster_anywhere_is_said(self):
        runs = {k: v for k, v in COMPACT_RUNS.items() if k[1] != "ref:sleep=1"}
        text = bench_table.compact_table(COMPACT_CONTEXT, runs)
        self.assertIn("No engine of this table steps any of its rows in the full tables faster than "
                      "`fast`.", text)
        self.assertIn("| vs `ref`† |", text)


class WritesTheFilesTest(unittest.TestCase):
    """main(): the compact table between the README's markers, the full tables between those of
    the results file, the text around the markers kept, and the same bytes on a second run."""

    README = "# project\n\nintro\n\n<!-- results:begin -->\nold tables\n<!-- results:end -->\n\nafter\n"

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)
        (self.dir / "docs").mkdir()
        self.json = self.dir / "bench.json"
        self.json.write_text(json.dumps({"context": COMPACT_CONTEXT,
                                         "benchmarks": list(COMPACT_RUNS.values())}), encoding="utf-8")
        self.readme = self.dir / "README.md"
        self.readme.write_text(self.README, encoding="utf-8")
        self.results = self.dir / "docs" / "results.md"

    def tearDown(self):
        self.tmp.cleanup()

    def run_script(self, *extra, check=True):
        return subprocess.run([sys.executable, str(SCRIPT), str(self.json), "--readme", str(self.readme),
                               "--results", str(self.results), *extra],
                              capture_output=True, text=True, check=check)

    def test_compact_to_the_readme_full_to_the_results_and_twice_the_same(self):
        self.run_script()
        readme = self.readme.read_text(encoding="utf-8")
        results = self.results.read_text(encoding="utf-8")
        self.assertTrue(readme.startswith("# project\n\nintro\n\n<!-- results:begin -->\nHow many times"))
        self.assertTrue(readme.endswith("same run.\n<!-- results:end -->\n\nafter\n"))
        self.assertIn("| `rain` cols=1,000 | 11,910 | 1.000 | 4.0x | 8.0x · 5.0x |", readme)
        self.assertIn("[docs/results.md](docs/results.md)", readme)
        self.assertNotIn("old tables", readme)
        self.assertNotIn("| scene | bodies | fast ms/step", readme)  # the full tables are not there
        # A new results file is written whole: its head, then the full tables between the markers.
        self.assertTrue(results.startswith("# Results: every benchmark table\n\nGenerated by "
                                           "`scripts/bench.sh` from `results/bench.json`"), results[:200])
        self.assertIn("\n<!-- results:begin -->\n**`fast` against every engine", results)
        self.assertIn("| scene | bodies | fast ms/step | fast:skip_rest=0 ms/step |", results)
        self.assertTrue(results.endswith("same run.\n<!-- results:end -->\n"))
        self.run_script()
        self.assertEqual(self.readme.read_text(encoding="utf-8"), readme)
        self.assertEqual(self.results.read_text(encoding="utf-8"), results)
        # Text written around the results file's markers stays, as the README's does.
        self.results.write_text(results + "\nWhat it shows: by hand.\n", encoding="utf-8")
        self.run_script()
        self.assertEqual(self.results.read_text(encoding="utf-8"), results + "\nWhat it shows: by hand.\n")

    def test_a_file_without_markers_is_refused(self):
        self.readme.write_text("# project\n", encoding="utf-8")
        done = self.run_script(check=False)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("has no <!-- results:begin --> ... <!-- results:end --> markers", done.stderr)
        self.assertEqual(self.readme.read_text(encoding="utf-8"), "# project\n")

    def test_stored_accuracy_runs_are_read_back_without_chainbench(self):
        runs_dir = self.dir / "runs"
        plan = bench_table.accuracy_plan(COMPACT_CONTEXT, COMPACT_RUNS, "chainbench", str(runs_dir))
        self.assertEqual([step.group for step in plan], [("pyramid", "100"), ("rain", "1000")])
        done = self.run_script("--reuse-runs", "--runs", str(runs_dir), check=False)
        self.assertNotEqual(done.returncode, 0)  # nothing stored, nothing to run it with
        self.assertIn("no stored accuracy run of pyramid 100", done.stderr)
        run = {"runs": [{"engine": "FAST", "label": "fast", "expect": {"pass": True, "max_error": 0.0}},
                        {"engine": "B3", "label": "box2d3", "expect": {"pass": False, "max_error": 0.11}}],
               "reference_run": {"engine": "REF", "label": "ref", "expect": {"pass": True, "max_error": 0.02}},
               "comparison": [{"engine": "FAST", "final_position_error": {"max": 0.02}}]}
        # A stored run that lacks an engine timed on its row is refused, not read as if whole.
        for step in plan:
            Path(step.path).write_text(json.dumps(run), encoding="utf-8")
        done = self.run_script("--reuse-runs", "--runs", str(runs_dir), check=False)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("the stored run has no", done.stderr)
        for step in plan:  # every engine the row timed, as a real run holds them
            args, path = step.args, step.path
            whole = dict(run)
            named = {r["label"] for r in run["runs"]}
            whole["runs"] = run["runs"] + [{"engine": e.upper(), "label": e} for e in
                                           args[args.index("--engines") + 1].split(",") if e not in named]
            Path(path).write_text(json.dumps(whole), encoding="utf-8")
        self.run_script("--reuse-runs", "--runs", str(runs_dir))
        self.assertIn("| `rain` cols=1,000 | 11,910 | 1.000 | 0 m | 4.0x (misses) | 8.0x · 5.0x |",
                      self.readme.read_text(encoding="utf-8"))
        self.assertIn("| fast vs ref max m | meets the scene's answer |", self.results.read_text(encoding="utf-8"))


if __name__ == "__main__":
    unittest.main()
