#!/usr/bin/env python3
"""Summary table and plots of an mddual benchmark database.

The database is the one `ompl_benchmark_statistics` builds from the OMPL
benchmark logs that `mddual bench` writes (one log per checker and shard).
Runs are grouped by config, planner and checker (experiment parameters
`config` and `checker`, set by `mddual bench`), so the logs of several
shards merge here.

    scripts/bench_report.py --db out/bench/thin_walls/bench.db [--plots DIR] [--markdown FILE]

Per config, planner and checker:
  runs            runs in the database (all shards);
  success         runs whose exact solution the strict verification found
                  collision-free (run property `verified`), over all runs;
  median time     median planning time over all runs, a run without a verified
                  solution counting at the time limit (unsolved, approximate
                  and invalid solutions alike);
  time / FCL      that median over the same planner's with the `fcl` checker
                  (FCL states + OMPL's discrete motion validator);
  median solve    the same median over the planner's own solve() time (run
                  property `solve time`, measured around the planner alone):
                  OMPL 1.5's benchmark "time" also holds the stop of its
                  termination-condition thread, up to 1 ms per run whatever
                  the checker, which hides the checker's share on runs of a
                  millisecond ("-" for logs without the property);
  solve / FCL     that median over the same planner's with the `fcl` checker;
  solved time     median planning time (the planner's solve time where the
                  logs have it, else OMPL's) of the runs that returned an
                  exact solution, valid or not ("-" if none): the planner's
                  raw speed;
  checking        median share of the planner's solve time (OMPL's time for
                  logs without `solve time`) spent in the checkers (run
                  property `checking time`);
  state / motion checks   medians over all runs;
  invalid         exact solutions the verification found in collision (its
                  exact MDD edge check or its dense FCL check);
  invalid raw     of the runs that were simplified, those whose path before
                  simplification was already invalid.
Runs whose verification failed with an error (`verification error`) count as
neither verified nor invalid and are listed under the table.

Run properties read (columns of `runs`): time, solve_time, solved, approximate_solution,
state_checks, motion_checks, pair_queries, checking_time, verified,
invalid_solution, invalid_raw_solution, verification_error. Python standard
library, plus matplotlib (Debian's python3-matplotlib) for the plots.
"""

import argparse
import math
import os
import sqlite3
import sys

CHECKER_ORDER = ["mdd", "fcl", "fcl-continuous", "fcl-fine"]


