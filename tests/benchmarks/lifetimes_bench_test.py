#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs chainbench_bench's benchmarks of the families whose bodies come and go (spawn_rain, churn)
at their smallest size, the harness ones in all three modes (bare, metrics, pair judging), and
checks that each runs to the end: warm-up and timed steps must add and remove bodies by the same
convention, or a body entering at the first timed step is never added and the first to leave is
removed from an engine that never had it (which aborted the whole suite).

    python3 tests/benchmarks/lifetimes_bench_test.py build/bin/chainbench_bench
"""
import json
import subprocess
import sys
import unittest

BENCH = sys.argv.pop(1) if len(sys.argv) > 1 else "build/bin/chainbench_bench"


class LifetimesBenchTest(unittest.TestCase):
    def test_families_with_bodies_coming_and_going_run_to_the_end(self):
        result = subprocess.run(
            [BENCH, "--benchmark_filter=^(harness/)?(spawn_rain/chain/100|churn/chain/1000|"
             "spawn_rain/100/metrics:[012]|churn/1000/metrics:[012])/",
             "--benchmark_format=json"],
            capture_output=True, text=True, timeout=600)
        self.assertEqual(result.returncode, 0, result.stderr[-2000:])
        # The harness benchmarks repeat and report their aggregates only.
        runs = json.loads(result.stdout)["benchmarks"]
        names = {b["run_name"] for b in runs}
        for mode in ("0", "1", "2"):
            for family in ("spawn_rain/100", "churn/1000"):
                self.assertTrue(any(n.startswith(f"harness/{family}/metrics:{mode}/") for n in names),
                                f"harness/{family}/metrics:{mode} did not run: {sorted(names)}")
        for b in runs:
            with self.subTest(b["name"]):
                self.assertNotIn("error_occurred", b)
                if b.get("aggregate_name") in (None, "mean", "median"):
                    self.assertGreater(b["real_time"], 0.0)


if __name__ == "__main__":
    unittest.main()
