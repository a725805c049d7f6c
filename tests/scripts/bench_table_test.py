#!/usr/bin/env python3
"""Tests scripts/bench_table.py on a synthetic Google Benchmark JSON: rows follow the benchmark's
order, scenes are named with the settings their family uses, the ratio is reference over subject
from the same run, and with accuracy runs each row carries its error and who meets the answer.

    /usr/bin/python3 tests/scripts/bench_table_test.py
"""
import importlib.util
import unittest
from pathlib import Path

SCRIPT = Path(__file__).resolve().parent.parent.parent / "scripts" / "bench_table.py"
spec = importlib.util.spec_from_file_location("bench_table", SCRIPT)
bench_table = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bench_table)

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


def run_json(error, passed):
    return {"runs": [{"engine": "FAST", "label": "fast", "expect": {"pass": passed[0]}}],
            "reference_run": {"engine": "REF", "label": "ref", "expect": {"pass": passed[1]}},
            "comparison": [{"engine": "FAST", "final_position_error": {"max": error}}]}


class BenchTableTest(unittest.TestCase):
    def test_rows_follow_the_benchmark_and_name_their_settings(self):
        text = bench_table.tables(CONTEXT, RUNS)
        lines = text.splitlines()
        self.assertIn("| scene | bodies | fast ms/step | ref ms/step | ref / fast | fast ns/body/step |",
                      lines[0])
        self.assertTrue(lines[2].startswith("| `stack` | 16 |"), lines[2])
        self.assertIn("| 10.0x |", lines[2])
        self.assertTrue(lines[3].startswith("| `random_pile` layers=5 friction=0.5 n=1,000 | 1,003 |"),
                        lines[3])
        self.assertIn("| 20.0x |", lines[3])

    def test_accuracy_sits_beside_the_speed(self):
        accuracy = {("stack", ""): (run_json(0.0094, (True, True)), None),
                    ("pile", "1000"): (run_json(0.09, (True, False)), 60)}
        lines = bench_table.tables(CONTEXT, RUNS, accuracy).splitlines()
        self.assertIn("| ref / fast | fast vs ref max m | meets the scene's answer |", lines[0])
        self.assertIn("| 10.0x | 0.0094 | `fast`, `ref` |", lines[2])
        self.assertIn("| 20.0x | 0.09 (60 steps) | `fast` |", lines[3])


if __name__ == "__main__":
    unittest.main()
