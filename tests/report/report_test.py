#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Tests scripts/report.py on a small synthetic results folder: the report opens with a conclusion
whose figures come from the data, explains its columns, shows the stress verdicts as a grid, and
links each scene's replay page with its screenshot inline.

    python3 tests/report/report_test.py
"""
import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SCRIPTS = Path(__file__).resolve().parent.parent.parent / "scripts"


def run_entry(label, ms, gate=False, expect=None, verdict="ok"):
    entry = {"engine": label + ":spec", "label": label, "gate": gate,
             "ms_per_step": {"median": ms}, "metrics": {}, "counters": {},
             "expect": expect, "verdict": {"class": verdict, "detail": "", "findings": []}}
    if label == "bee":
        entry["caveat"] = "bee is a debug build"
    return entry


def scene(name, a_ms, b_ms, b_miss, family="stacking"):
    ant = run_entry("ant", a_ms, gate=True, expect={"pass": True, "max_error": 0.0})
    if name == "stack":  # a run with the worst frame; the others are older files without it
        ant["ms_per_step"].update({"p99": 0.0031, "max": 0.0042})
        ant["expect"].update({"max_speed_error": 0.0, "near_miss": False})
    return {"schema": "chainbench.run/1",
            "scene": {"name": name, "family": family, "bodies": 3, "steps": 60,
                      "expect": [{"kind": "center"}]},
            "reference": "bee:spec",
            "runs": [ant,
                     run_entry("bee", b_ms, expect={"pass": b_miss is None,
                                                     "max_error": b_miss or 0.001},
                               verdict="ok" if b_miss is None else "wrong")],
            "comparison": [{"engine": "ant:spec", "final_position_error": {"max": 0, "rms": 0},
                            "speedup": b_ms / a_ms}]}


def stress_case(case, group, label, verdict, known=None):
    c = {"case": case, "group": group, "label": label, "engine": label + ":spec",
         "verdict": verdict, "detail": "why"}
    if known:
        c["known_failure"] = known
    return c


class ReportTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        (root / "runs").mkdir()
        (root / "replay").mkdir()
        scenes = {"stack": scene("stack", 0.001, 0.01, None),
                  "pile": scene("pile", 0.002, 0.05, 1.5),
                  "row": scene("row", 0.004, 0.002, None, family="moving")}
        for name, data in scenes.items():
            (root / "runs" / f"{name}.json").write_text(json.dumps(data))
        for name in ("stack", "pile"):  # row has no replay page
            (root / "replay" / f"{name}.html").write_text("<html></html>")
            (root / "replay" / f"{name}.png").write_bytes(b"\x89PNG")
        (root / "replay" / "timings.json").write_text(json.dumps([
            {"page": "results/replay/stack.html", "bytes": 2_000_000, "steps": 60, "open_s": 0.4,
             "play_s": 0.3, "speed": 16},
            {"page": "results/replay/pile.html", "bytes": 500_000, "steps": 60, "open_s": 0.2,
             "play_s": 0.1, "speed": 16}]))
        cases = [stress_case("fast", "fast body", "ant", "tunnelled", known="no CCD"),
                 stress_case("fast", "fast body", "bee", "ok"),
                 stress_case("tall", "tall stack", "ant", "ok"),
                 stress_case("tall", "tall stack", "bee", "wrong"),
                 dict(stress_case("wide", "tall stack", "bee", "wrong"), near_miss=True)]
        (root / "stress.json").write_text(json.dumps({"schema": "chainbench.stress/1",
                                                      "cases": cases}))
        # The default suite's order, as scripts/run.sh leaves it: pile before stack; row, not in
        # it, after both.
        (root / "suite.txt").write_text("pile\nstack\n")
        result = subprocess.run([sys.executable, str(SCRIPTS / "report.py"), str(root)],
                                capture_output=True, text=True, timeout=60)
        assert result.returncode == 0, result.stderr
        cls.text = (root / "report.md").read_text()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def conclusion(self):
        start = self.text.index("## Conclusion")
        return self.text[start:self.text.index("## Summary")]

    def test_conclusion_comes_first_with_the_datas_figures(self):
        self.assertLess(self.text.index("## Conclusion"), self.text.index("## Summary"))
        c = self.conclusion()
        self.assertIn("For scenes like these, `ant`: it meets the stated answer on 3 of 3 scenes "
                      "and is the fastest on 2 of 3", c)
        # bee's time over ant's: 10x (stack), 25x (pile), 0.5x (row, a moving scene); every
        # ratio of bee's carries its caveat
        self.assertIn("On the moving scene (family `moving`, every body at work each step): "
                      "`bee`† 0.5x (`row`). On the other 2: `bee`† 10x (`stack`) to 25x (`pile`), "
                      "median 18x. † bee is a debug build.", c)
        self.assertIn("**Where `ant` loses.** `bee`† steps `row` 2.0x faster (0.002 against "
                      "0.004 ms per step).", c)
        self.assertIn("`bee` on 2 of 3 (misses `pile`; largest 1.5 m on `pile`)", c)
        self.assertIn("`ant` is ok on 1 of 2 (elsewhere 1 tunnelled; most in fast body (1); "
                      "1 listed known failure)", c)
        self.assertIn("Where it breaks (1 stress case: fast body), `bee` is ok on 1 of them", c)
        # A near miss is tallied apart from a clear one.
        self.assertIn("`bee` is ok on 1 of 3 (elsewhere 1 wrong, 1 wrong (near miss);", c)

    def test_scene_tables_show_the_slowest_step_where_the_run_has_it(self):
        self.assertIn("| engine | ms/step | max ms | x ref |", self.text)
        self.assertIn("| ant | 0.001 | 0.0042 |", self.text)
        self.assertIn("| ant | 0.002 | - |", self.text)  # pile: a file without max

    def test_expect_cells_keep_metres_and_speeds_apart(self):
        self.assertIn("| pass (0 m, rest 0 m/s) |", self.text)
        self.assertIn("| **FAIL** (1.5 m) |", self.text)

    def test_scenes_follow_the_suites_order(self):
        headings = [line for line in self.text.splitlines() if line.startswith("### ")]
        names = [h.split()[1].strip("`") for h in headings if h.split()[1].strip("`") in
                 ("pile", "stack", "row")]
        self.assertEqual(names, ["pile", "stack", "row"], headings)

    def test_columns_are_explained(self):
        self.assertIn("What the columns say:", self.text)
        self.assertIn("*EFD/body-step m*", self.text)

    def test_stress_is_a_grid(self):
        self.assertIn("| case | `ant` | `bee` |", self.text)
        self.assertIn("| wide | - | **wrong** |", self.text)
        self.assertIn("| fast | **tunnelled** (known) | ok |", self.text)

    def test_scenes_link_their_replay_with_its_screenshot(self):
        self.assertIn("[Replay: every engine's run of `stack`, step by step](replay/stack.html)",
                      self.text)
        self.assertIn("[![pile: the replay page at the last step](replay/pile.png)]"
                      "(replay/pile.html)", self.text)
        self.assertNotIn("replay/row.html", self.text)
        self.assertIn("The 2 pages take 2.5 MB together, the largest 2.0 MB (`stack.html`)",
                      self.text)


if __name__ == "__main__":
    unittest.main()
