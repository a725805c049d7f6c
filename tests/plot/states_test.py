#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Tests the states plot (scripts/chainbench_tools/plotting/states.py, expected.py) on a synthetic squeeze: the
whole scene in view, expected centres and bounds drawn, bodies named where they fit, and the
per-body panel where the drawing cannot show the engines' differences.

    python3 tests/plot/states_test.py
"""
import json
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot_test import BOX2D, MODERN, SEED, Drawing, label, plotting  # noqa: E402


class StatesTest(Drawing, unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.dir = Path(self.tmp.name)

    def squeeze_run(self, offsets):
        """A box between a 1 km floor and a lift, a ceiling far above, each engine's box moved by
        its offset in `offsets`; the scene expects the box back where it started."""
        engines = [MODERN, SEED, BOX2D.format(8, 1)][:len(offsets)]
        return {"schema": "chainbench.run/1",
                "scene": {"name": "squeeze", "bodies": 4, "steps": 60, "dt": 1 / 60,
                          "names": ["floor", "box", "lift", "ceiling"],
                          "kinds": ["static", "dynamic", "kinematic", "static"],
                          "half_extents": [[500, 1], [0.5, 0.5], [1.5, 0.5], [2, 0.5]],
                          "centers": [[0, -1], [0, 0.5], [0, 1.6], [0, 30]],
                          "expect": [{"kind": "moved", "body": "box", "moved": [0, 0],
                                      "tolerance": 0.01},
                                     {"kind": "bounds", "body": "box", "min": [None, 0],
                                      "max": [None, 0.5], "from_step": 0, "to_step": 30}]},
                "reference": engines[-1],
                "runs": [{"engine": e, "label": label(e),
                          "final_positions": [[0, -1], [dx, 0.5], [0, 1.1], [0, 30]]}
                         for e, dx in zip(engines, offsets)]}

    def test_states_whole_scene(self):
        """The lift and the ceiling far above are in view; the 1 km floor is cut to a band; the
        expected centre is crossed, the bound drawn with its window, big boxes named."""
        path = self.write("squeeze.json", json.dumps(self.squeeze_run([0.0, 0.3])))
        fig = self.drawn("states", "plot_states", path, plotting("states").load_run(path),
                         self.dir / "unused", False)
        ax = fig.axes[0]
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        self.assertTrue(y1 > 30.5 and y0 < 0, (y0, y1))
        self.assertLess(x1 - x0, 200)
        crosses = [line for line in ax.lines if line.get_marker() == "x"]
        self.assertEqual([tuple(line.get_xydata()[0]) for line in crosses], [(0.0, 0.5)])
        texts = [t.get_text() for t in ax.texts]
        self.assertIn("expect[1] box: 0 <= y <= 0.5 (steps 0-30)", texts)
        self.assertIn("ceiling", texts)

    def test_states_per_body_panel(self):
        """Millimetres the drawing cannot show get a panel of each body's distance from its
        expected centre; differences the drawing shows do not."""
        plot, states = plotting("states"), plotting("states")
        for offsets, panels in (([0.0, 0.002], 2), ([0.0, 0.3], 1), ([0.0, 0.0], 1)):
            path = self.write("mm.json", json.dumps(self.squeeze_run(offsets)))
            fig = self.drawn("states", "plot_states", path, plot.load_run(path),
                             self.dir / "unused", False)
            self.assertEqual(len(fig.axes), panels, offsets)
        values, origin, bodies = states.per_body(*states.load_run(path))
        self.assertEqual(origin, "the expected centre")
        self.assertEqual(bodies, [1])
        self.assertEqual(values, {"chain": [0.0], "chain:variant=seed2014": [0.0]})

    def test_expected_marks(self):
        """Centres of centre and moved entries ("*": every dynamic body), merged bound labels."""
        scene = {"names": ["g", "a", "b"], "kinds": ["static", "dynamic", "dynamic"],
                 "centers": [[0, 0], [1, 2], [3, 4]],
                 "expect": [{"kind": "center", "body": "a", "center": [5, 6], "tolerance": 0.1},
                            {"kind": "moved", "body": "*", "moved": [1, 0], "tolerance": 0.2,
                             "from_step": 3, "to_step": 9},
                            {"kind": "bounds", "body": "b", "min": [0, None], "max": [2, None]},
                            {"kind": "no_overlap", "no_overlap": 0.01}]}
        targets, bounds, left_out = plotting("expected").expected_marks(scene)
        self.assertEqual([(t["x"], t["y"], t["body"], t["final"]) for t in targets],
                         [(5, 6, 1, True), (2, 2, 1, False), (4, 4, 2, False)])
        self.assertEqual(bounds, [(0, 0, "expect[2] b: 0 <= x <= 2"), (0, 2, "")])
        self.assertEqual(left_out, [])
        # A "*" entry over more bodies than the limit is left out whole, and named.
        targets, _, left_out = plotting("expected").expected_marks(scene, limit=1)
        self.assertEqual([t["body"] for t in targets], [1])
        self.assertEqual(left_out, ["expect[1] (2 bodies)"])
        del scene["centers"]  # an older run JSON: moved entries cannot be placed
        self.assertEqual(len(plotting("expected").expected_marks(scene)[0]), 1)


if __name__ == "__main__":
    unittest.main()
