#!/usr/bin/env python3
"""The mesh-config results of docs/results/mesh.md, from `mddual bench` databases.

Reads <bench>/<config>/bench.db for the mesh configs (bugtrap, twistycool,
cubicles_mesh, apartment, maze_planar; made by scripts/run-mesh-bench.sh),
and writes one table: per config and planner, success, median planning time
(runs without a verified solution count at the time limit), MDD's median over
FCL discrete's, the longest run against the limit (does a run end near its
limit?), invalid solutions, the median share of planning time spent in the
checkers (where it is small, a faster checker cannot make the planner much
faster), median peak memory, and the median verification time per solved
run, the checkers' time per motion check (their summed time over the summed
motion checks of the group's runs: state checks included, as OMPL counts
them), then the targets with their verdicts as measured.
The text replaces what lies between `<!-- mesh-results:begin -->` and
`<!-- mesh-results:end -->` in docs/results/mesh.md (--readme names another
file, --readme - prints to standard output; --marker names other markers).

--repeats DIR reads DIR/<config>-<planner>/bench.db instead (one `mddual
bench` run per group, e.g. 30 runs of the groups nearest the target) and
writes one row per group with the verdict of each (markers mesh-repeats).

    scripts/mesh_results.py [--bench out/bench-mesh] [--readme FILE|-] [--command TEXT]
    scripts/mesh_results.py --repeats out/bench-check30 [--readme FILE|-] [--command TEXT]
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_report  # noqa: E402
import readme_markers  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
CONFIGS = ["bugtrap", "twistycool", "cubicles_mesh", "apartment", "maze_planar"]
CHECKERS = ["mdd", "fcl"]
MARKER = "mesh-results"


def pair(values, fn):
    return " / ".join(fn(v) if v is not None else "-" for v in values)


def share(s):
    """The median share of planning time spent in the checkers, as a percentage."""
    v = s.get("checking_share")
    return "-" if v is None or math.isnan(v) else "%.0f%%" % (100 * v)


def median_of(rows, key):
    vals = [r[key] for r in rows if r.get(key) is not None]
    return bench_report.median(vals) if vals else None


def per_check(rows):
    """The checkers' summed time over the summed motion checks, in microseconds."""
    t = sum(r.get("checking_time") or 0.0 for r in rows)
    n = sum(r.get("motion_checks") or 0 for r in rows)
    return 1e6 * t / n if n else None


def verdict(mdd, fcl):
    """The planning target: at most half of FCL's median (a NaN ratio fails) at the same or better success."""
    return mdd["ratio"] <= 0.5 and mdd["success"] >= fcl["success"]


def repeats(repeat_dir, command, marker="mesh-repeats"):
    """One row per <config>-<planner> folder of repeat_dir, in CONFIGS order."""
    lines = ["| config, planner (runs x limit) | success mdd / fcl | median time (s) mdd / fcl | mdd / FCL | "
             "invalid mdd / fcl | solved time (s) mdd / fcl | per motion check (us) mdd / fcl | target |",
             "|---|---|---|---|---|---|---|---|"]
    groups = []
    for name in sorted(os.listdir(repeat_dir)):
        db = os.path.join(repeat_dir, name, "bench.db")
        if os.path.exists(db):
            rows = bench_report.load(db)
            c = rows[0]["config"] if rows else name
            groups.append((CONFIGS.index(c) if c in CONFIGS else len(CONFIGS), name, rows))
    if not groups:
        raise SystemExit("mesh_results: no %s/<config>-<planner>/bench.db" % repeat_dir)
    n_met = 0
    for _, name, rows in sorted(groups, key=lambda g: (g[0], g[1])):
        stats = bench_report.summarise(rows)
        for (c, p, k), mdd in sorted(stats.items()):
            fcl = stats.get((c, p, "fcl"))
            if k != "mdd" or not fcl:
                continue
            group = [[r for r in rows if r["planner"] == p and r["checker"] == ck] for ck in CHECKERS]
            met = verdict(mdd, fcl)
            n_met += met
            lines.append("| %s, %s (%d x %gs) | %s | %s | %s | %s | %s | %s | %s |" % (
                c, p, max(mdd["runs"], fcl["runs"]), group[0][0]["timelimit"],
                pair([mdd, fcl], lambda s: "%d of %d" % (s["verified"], s["runs"])),
                pair([mdd, fcl], lambda s: bench_report.fmt(s["median_time"])),
                bench_report.fmt(mdd["ratio"], 2),
                pair([mdd, fcl], lambda s: str(s["invalid"])),
                pair([mdd, fcl], lambda s: bench_report.fmt(s["solved_time"])),
                pair([per_check(g) for g in group], lambda t: "%.3g" % t),
                "met" if met else "**missed**"))
    text = ["Made by `scripts/mesh_results.py --repeats DIR%s` from `%s`: "
            "the target (median at most half of FCL's at the same or better success) met in %d of %d groups. "
            "`solved time` is the median over the runs that returned a path, valid or not (the planner's raw "
            "speed); `per motion check`, the checkers' summed time over the summed motion checks."
            % ("" if marker == "mesh-repeats" else " --marker " + marker, command, n_met, len(lines) - 2), ""]
    return "\n".join(text + lines) + "\n"


