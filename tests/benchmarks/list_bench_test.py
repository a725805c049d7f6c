#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""chainbench_bench registers its benchmarks without building their scenes: listing them works
in a heap of 64 MB (building every size, up to a million bodies, took 314 MB and 2 s), and the
list holds every family at every size the tables quote.

    python3 tests/benchmarks/list_bench_test.py build/bin/chainbench_bench
"""
import resource
import subprocess
import sys
import unittest

BENCH = sys.argv.pop(1) if len(sys.argv) > 1 else "build/bin/chainbench_bench"
HEAP = 64 * 1024 * 1024


def limit_heap():
    resource.setrlimit(resource.RLIMIT_DATA, (HEAP, HEAP))


class ListBenchTest(unittest.TestCase):
    def test_listing_builds_no_large_scene(self):
        result = subprocess.run([BENCH, "--benchmark_list_tests"], capture_output=True, text=True,
                                timeout=120, preexec_fn=limit_heap)
        self.assertEqual(result.returncode, 0, result.stderr[-2000:])
        names = result.stdout.split()
        # The largest sizes are registered all the same, the harness's as the engines'.
        for prefix in ("random_pile/chain/1000000/", "harness/random_pile/1000000/metrics:1/",
                       "rain/chain/10000/", "push_row/box2d/100000/"):
            self.assertTrue(any(n.startswith(prefix) for n in names),
                            f"no benchmark {prefix}... among {len(names)}")

    def test_the_limit_bites(self):
        # The heap limit is real: a child that asks for more than it fails.
        probe = subprocess.run([sys.executable, "-c", "b = bytearray(%d)" % (2 * HEAP)],
                               capture_output=True, preexec_fn=limit_heap)
        self.assertNotEqual(probe.returncode, 0)


if __name__ == "__main__":
    unittest.main()