def median(values):
    values = sorted(v for v in values if v is not None)
    if not values:
        return float("nan")
    n = len(values)
    return values[n // 2] if n % 2 else 0.5 * (values[n // 2 - 1] + values[n // 2])


def columns(db, table):
    return {row[1] for row in db.execute("pragma table_info(%s)" % table)}


def load(db_path):
    """Rows: dict per run with config, checker, planner and the run's fields."""
    db = sqlite3.connect(db_path)
    exp_cols = columns(db, "experiments")
    run_cols = columns(db, "runs")
    for needed in ("config", "checker"):
        if needed not in exp_cols:
            raise SystemExit("bench_report: %s: experiments have no '%s' parameter (not written by mddual bench?)"
                             % (db_path, needed))
    wanted = ["time", "solve_time", "solved", "approximate_solution", "state_checks", "motion_checks", "pair_queries",
              "checking_time", "invalid_solution", "verified", "invalid_raw_solution", "verification_error",
              "run_index", "memory", "verification_time", "verification_mdd_time", "verification_fcl_time"]
    present = [c for c in wanted if c in run_cols]
    query = ("select e.config, e.checker, e.timelimit, p.name, %s from runs r "
             "join experiments e on r.experimentid = e.id join plannerConfigs p on r.plannerid = p.id"
             % ", ".join("r." + c for c in present))
    rows = []
    for rec in db.execute(query):
        name = rec[3]
        if name.startswith("geometric_"):
            name = name[len("geometric_"):]
        row = {"config": rec[0], "checker": rec[1], "timelimit": rec[2], "planner": name}
        row.update(dict(zip(present, rec[4:])))
        rows.append(row)
    return rows


def exact(r):
    return bool(r.get("solved")) and not r.get("approximate_solution")


def verified(r):
    """A run whose exact solution passed the verification."""
    if "verified" in r:
        return bool(r.get("verified"))
    return exact(r) and not r.get("invalid_solution")  # databases without the property


def counted_time(r, field="time"):
    """Planning time (OMPL's `time`, or `solve_time`) of a run with a verified
    solution, else the time limit; None for a verified run without the field."""
    if not verified(r):
        return r["timelimit"]
    return r.get(field)


def planner_time(r):
    """The planner's own solve time where the log has it, else OMPL's time."""
    return r["solve_time"] if r.get("solve_time") is not None else r.get("time")


def summarise(rows):
    groups = {}
    for r in rows:
        groups.setdefault((r["config"], r["planner"], r["checker"]), []).append(r)
    stats = {}
    for key, runs in groups.items():
        solved = [r for r in runs if exact(r)]
        shares = [r["checking_time"] / planner_time(r) for r in runs
                  if r.get("checking_time") is not None and planner_time(r)]
        solves = [counted_time(r, "solve_time") for r in runs]
        stats[key] = {
            "runs": len(runs),
            "verified": sum(1 for r in runs if verified(r)),
            "success": sum(1 for r in runs if verified(r)) / len(runs),
            "median_time": median([counted_time(r) for r in runs]),
            # Only when every run has it: a median over some runs would mislead.
            "median_solve": median(solves) if None not in solves else float("nan"),
            "solved_time": median([planner_time(r) for r in solved]),
            "checking_share": median(shares),
            "state_checks": median([r.get("state_checks") for r in runs]),
            "motion_checks": median([r.get("motion_checks") for r in runs]),
            "invalid": sum(1 for r in solved if r.get("invalid_solution")),
            "invalid_raw": sum(1 for r in solved if r.get("invalid_raw_solution")),
            "errors": [r.get("verification_error") for r in runs if r.get("verification_error")],
            "solved": len(solved),
        }
    for (config, planner, checker), s in stats.items():
        fcl = stats.get((config, planner, "fcl"))
        s["ratio"] = s["median_time"] / fcl["median_time"] if fcl and fcl["median_time"] > 0 else float("nan")
        s["solve_ratio"] = (s["median_solve"] / fcl["median_solve"]
                            if fcl and fcl["median_solve"] > 0 else float("nan"))
    return stats


def planning_time_fields(stats):
    """The fields a table of planning times reads: the planner's own solve
    time and its ratio to FCL's where every group has it, else OMPL's time
    (databases of logs without `solve time`), with the column's label."""
    if stats and all(not math.isnan(s["median_solve"]) for s in stats.values()):
        return "median_solve", "solve_ratio", "median solve (s)"
    return "median_time", "ratio", "median time (s)"


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if isinstance(x, float):
        return "%.*g" % (digits, x)
    return str(x)


def order(key):
    config, planner, checker = key
    rank = CHECKER_ORDER.index(checker) if checker in CHECKER_ORDER else len(CHECKER_ORDER)
    return (config, planner, rank, checker)


def markdown(stats):
    lines = ["| config | planner | checker | runs | success | median time (s) | time / FCL | median solve (s) | "
             "solve / FCL | solved time (s) | checking | state checks | motion checks | invalid | invalid raw |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for key in sorted(stats, key=order):
        s = stats[key]
        share = "-" if math.isnan(s["checking_share"]) else "%.0f%%" % (100 * s["checking_share"])
        lines.append("| %s | %s | %s | %d | %.0f%% | %s | %s | %s | %s | %s | %s | %s | %s | %d | %d |" % (
            key[0], key[1], key[2], s["runs"], 100 * s["success"], fmt(s["median_time"]), fmt(s["ratio"], 2),
            fmt(s["median_solve"]), fmt(s["solve_ratio"], 2), fmt(s["solved_time"]), share, fmt(s["state_checks"], 4), fmt(s["motion_checks"], 4), s["invalid"],
            s["invalid_raw"]))
    notes = []
    for key in sorted(stats, key=order):
        for e in stats[key]["errors"]:
            notes.append("- verification error (%s, %s, %s): %s" % (key[0], key[1], key[2], e))
    text = "\n".join(lines) + "\n"
    if notes:
        text += "\n" + "\n".join(notes) + "\n"
    return text


def plot(rows, stats, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs(out_dir, exist_ok=True)
    written = []
    for config in sorted({k[0] for k in stats}):
        planners = sorted({k[1] for k in stats if k[0] == config})
        checkers = [c for c in CHECKER_ORDER if any(k[0] == config and k[2] == c for k in stats)]
        checkers += sorted({k[2] for k in stats if k[0] == config} - set(checkers))
        fig, axes = plt.subplots(2, 2, figsize=(12, 8))
        width = 0.8 / max(1, len(checkers))
        for ci, checker in enumerate(checkers):
            xs = [i + (ci - (len(checkers) - 1) / 2) * width for i in range(len(planners))]
            times = [[planner_time(r) for r in rows if r["config"] == config and r["planner"] == p and
                      r["checker"] == checker and planner_time(r) is not None] or [float("nan")] for p in planners]
            box = axes[0][0].boxplot(times, positions=xs, widths=width * 0.9, patch_artist=True, showfliers=False)
            for patch in box["boxes"]:
                patch.set_facecolor("C%d" % ci)
            get = lambda field: [stats.get((config, p, checker), {}).get(field, 0) or 0 for p in planners]
            axes[0][1].bar(xs, [100 * v for v in get("success")], width, color="C%d" % ci, label=checker)
            axes[1][0].bar(xs, get("motion_checks"), width, color="C%d" % ci)
            axes[1][1].bar(xs, get("invalid"), width, color="C%d" % ci)
        titles = ["planner's solve time of every run (s; valid, invalid or none)",
                  "success rate (%, verified solutions)", "motion checks (median)",
                  "invalid solutions (count)"]
        for ax, title in zip(axes.flat, titles):
            ax.set_title(title, fontsize=10)
            ax.set_xticks(range(len(planners)))
            ax.set_xticklabels(planners, rotation=20)
        most_invalid = max([stats[k]["invalid"] for k in stats if k[0] == config] + [0])
        axes[1][1].set_ylim(0, max(1, most_invalid) * 1.15)
        axes[0][0].set_yscale("log")
        axes[1][0].set_yscale("symlog")
        axes[0][1].set_ylim(0, 105)
        handles, labels = axes[0][1].get_legend_handles_labels()
        fig.legend(handles, labels, title="checker", loc="upper right", ncol=len(checkers), fontsize=9)
        runs = max([stats[k]["runs"] for k in stats if k[0] == config] + [0])
        fig.suptitle("%s: checkers compared per planner (%d runs each)" % (config, runs), x=0.02, ha="left")
        fig.tight_layout(rect=(0, 0, 1, 0.92))
        path = os.path.join(out_dir, "%s.png" % config)
        fig.savefig(path, dpi=80)
        plt.close(fig)
        written.append(path)
    return written


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--db", required=True, help="database built by ompl_benchmark_statistics")
    parser.add_argument("--plots", help="folder for the PNG plots (one per config)")
    parser.add_argument("--markdown", help="write the summary table there too")
    args = parser.parse_args()
    if not os.path.exists(args.db):
        raise SystemExit("bench_report: no database '%s'" % args.db)
    rows = load(args.db)
    if not rows:
        raise SystemExit("bench_report: '%s' holds no runs" % args.db)
    stats = summarise(rows)
    table = markdown(stats)
    sys.stdout.write(table)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(table)
    if args.plots:
        for path in plot(rows, stats, args.plots):
            print("plot: %s" % path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
