#!/usr/bin/env python3
"""scripts/arm_headline.py: one line per (robot, set) from the planner's rows
of run-arm-bench.sh's pages, a checker a page lacks shown as "-", the
planner's own solve time where every page has it (else OMPL's time), filed
between the README's arm markers; a page that is not run-arm-bench.sh's, a
short row, a table without a needed column and a planner without rows
refused."""

import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "arm_headline.py")
HEADER = ("| config | planner | checker | runs | success | median time (s) | time / FCL | median solve (s) | "
          "solve / FCL | solved time (s) | checking | state checks | motion checks | invalid | invalid raw |")
# Pages written before bench_report.py had the planner's own solve time.
OLD_HEADER = ("| config | planner | checker | runs | success | median time (s) | time / FCL | solved time (s) | "
              "checking | state checks | motion checks | invalid | invalid raw |")


def page(robot, rows, made="Made by `run X` at abc123 on 2026-12-06, 2 cores; seed 1.", old=False):
    """rows: (set, planner, checker, success, median time, invalid); the
    solve time is a tenth of the time, so that the two cannot be confused."""
    if old:
        body = "\n".join("| %s | %s | %s | 6 | %s | %s | 1 | 0.1 | 90%% | 10 | 5 | %s | 0 |" % r for r in rows)
    else:
        body = "\n".join("| %s | %s | %s | 6 | %s | %s | 1 | %g | 1 | 0.1 | 90%% | 10 | 5 | %s | 0 |"
                         % (r[:5] + (float(r[4]) / 10, r[5])) for r in rows)
    return "# %s on its MotionBenchMaker problem sets\n\n%s\n\n%s\n|---|\n%s\n\n" % (
        robot, made, OLD_HEADER if old else HEADER, body)


class ArmHeadline(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.readme = os.path.join(self.tmp.name, "README.md")
        with open(self.readme, "w") as f:
            f.write("before\n<!-- arms:begin -->\nold\n<!-- arms:end -->\nafter\n")

    def tearDown(self):
        self.tmp.cleanup()

    def run_script(self, pages, *extra):
        paths = []
        for i, text in enumerate(pages):
            paths.append(os.path.join(self.tmp.name, "page%d.md" % i))
            with open(paths[-1], "w") as f:
                f.write(text)
        return subprocess.run([sys.executable, SCRIPT, "--results"] + paths + ["--readme", self.readme] + list(extra),
                              capture_output=True, text=True)

    def test_one_line_per_robot_and_set(self):
        arm7 = page("arm7", [("cage", "RRTConnectkConfigDefault", "mdd", "100%", "0.07", "0"),
                             ("cage", "RRTConnectkConfigDefault", "fcl", "83%", "0.05", "1"),
                             ("cage", "BKPIECEGood", "mdd", "50%", "9", "0"),
                             ("box", "RRTConnectkConfigDefault", "mdd", "100%", "0.002", "0")])
        panda = page("panda", [("box", "RRTConnectkConfigDefault", "hull-cast", "75%", "2.3", "2")])
        result = self.run_script([arm7, panda])
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.readme) as f:
            text = f.read()
        self.assertTrue(text.startswith("before\n<!-- arms:begin -->\nMade by `scripts/arm_headline.py` from the "
                                        "RRTConnectkConfigDefault rows of docs/results (arm7: `run X` at abc123; "
                                        "panda: `run X` at abc123).\n"))
        self.assertIn("| robot, set | success mdd / fcl / hull-cast | median solve (s) mdd / fcl / hull-cast "
                      "| invalid solutions mdd / fcl / hull-cast |\n|---|---|---|---|\n"
                      "| arm7, cage | 100% / 83% / - | 0.007 / 0.005 / - | 0 / 1 / - |\n"
                      "| arm7, box | 100% / - / - | 0.0002 / - / - | 0 / - / - |\n"
                      "| panda, box | - / - / 75% | - / - / 0.23 | - / - / 2 |\n<!-- arms:end -->\nafter\n", text)
        self.assertNotIn("old", text)
        self.assertNotIn("| 0.9 |", text)  # the BKPIECE row is not this planner's

    def test_a_robots_second_page_goes_by_its_file_name(self):
        first = page("panda", [("box", "RRTConnectkConfigDefault", "mdd", "100%", "0.07", "0")])
        second = page("panda", [("mbm_box", "RRTConnectkConfigDefault", "mdd", "90%", "0.5", "0")])
        result = self.run_script([first, second])
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.readme) as f:
            text = f.read()
        self.assertIn("(panda: `run X` at abc123; page1: `run X` at abc123).\n", text)
        self.assertIn("| panda, mbm_box | 90% | 0.05 | 0 |\n", text)

    def test_a_page_without_solve_times_gives_ompls_times(self):
        new = page("arm7", [("cage", "RRTConnectkConfigDefault", "mdd", "100%", "0.07", "0")])
        old = page("panda", [("box", "RRTConnectkConfigDefault", "mdd", "100%", "0.5", "0")], old=True)
        result = self.run_script([new, old])
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.readme) as f:
            text = f.read()
        self.assertIn("| robot, set | success mdd | median time (s) mdd | invalid solutions mdd |", text)
        self.assertIn("| arm7, cage | 100% | 0.07 | 0 |\n| panda, box | 100% | 0.5 | 0 |", text)
        # A new table from old logs: the column is there, its cells "-".
        dashed = page("panda", [("box", "RRTConnectkConfigDefault", "mdd", "100%", "0.5", "0")])
        dashed = dashed.replace("| 0.05 |", "| - |")
        result = self.run_script([new, dashed])
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.readme) as f:
            text = f.read()
        self.assertIn("| arm7, cage | 100% | 0.07 | 0 |\n| panda, box | 100% | 0.5 | 0 |", text)

    def test_refuses_bad_pages_and_an_unknown_planner(self):
        result = self.run_script(["# something else\n"])
        self.assertIn("not a page of scripts/run-arm-bench.sh", result.stderr)
        short = page("arm7", []).replace("|---|\n", "|---|\n| cage | mdd | 100% |\n")
        result = self.run_script([short])
        self.assertIn("not a row of 15 cells", result.stderr)
        result = self.run_script([page("arm7", []).replace("| invalid |", "| broken |")])
        self.assertIn("the summary table has no column invalid", result.stderr)
        good = page("arm7", [("cage", "RRTConnectkConfigDefault", "mdd", "100%", "0.07", "0")])
        result = self.run_script([good], "--planner", "PRM")
        self.assertIn("no row of planner PRM", result.stderr)
        self.assertNotEqual(result.returncode, 0)


if __name__ == "__main__":
    unittest.main()
