#!/usr/bin/env python3
"""scripts/mesh_results.py on small databases of known runs: the verdicts, the
counted times, the time per motion check and the order of the groups."""

import os
import sqlite3
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import mesh_results  # noqa: E402


def write_db(path, config, planner, runs_by_checker, limit=10.0):
    """runs_by_checker: checker -> list of (time, solved, verified, checking_time, motion_checks)."""
    db = sqlite3.connect(path)
    db.execute("create table experiments (id integer primary key, config text, checker text, timelimit real)")
    db.execute("create table plannerConfigs (id integer primary key, name text)")
    db.execute("create table runs (id integer primary key, experimentid integer, plannerid integer, time real, "
               "solved integer, approximate_solution integer, verified integer, invalid_solution integer, "
               "checking_time real, motion_checks integer)")
    db.execute("insert into plannerConfigs values (1, ?)", ("geometric_" + planner,))
    for e, (checker, runs) in enumerate(sorted(runs_by_checker.items()), start=1):
        db.execute("insert into experiments values (?, ?, ?, ?)", (e, config, checker, limit))
        for time, solved, verified, checking, checks in runs:
            db.execute("insert into runs (experimentid, plannerid, time, solved, approximate_solution, verified, "
                       "invalid_solution, checking_time, motion_checks) values (?, 1, ?, ?, 0, ?, ?, ?, ?)",
                       (e, time, solved, verified, int(solved and not verified), checking, checks))
    db.commit()
    db.close()


class Repeats(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def group(self, config, planner, runs_by_checker):
        os.makedirs(os.path.join(self.dir, "%s-%s" % (config, planner)))
        write_db(os.path.join(self.dir, "%s-%s" % (config, planner), "bench.db"), config, planner, runs_by_checker)

    def rows(self):
        text = mesh_results.repeats(self.dir, "test")
        return text, [line for line in text.splitlines() if line.startswith("| ") and "(3 x 10s)" in line]

    def test_invalid_paths_count_at_the_limit_and_decide_the_verdict(self):
        # MDD: 1, 2, 3 s, all verified (median 2). FCL: 0.5 s valid, two
        # invalid paths counted at the 10 s limit (median 10): ratio 0.2, met.
        self.group("bugtrap", "rrt", {
            "mdd": [(1.0, 1, 1, 0.5, 100), (2.0, 1, 1, 1.0, 200), (3.0, 1, 1, 1.5, 300)],
            "fcl": [(0.5, 1, 1, 0.2, 10), (0.6, 1, 0, 0.3, 10), (0.7, 1, 0, 0.5, 20)]})
        text, rows = self.rows()
        self.assertEqual(len(rows), 1)
        cells = [c.strip() for c in rows[0].split("|")[1:-1]]
        self.assertEqual(cells[0], "bugtrap, rrt (3 x 10s)")
        self.assertEqual(cells[1], "3 of 3 / 1 of 3")
        self.assertEqual(cells[2], "2 / 10")
        self.assertEqual(cells[3], "0.2")
        self.assertEqual(cells[4], "0 / 2")
        self.assertEqual(cells[5], "2 / 0.6")  # solved time: every returned path, valid or not
        self.assertEqual(cells[6], "5e+03 / 2.5e+04")  # 3 s over 600 checks; 1 s over 40
        self.assertEqual(cells[7], "met")
        self.assertIn("met in 1 of 1 groups", text)

    def test_lower_success_misses_even_with_a_lower_median(self):
        # MDD solves one of three (median 10, counted at the limit), FCL none:
        # ratio 1, missed; then a group where MDD is faster but solves less.
        # Their folders sort the other way round from the configs' order.
        self.group("twistycool", "kpiece", {
            "mdd": [(1.0, 1, 1, 0.1, 1), (10.0, 0, 0, 1.0, 1), (10.0, 0, 0, 1.0, 1)],
            "fcl": [(10.0, 0, 0, 1.0, 1), (10.0, 0, 0, 1.0, 1), (10.0, 0, 0, 1.0, 1)]})
        self.group("cubicles_mesh", "kpiece", {
            "mdd": [(1.0, 1, 1, 0.1, 1), (1.0, 1, 1, 0.1, 1), (10.0, 0, 0, 1.0, 1)],
            "fcl": [(4.0, 1, 1, 0.1, 1), (4.0, 1, 1, 0.1, 1), (4.0, 1, 1, 0.1, 1)]})
        text, rows = self.rows()
        # twistycool before cubicles_mesh (the configs' order), not by folder name.
        self.assertTrue(rows[0].startswith("| twistycool, kpiece"))
        self.assertTrue(rows[1].startswith("| cubicles_mesh, kpiece"))
        self.assertTrue(rows[0].rstrip().endswith("| **missed** |"))  # ratio 1
        self.assertTrue(rows[1].rstrip().endswith("| **missed** |"))  # 0.25 but 2 of 3 against 3 of 3
        self.assertIn("met in 0 of 2 groups", text)

    def test_an_empty_folder_is_an_error_naming_it(self):
        with self.assertRaises(SystemExit) as e:
            mesh_results.repeats(self.dir, "test")
        self.assertIn(self.dir, str(e.exception))


if __name__ == "__main__":
    unittest.main()
