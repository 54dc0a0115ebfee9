#!/usr/bin/env python3
"""The README's arm table, from the pages scripts/run-arm-bench.sh writes.

Reads the summary tables of docs/results/arms.md (arm7),
docs/results/panda.md (the Panda) and docs/results/panda-mbm.md (the Panda in
MotionBenchMaker's own scenes), keeps the rows of one planner
(RRTConnectkConfigDefault unless --planner says otherwise) and writes one
line per (robot, problem set): success, median planning time (the planner's
own solve time, `median solve (s)`, where the page has it, else OMPL's
`median time (s)`) and invalid solutions for each checker, between the
markers `<!-- arms:begin -->` and `<!-- arms:end -->` of README.md (--readme names another file; --readme -
prints to standard output). A page that is missing is skipped; none at all
is an error.

    scripts/arm_headline.py [--results docs/results/arms.md ...] [--planner NAME] [--readme FILE|-]
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import readme_markers  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
HEADER_START = "| config | planner | checker |"
NEEDED = ["config", "planner", "checker", "success", "median time (s)", "invalid"]
CHECKERS = ["mdd", "fcl", "fcl-fine", "hull-cast"]


def cells_of(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def read_page(path):
    """The robot named in the page's title, its "Made by" line and its rows
    (dicts from the summary tables' column names to cells)."""
    with open(path) as f:
        lines = [line.rstrip("\n") for line in f]
    if not lines or not lines[0].startswith("# ") or " on its MotionBenchMaker problem sets" not in lines[0]:
        raise SystemExit("arm_headline: %s: not a page of scripts/run-arm-bench.sh (its title)" % path)
    robot = lines[0][2:].split(" ")[0]
    made = next((line for line in lines if line.startswith("Made by ")), None)
    if made is None:
        raise SystemExit("arm_headline: %s: no \"Made by\" line" % path)
    rows = []
    header = None
    for number, line in enumerate(lines, 1):
        if line.startswith(HEADER_START):
            header = cells_of(line)
            missing = [n for n in NEEDED if n not in header]
            if missing:
                raise SystemExit("arm_headline: %s:%d: the summary table has no column %s" % (path, number, missing[0]))
            continue
        if header is None or not line.startswith("|"):
            header = None
            continue
        if line.startswith("|---"):
            continue
        cells = cells_of(line)
        if len(cells) != len(header):
            raise SystemExit("arm_headline: %s:%d: not a row of %d cells" % (path, number, len(header)))
        rows.append(dict(zip(header, cells)))
    if not rows:
        raise SystemExit("arm_headline: %s: no summary table" % path)
    return robot, made, rows


def headline(pages, planner):
    checkers = [c for c in CHECKERS if any(r["checker"] == c for _, _, rows in pages for r in rows)]
    joined = " / ".join(checkers)
    # The planner's own solve time when every row has it (OMPL's time adds
    # its harness's thread stop to every run; bench_report.py), else OMPL's.
    every = all(r.get("median solve (s)", "-") != "-" for _, _, rows in pages for r in rows)
    time = "median solve (s)" if every else "median time (s)"
    lines = ["| robot, set | success %s | %s %s | invalid solutions %s |" % (joined, time, joined, joined),
             "|---|---|---|---|"]
    for robot, _, rows in pages:
        sets = []
        for r in rows:
            if r["planner"] == planner and r["config"] not in sets:
                sets.append(r["config"])
        for s in sets:
            by = {r["checker"]: r for r in rows if r["config"] == s and r["planner"] == planner}
            cell = lambda name: " / ".join(by[c][name] if c in by else "-" for c in checkers)  # noqa: E731
            lines.append("| %s, %s | %s | %s | %s |" % (robot, s, cell("success"), cell(time), cell("invalid")))
    if len(lines) == 2:
        raise SystemExit("arm_headline: no row of planner %s" % planner)
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--results", nargs="+", default=[os.path.join(ROOT, "docs", "results", "arms.md"),
                                                          os.path.join(ROOT, "docs", "results", "panda.md"),
                                                          os.path.join(ROOT, "docs", "results", "panda-mbm.md")])
    parser.add_argument("--planner", default="RRTConnectkConfigDefault")
    parser.add_argument("--readme", default=os.path.join(ROOT, "README.md"))
    args = parser.parse_args()
    pages = [read_page(p) for p in args.results if os.path.exists(p)]
    if not pages:
        raise SystemExit("arm_headline: none of %s exists" % ", ".join(args.results))
    # Each page by its robot, a robot's second page by its file name (panda-mbm.md).
    names, seen = [], set()
    for path, (robot, _, _) in zip([p for p in args.results if os.path.exists(p)], pages):
        names.append(os.path.splitext(os.path.basename(path))[0] if robot in seen else robot)
        seen.add(robot)
    made = "; ".join("%s: %s" % (name, line[len("Made by "):].split(" on ")[0])
                     for name, (_, line, _) in zip(names, pages))
    text = "\n".join(["Made by `scripts/arm_headline.py` from the %s rows of docs/results (%s)." % (args.planner, made),
                      ""] + headline(pages, args.planner)) + "\n"
    readme_markers.replace_between(args.readme, "<!-- arms:begin -->", "<!-- arms:end -->", text, "arm_headline")


if __name__ == "__main__":
    main()
