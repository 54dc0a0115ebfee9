"""Replace the generated part of a Markdown file: the text between two marker
comments (e.g. `<!-- results:begin -->` and `<!-- results:end -->`), which the
table scripts (results_overview.py, planning_table.py, replay_table.py,
mesh_results.py) own. Each script writes into its page of docs/results/ by
default; `--readme FILE` names another file, `--readme -` prints instead."""

import os
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
PRINT = "-"


def default_target(name):
    """The page of docs/results/ that holds a script's tables, as an absolute path."""
    return os.path.join(ROOT, "docs", "results", name)


def replace_between(path, begin, end, text, who):
    """Writes `text` between the markers `begin` and `end` of the file at `path`
    (standard output if `path` is "-"); exits with a message naming `who` and
    the file if a marker is missing."""
    if path == PRINT:
        sys.stdout.write(text)
        return
    with open(path) as f:
        content = f.read()
    if begin not in content or end not in content:
        raise SystemExit("%s: %s has no %s ... %s markers" % (who, path, begin, end))
    head, rest = content.split(begin, 1)
    _, tail = rest.split(end, 1)
    with open(path, "w") as f:
        f.write(head + begin + "\n" + text + end + tail)