def overview(bench_dir, command, marker=MARKER):
    lines = ["| config (runs x limit) | planner | success mdd / fcl | median time (s) mdd / fcl | mdd / FCL | "
             "longest run / limit mdd / fcl | invalid mdd / fcl | checking share mdd / fcl | memory (MB) mdd / fcl | "
             "verification (s) mdd / fcl | per motion check (us) mdd / fcl |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    verdicts, overruns, mdd_invalid, found = [], [], 0, []
    for c in CONFIGS:
        db = os.path.join(bench_dir, c, "bench.db")
        if not os.path.exists(db):
            continue
        found.append(c)
        rows = bench_report.load(db)
        stats = bench_report.summarise(rows)
        planners = sorted({k[1] for k in stats if k[0] == c})
        for p in planners:
            st = [stats.get((c, p, k)) for k in CHECKERS]
            group = [[r for r in rows if r["planner"] == p and r["checker"] == k] for k in CHECKERS]
            limit = rows[0]["timelimit"]
            longest = [max((r["time"] for r in g if r.get("time") is not None), default=None) for g in group]
            solved = [[r for r in g if bench_report.exact(r)] for g in group]
            lines.append("| %s, %d x %gs | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                c, max(len(g) for g in group), limit, p,
                pair(st, lambda s: "%.0f%%" % (100 * s["success"])),
                pair(st, lambda s: bench_report.fmt(s["median_time"])),
                bench_report.fmt(st[0]["ratio"], 2) if st[0] and st[0].get("ratio") is not None else "-",
                pair(longest, lambda t: "%.2f" % (t / limit)),
                pair(st, lambda s: str(s["invalid"])),
                pair(st, share),
                pair([median_of(g, "memory") for g in group], lambda m: "%.0f" % m),
                pair([median_of(g, "verification_time") for g in solved], lambda t: bench_report.fmt(t)),
                pair([per_check(g) for g in group], lambda t: "%.3g" % t)))
            mdd, fcl = st
            if mdd:
                mdd_invalid += mdd["invalid"]
            if mdd and fcl:
                met = verdict(mdd, fcl)
                verdicts.append("%s %s: %s / %s s (ratio %s), success %.0f%% / %.0f%%: %s" % (
                    c, p, bench_report.fmt(mdd["median_time"]), bench_report.fmt(fcl["median_time"]),
                    bench_report.fmt(mdd["ratio"], 2) if mdd["ratio"] is not None else "-",
                    100 * mdd["success"], 100 * fcl["success"], "met" if met else "missed"))
            for k, t in zip(CHECKERS, longest):
                if t is not None and t > 1.1 * limit:
                    overruns.append("%s %s %s: %.1f s for %g s" % (c, p, k, t, limit))
    if not found:
        raise SystemExit("mesh_results: no %s/<config>/bench.db (run scripts/run-mesh-bench.sh)" % bench_dir)
    made_by = "scripts/mesh_results.py" + ("" if marker == MARKER else " --marker " + marker)
    text = ["Made by `%s` from `%s`. FCL is OMPL's discrete motion "
            "validator at the default resolution with FCL's collide(); every solution verified (exact MDD edge "
            "check + dense FCL check); a run without a verified solution counts at the time limit."
            % (made_by, command), ""]
    text += lines + [""]
    n_met = sum(v.endswith(": met") for v in verdicts)
    text.append("Targets as measured:")
    text.append("")
    text.append("- median planning time at most half of FCL discrete's at the same or better success: met in %d of "
                "%d (config, planner) groups:" % (n_met, len(verdicts)))
    text += ["  - " + v for v in verdicts]
    text.append("- zero invalid solutions from the MDD checker: %d invalid (%s)"
                % (mdd_invalid, "met" if mdd_invalid == 0 else "missed"))
    text.append("- every run ends within its limit + 10%%: %s" % (
        "met" if not overruns else "missed (" + "; ".join(overruns) + ")"))
    return "\n".join(text) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", default=os.path.join(ROOT, "out", "bench-mesh"))
    parser.add_argument("--readme", default=readme_markers.default_target("mesh.md"),
                        help="replace the text between the markers in this file (default: docs/results/mesh.md; "
                        "- prints)")
    parser.add_argument("--command", default="./scripts/run-mesh-bench.sh")
    parser.add_argument("--repeats", metavar="DIR",
                        help="one group per DIR/<config>-<planner>/bench.db (markers mesh-repeats by default)")
    parser.add_argument("--marker", help="the markers' name: <!-- NAME:begin --> ... <!-- NAME:end --> "
                        "(default mesh-results, mesh-repeats with --repeats)")
    args = parser.parse_args()
    if args.repeats:
        args.marker = args.marker or "mesh-repeats"
        text = repeats(args.repeats, args.command, args.marker)
    else:
        args.marker = args.marker or MARKER
        text = overview(args.bench, args.command, args.marker)
    readme_markers.replace_between(args.readme, "<!-- %s:begin -->" % args.marker, "<!-- %s:end -->" % args.marker,
                                   text, "mesh_results")


if __name__ == "__main__":
    main()
