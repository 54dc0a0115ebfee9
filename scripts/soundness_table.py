#!/usr/bin/env python3
"""The soundness table of docs/results/soundness.md, from mddual_soundness.

Reads the Markdown table that scripts/run-soundness.sh writes
(out/soundness/summary.md by default: one row per case family and checker) and
writes it, after a line naming the command and the build that made it, between
the markers `<!-- soundness:begin -->` and `<!-- soundness:end -->` of
docs/results/soundness.md (--readme names another file; --readme - prints to
standard output).

    scripts/soundness_table.py [--input out/soundness/summary.md] [--readme FILE|-]
        [--command "./scripts/run-soundness.sh"]
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import readme_markers  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
HEADER = "| case | checker | edges | colliding edges | missed | false alarms | median time per edge (us) |"


def read_rows(path):
    with open(path) as f:
        lines = [line.rstrip("\n") for line in f if line.strip()]
    if not lines or lines[0] != HEADER:
        raise SystemExit("soundness_table: %s does not start with the soundness table's header" % path)
    rows = lines[2:]
    for line in rows:
        if len(line.strip().strip("|").split("|")) != 7:
            raise SystemExit("soundness_table: %s: not a row of 7 cells: %s" % (path, line))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--input", default=os.path.join(ROOT, "out", "soundness", "summary.md"))
    parser.add_argument("--readme", default=readme_markers.default_target("soundness.md"))
    parser.add_argument("--command", default="./scripts/run-soundness.sh")
    args = parser.parse_args()
    rows = read_rows(args.input)
    text = "\n".join(["Made by `scripts/soundness_table.py` from `%s`." % args.command, "", HEADER,
                      "|---|---|---|---|---|---|---|"] + rows) + "\n"
    readme_markers.replace_between(args.readme, "<!-- soundness:begin -->", "<!-- soundness:end -->", text,
                                   "soundness_table")


if __name__ == "__main__":
    main()
