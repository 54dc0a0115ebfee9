#!/usr/bin/env python3
"""scripts/bench_report.py on small databases of known runs: the planner's own
solve time beside OMPL's time (its median, its ratio to FCL's, the checking
share over it), runs without a verified solution at the limit whichever time
is read, and databases of older logs (no solve time) falling back to OMPL's."""

import math
import os
import sqlite3
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import bench_report  # noqa: E402


def write_db(path, runs_by_checker, solve_time=True, limit=10.0):
    """runs_by_checker: checker -> list of (time, solve_time, solved, verified, checking_time)."""
    db = sqlite3.connect(path)
    db.execute("create table experiments (id integer primary key, config text, checker text, timelimit real)")
    db.execute("create table plannerConfigs (id integer primary key, name text)")
    db.execute("create table runs (id integer primary key, experimentid integer, plannerid integer, time real, "
               "solved integer, approximate_solution integer, verified integer, invalid_solution integer, "
               "checking_time real%s)" % (", solve_time real" if solve_time else ""))
    db.execute("insert into plannerConfigs values (1, 'geometric_rrtconnect')")
    for e, (checker, runs) in enumerate(sorted(runs_by_checker.items()), start=1):
        db.execute("insert into experiments values (?, 'tiny', ?, ?)", (e, checker, limit))
        for time, solve, solved, verified, checking in runs:
            values = [e, time, solved, verified, int(solved and not verified), checking]
            columns = "experimentid, plannerid, time, solved, approximate_solution, verified, invalid_solution, " \
                      "checking_time"
            if solve_time:
                values.append(solve)
                columns += ", solve_time"
            db.execute("insert into runs (%s) values (?, 1, ?, ?, 0, ?, ?, ?%s)"
                       % (columns, ", ?" if solve_time else ""), values)
    db.commit()
    db.close()


# Every run's OMPL time is its solve time plus 1 ms (the harness's thread).
RUNS = {
    # mdd: solves in 0.1, 0.2, 0.3 ms, all verified; checking half of each.
    "mdd": [(0.0011, 0.0001, 1, 1, 0.00005), (0.0012, 0.0002, 1, 1, 0.0001), (0.0013, 0.0003, 1, 1, 0.00015)],
    # fcl: 0.4 and 0.6 ms verified, one invalid path (counted at the limit).
    "fcl": [(0.0014, 0.0004, 1, 1, 0.0002), (0.0016, 0.0006, 1, 1, 0.0003), (0.0015, 0.0005, 1, 0, 0.0001)],
}


class BenchReport(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.db = os.path.join(self.tmp.name, "bench.db")

    def tearDown(self):
        self.tmp.cleanup()

    def stats(self, **kwargs):
        write_db(self.db, RUNS, **kwargs)
        return bench_report.summarise(bench_report.load(self.db))

    def test_solve_time_beside_ompls_time(self):
        s = self.stats()
        mdd, fcl = s[("tiny", "rrtconnect", "mdd")], s[("tiny", "rrtconnect", "fcl")]
        self.assertAlmostEqual(mdd["median_time"], 0.0012)
        self.assertAlmostEqual(mdd["median_solve"], 0.0002)
        self.assertAlmostEqual(fcl["median_time"], 0.0016)   # 1.4, 1.6 ms and the limit
        self.assertAlmostEqual(fcl["median_solve"], 0.0006)  # 0.4, 0.6 ms and the limit
        self.assertAlmostEqual(mdd["ratio"], 0.0012 / 0.0016)
        self.assertAlmostEqual(mdd["solve_ratio"], 0.0002 / 0.0006)
        self.assertAlmostEqual(mdd["checking_share"], 0.5)  # over the solve time, not OMPL's
        self.assertAlmostEqual(mdd["solved_time"], 0.0002)
        self.assertEqual(bench_report.planning_time_fields(s), ("median_solve", "solve_ratio", "median solve (s)"))
        table = bench_report.markdown(s)
        self.assertIn("| median solve (s) | solve / FCL |", table)
        self.assertIn("| tiny | rrtconnect | mdd | 3 | 100% | 0.0012 | 0.75 | 0.0002 | 0.33 | 0.0002 | 50% |", table)

    def test_older_logs_fall_back_to_ompls_time(self):
        s = self.stats(solve_time=False)
        mdd = s[("tiny", "rrtconnect", "mdd")]
        self.assertTrue(math.isnan(mdd["median_solve"]))
        self.assertTrue(math.isnan(mdd["solve_ratio"]))
        self.assertAlmostEqual(mdd["checking_share"], 0.0001 / 0.0012)  # the median of the shares
        self.assertAlmostEqual(mdd["solved_time"], 0.0012)
        self.assertEqual(bench_report.planning_time_fields(s), ("median_time", "ratio", "median time (s)"))
        self.assertIn("| tiny | rrtconnect | mdd | 3 | 100% | 0.0012 | 0.75 | - | - | 0.0012 |",
                      bench_report.markdown(s))

    def test_a_run_without_a_verified_solution_counts_at_the_limit_without_a_time(self):
        runs = {"mdd": RUNS["mdd"], "fcl": [(None, None, 0, 0, 0.0), (None, None, 0, 0, 0.0),
                                            (0.0014, 0.0004, 1, 1, 0.0002)]}
        write_db(self.db, runs)
        s = bench_report.summarise(bench_report.load(self.db))
        fcl = s[("tiny", "rrtconnect", "fcl")]
        self.assertEqual(fcl["median_time"], 10.0)
        self.assertEqual(fcl["median_solve"], 10.0)


if __name__ == "__main__":
    unittest.main()
