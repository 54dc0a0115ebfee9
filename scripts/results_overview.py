#!/usr/bin/env python3
"""The benchmark overview of docs/results/overview.md, from the full runs' databases.

Reads out/bench-full/<config>/bench.db (made by scripts/run-full-bench.sh via
`mddual bench`), summarises them with scripts/bench_report.py, and writes one
compact table (per config and planner: success, median planning time and
invalid solutions of each checker, MDD's time over FCL discrete's, and the MDD
and FCL checkers' median time over the runs that returned a solution, valid or
not), the
targets with their verdicts as measured, and how often the two halves of the
strict verification agreed. The planning time is the planner's own solve time
(`median solve`, bench_report.py) when every database has it, else OMPL's. The text replaces what lies between the markers
`<!-- results:begin -->` and `<!-- results:end -->` in docs/results/overview.md
(--readme names another file; --readme - prints to standard output).

--headline FILE also writes the headline table (per config, the RRT-Connect
runs: success, median time and invalid solutions of each checker) between
`<!-- headline:begin -->` and `<!-- headline:end -->` of FILE (README.md), with
--made-by naming the command and build the databases come from.

    scripts/results_overview.py [--bench DIR] [--readme FILE|-] [--headline FILE] [--made-by TEXT]
"""

import argparse
import os
import sqlite3
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_report  # noqa: E402
import readme_markers  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
CONFIGS = ["thin_walls", "convex_field", "narrow_passage", "maze_se2", "cubicles"]
CHECKERS = ["mdd", "fcl", "fcl-continuous", "hull-cast"]
SHORT = {"fcl-continuous": "fcl-cont"}
BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"
HEADLINE_BEGIN, HEADLINE_END = "<!-- headline:begin -->", "<!-- headline:end -->"
HEADLINE_PLANNER = "rrtconnect"
SPACES = {"thin_walls": "R^3", "convex_field": "R^3", "narrow_passage": "SE(3)", "maze_se2": "SE(2)",
          "cubicles": "SE(3)"}


def translation_only(config):
    path = os.path.join(ROOT, "configs", config, config + ".cfg")
    with open(path) as f:
        return any(line.replace(" ", "").strip().lower() == "translation_only=true" for line in f)


def agreement(db_path):
    """(flagged by both checks, by the MDD check only, by the FCL check only) over invalid solutions."""
    db = sqlite3.connect(db_path)
    cols = bench_report.columns(db, "runs")
    if not {"invalid_by_mdd", "invalid_by_fcl"} <= cols:
        return (0, 0, 0)
    row = db.execute("select sum(invalid_by_mdd = 1 and invalid_by_fcl = 1), sum(invalid_by_mdd = 1 and "
                     "coalesce(invalid_by_fcl, 0) = 0), sum(coalesce(invalid_by_mdd, 0) = 0 and invalid_by_fcl = 1) "
                     "from runs where invalid_solution = 1").fetchone()
    return tuple(int(x or 0) for x in row)


def present(stats):
    """The checkers of CHECKERS that ran (hull-cast only in builds with Bullet)."""
    return [c for c in CHECKERS if any(k[2] == c for k in stats)]


def names(stats):
    return " / ".join(SHORT.get(c, c) for c in present(stats))


def triple(stats, config, planner, fn):
    """One cell: fn of each present checker's group, "-" where it has none."""
    return " / ".join(fn(stats[(config, planner, c)]) if (config, planner, c) in stats else "-"
                      for c in present(stats))


def gather(bench_dir):
    """(configs found, per-group statistics, (runs, limit) per config, verification agreement)."""
    stats, runs_limit, agree = {}, {}, [0, 0, 0]
    configs = [c for c in CONFIGS if os.path.exists(os.path.join(bench_dir, c, "bench.db"))]
    if not configs:
        raise SystemExit("results_overview: no %s/<config>/bench.db (run scripts/run-full-bench.sh)" % bench_dir)
    for c in configs:
        db = os.path.join(bench_dir, c, "bench.db")
        rows = bench_report.load(db)
        stats.update(bench_report.summarise(rows))
        per_group = {}
        for r in rows:
            per_group[(r["planner"], r["checker"])] = per_group.get((r["planner"], r["checker"]), 0) + 1
        runs_limit[c] = (max(per_group.values()), rows[0]["timelimit"])
        agree = [a + b for a, b in zip(agree, agreement(db))]
    return configs, stats, runs_limit, agree


