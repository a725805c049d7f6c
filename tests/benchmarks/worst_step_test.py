#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs chainbench_bench on two small families, one at rest and one moving, and checks that each
benchmark reports its slowest step beside its median (counters step_ms_max and step_ms_median,
ms): present, finite, max >= median > 0, and max at least the mean time the benchmark reports (the
mean of the same step times, given to it as manual time, never exceeds the largest of them).

    python3 tests/benchmarks/worst_step_test.py build/bin/chainbench_bench
"""
import json
import math
import subprocess
import sys
import unittest

BENCH = sys.argv.pop(1) if len(sys.argv) > 1 else "build/bin/chainbench_bench"


class WorstStepTest(unittest.TestCase):
    def test_every_benchmark_reports_its_slowest_step_beside_its_median(self):
        result = subprocess.run(
            [BENCH, "--benchmark_filter=^(stack/chain/0|smash/chain/250)/",
             "--benchmark_format=json", "--benchmark_min_time=0.05"],
            capture_output=True, text=True, timeout=300)
        self.assertEqual(result.returncode, 0, result.stderr)
        runs = [b for b in json.loads(result.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
        self.assertEqual(sorted(b["run_name"].split("/")[0] for b in runs), ["smash", "stack"])
        for b in runs:
            with self.subTest(b["name"]):
                self.assertTrue(b["name"].endswith("/manual_time"), b["name"])
                median, worst = b["step_ms_median"], b["step_ms_max"]
                self.assertTrue(math.isfinite(median) and math.isfinite(worst))
                self.assertGreater(median, 0.0)
                self.assertGreaterEqual(worst, median)
                self.assertEqual(b["time_unit"], "ms")
                # The time Google Benchmark reports is the mean of the same step times.
                self.assertGreaterEqual(worst * (1 + 1e-9), b["real_time"])


if __name__ == "__main__":
    unittest.main()
