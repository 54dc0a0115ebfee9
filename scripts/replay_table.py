#!/usr/bin/env python3
"""The replay table of docs/results/planning-speed.md: a planner's motion checks, replayed with each checker.

Reads the Markdown that mddual_bench_replay prints (out/bench-replay.md by default,
written by scripts/run-planning-bench.sh): its title line and its table. Writes them,
after a line naming the command that made them, between the markers
`<!-- replay:begin -->` and `<!-- replay:end -->` of docs/results/planning-speed.md
(--readme names another file; --readme - prints to standard output).

    scripts/replay_table.py [--input out/bench-replay.md] [--readme FILE|-] [--command TEXT]
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import readme_markers  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def table(path, command):
    with open(path) as f:
        lines = [line.rstrip("\n") for line in f]
    title = [line for line in lines if line.startswith("Motion checks a planner made")]
    rows = [line for line in lines if line.startswith("|")]
    if not title or len(rows) < 3:
        raise SystemExit("replay_table: %s holds no mddual_bench_replay table (title and at least one row)" % path)
    text = ["Made by `scripts/replay_table.py` from `%s`. %s" % (command, title[0]), ""]
    return "\n".join(text + rows) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--input", default=os.path.join(ROOT, "out", "bench-replay.md"))
    ap.add_argument("--readme", default=readme_markers.default_target("planning-speed.md"),
                    help="file to rewrite between the replay markers (default: docs/results/planning-speed.md; "
                    "- prints)")
    ap.add_argument("--command", default="./scripts/run-planning-bench.sh")
    args = ap.parse_args()
    text = table(args.input, args.command)
    readme_markers.replace_between(args.readme, "<!-- replay:begin -->", "<!-- replay:end -->", text, "replay_table")


if __name__ == "__main__":
    main()