def headline(bench_dir, target, made_by):
    """The README's table: one row per config, the RRT-Connect runs of every checker."""
    configs, stats, runs_limit, _ = gather(bench_dir)
    time_field, _, time_label = bench_report.planning_time_fields(stats)
    overview_page = os.path.join(ROOT, "docs", "results", "overview.md")
    link = (os.path.relpath(overview_page, os.path.dirname(os.path.abspath(target))) if target != "-"
            else "docs/results/overview.md")
    n = names(stats)
    lines = ["| config (runs x limit) | success %s | %s %s | invalid solutions %s |" % (n, time_label, n, n),
             "|---|---|---|---|"]
    for c in configs:
        p = HEADLINE_PLANNER
        if not any((c, p, k) in stats for k in CHECKERS):
            continue
        lines.append("| %s, %s, %d x %g s | %s | %s | %s |" % (
            c, SPACES.get(c, "?"), runs_limit[c][0], runs_limit[c][1],
            triple(stats, c, p, lambda s: "%.0f%%" % (100 * s["success"])),
            triple(stats, c, p, lambda s: bench_report.fmt(s[time_field])),
            triple(stats, c, p, lambda s: str(s["invalid"]))))
    text = ["Made by `scripts/results_overview.py --headline` from the databases of `%s`: the RRT-Connect "
            "rows of [docs/results/overview.md](%s), which has the other planners." % (made_by, link), ""]
    return "\n".join(text + lines) + "\n"


def overview(bench_dir):
    configs, stats, runs_limit, agree = gather(bench_dir)
    time_field, ratio_field, time_label = bench_report.planning_time_fields(stats)
    n = names(stats)
    lines = ["| config (runs x limit) | planner | success %s | %s %s | mdd / FCL | solved time (s) mdd / fcl "
             "| invalid %s |" % (n, time_label, n, n), "|---|---|---|---|---|---|---|"]
    verdicts, mdd_invalid, thin_fcl_invalid = [], 0, 0
    for c in configs:
        planners = sorted({k[1] for k in stats if k[0] == c})
        for p in planners:
            mdd, fcl = stats.get((c, p, "mdd")), stats.get((c, p, "fcl"))
            space = " (translation)" if translation_only(c) else ""
            lines.append("| %s%s, %d x %gs | %s | %s | %s | %s | %s | %s |" % (
                c, space, runs_limit[c][0], runs_limit[c][1], p,
                triple(stats, c, p, lambda s: "%.0f%%" % (100 * s["success"])),
                triple(stats, c, p, lambda s: bench_report.fmt(s[time_field])),
                bench_report.fmt(mdd[ratio_field], 2) if mdd else "-",
                " / ".join(bench_report.fmt(x["solved_time"]) if x else "-" for x in (mdd, fcl)),
                triple(stats, c, p, lambda s: str(s["invalid"]))))
            if mdd:
                mdd_invalid += mdd["invalid"]
            if c == "thin_walls" and fcl:
                thin_fcl_invalid += fcl["invalid"]
            if translation_only(c) and mdd and fcl:
                met = mdd[ratio_field] <= 0.5 and mdd["success"] >= fcl["success"]
                verdicts.append("%s %s: MDD median %s s vs FCL %s s (ratio %s), success %.0f%% vs %.0f%%: %s" % (
                    c, p, bench_report.fmt(mdd[time_field]), bench_report.fmt(fcl[time_field]),
                    bench_report.fmt(mdd[ratio_field], 2), 100 * mdd["success"], 100 * fcl["success"],
                    "met" if met else "missed"))
    text = ["Made by `scripts/results_overview.py` from the databases of `scripts/run-full-bench.sh` "
            "(per-config tables, commands and plots: docs/results/README.md).", ""]
    text += lines + [""]
    text.append("Targets as measured:")
    text.append("")
    text.append("- translation-only configs, MDD's %s at most half of FCL discrete's at the same or "
                "better success:" % time_label.replace(" (s)", ""))
    text += ["  - " + v for v in verdicts]
    text.append("- zero invalid solutions from the MDD checker on every config: %d invalid (%s)"
                % (mdd_invalid, "met" if mdd_invalid == 0 else "missed"))
    text.append("- thin_walls shows FCL discrete returning invalid solutions: %d invalid (%s)"
                % (thin_fcl_invalid, "met" if thin_fcl_invalid > 0 else "missed"))
    text.append("- the two halves of the verification: of the invalid solutions (all checkers), %d were found by "
                "both the exact MDD edge check and the dense FCL check, %d by the MDD check only, %d by the FCL "
                "check only" % tuple(agree))
    return "\n".join(text) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", default=os.path.join(ROOT, "out", "bench-full"))
    parser.add_argument("--readme", default=readme_markers.default_target("overview.md"),
                        help="replace the text between the results markers in this file (default: "
                        "docs/results/overview.md; - prints)")
    parser.add_argument("--headline", help="also write the headline table between the headline markers of this "
                        "file (README.md; - prints)")
    parser.add_argument("--made-by", default="scripts/run-full-bench.sh",
                        help="the command and build the databases come from, for the headline's first line")
    args = parser.parse_args()
    text = overview(args.bench)
    readme_markers.replace_between(args.readme, BEGIN, END, text, "results_overview")
    if args.headline:
        readme_markers.replace_between(args.headline, HEADLINE_BEGIN, HEADLINE_END,
                                       headline(args.bench, args.headline, args.made_by), "results_overview")


if __name__ == "__main__":
    main()
