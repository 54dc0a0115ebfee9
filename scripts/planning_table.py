#!/usr/bin/env python3
"""The planning-layer speed tables of docs/results/planning-speed.md, from mddual_bench_planning.

Reads the Markdown that scripts/run-planning-bench.sh writes (out/bench-planning.md
by default): per scene, the state-check line and the edge table. Writes one row per
scene and edge kind (state checks, MDD and OMPL's discrete + FCL time per edge and
their ratio, the ratio on valid and on invalid edges alone, FCL's continuous
validator with conservative advancement and how often its answer differs from
MDD's, and MDD's pair queries per edge), then the lastValid table (the same edges
checked with lastValid: times and the mean fraction kept of the invalid edges), and MDD's one-time
set-up per scene when the input has it, between the markers
`<!-- planning:begin -->` and `<!-- planning:end -->` of docs/results/planning-speed.md
(--readme names another file; --readme - prints to standard output).

    scripts/planning_table.py [--input out/bench-planning.md] [--readme FILE|-]
        [--marker planning] [--command "./scripts/run-planning-bench.sh"]

--marker names the block (`<!-- NAME:begin -->` ... `<!-- NAME:end -->`):
`planning` for the example scenes, `planning-mesh` for the mesh configs.
"""

import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import readme_markers  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def parse(text):
    header = re.search(r"seed (\d+), (\d+) states, (\d+) edges per kind, fastest of (\d+) passes", text)
    if not header:
        raise SystemExit("planning_table: no benchmark header in the input (not mddual_bench_planning output?)")
    scenes = []
    for block in re.split(r"^### ", text, flags=re.M)[1:]:
        name = block.split(":", 1)[0].strip()
        state = re.search(r"MDD ([\d.]+) us .*?FCL ([\d.]+) us .*?FCL / MDD = ([\d.]+)x", block)
        if not state:
            raise SystemExit("planning_table: scene '%s' has no state-check line" % name)
        setup = re.search(r"MDD one-time set-up: enlarged robot pieces \((\d+) levels x (\d+) pieces\) ([\d.]+) ms",
                          block)
        rows, last_valid = [], []
        for line in block.splitlines():
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == 13 and re.match(r"(translation|rotating),", cells[0]):
                rows.append(cells)
            elif len(cells) == 6 and cells[0].startswith("lastValid: "):
                last_valid.append(cells)
        scenes.append((name, state.groups(), rows, last_valid, setup.groups() if setup else None))
    return header.groups(), scenes


def table(parsed, command):
    (seed, states, edges, passes), scenes = parsed
    out = ["Made by `scripts/planning_table.py` from `%s` "
           "(seed %s, %s random states and %s random edges per kind and scene, fastest of %s passes)." %
           (command, seed, states, edges, passes), "",
           "| scene | state check MDD / FCL (us) | FCL / MDD | edges | MDD (us) | OMPL discrete + FCL (us) | "
           "discrete / MDD: all | valid only / invalid only | FCL CCD CA (us) | CA answers != MDD | pair queries |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, (t_mdd, t_fcl, ratio), rows, _, _ in scenes:
        for r in rows:
            differs = "-" if r[12] == "-" else "%s of %s" % (r[12], edges)
            out.append("| %s | %s / %s | %sx | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                name, t_mdd, t_fcl, ratio, r[0], r[2], r[5], r[7], r[8], r[11], differs, r[3]))
    if any(last_valid for _, _, _, last_valid, _ in scenes):
        out += ["", "The same edges with `checkMotion(s1, s2, lastValid)` (what KPIECE calls: the part of an invalid "
                "edge before its first contact), and the mean fraction each keeps of the invalid edges:", "",
                "| scene | edges | MDD (us) | OMPL discrete + FCL (us) | discrete / MDD | kept MDD / discrete |",
                "|---|---|---|---|---|---|"]
        for name, _, _, last_valid, _ in scenes:
            for r in last_valid:
                out.append("| %s | %s | %s | %s | %s | %s |" % (
                    name, r[0][len("lastValid: "):], r[1], r[3], r[4], r[5]))
    setups = [(name, setup) for name, _, _, _, setup in scenes if setup]
    if setups:
        out += ["", "Not in the times above: MDD's one-time set-up per scene, the enlarged robot pieces of rotating "
                "edges (levels x pieces), which a planning run builds on first use and the benchmark builds before "
                "timing: " + "; ".join("%s %s ms (%s x %s)" % (name, ms, levels, pieces)
                                       for name, (levels, pieces, ms) in setups) + "."]
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--input", default=os.path.join(ROOT, "out", "bench-planning.md"))
    parser.add_argument("--readme", default=readme_markers.default_target("planning-speed.md"),
                        help="replace the text between the planning markers in this file (default: "
                        "docs/results/planning-speed.md; - prints)")
    parser.add_argument("--marker", default="planning", help="name of the block (default: planning)")
    parser.add_argument("--command", default="./scripts/run-planning-bench.sh",
                        help="the command that made the input, quoted in the table's first line")
    args = parser.parse_args()
    with open(args.input) as f:
        text = table(parse(f.read()), args.command)
    begin, end = "<!-- %s:begin -->" % args.marker, "<!-- %s:end -->" % args.marker
    readme_markers.replace_between(args.readme, begin, end, text, "planning_table")


if __name__ == "__main__":
    main()
