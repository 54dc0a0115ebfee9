"""Replace the generated part of a Markdown file: the text between two marker
comments (e.g. `<!-- results:begin -->` and `<!-- results:end -->`), which the
table scripts (results_overview.py, planning_table.py) own."""


def replace_between(path, begin, end, text, who):
    """Writes `text` between the markers `begin` and `end` of the file at `path`;
    exits with a message naming `who` and the file if a marker is missing."""
    with open(path) as f:
        content = f.read()
    if begin not in content or end not in content:
        raise SystemExit("%s: %s has no %s ... %s markers" % (who, path, begin, end))
    head, rest = content.split(begin, 1)
    _, tail = rest.split(end, 1)
    with open(path, "w") as f:
        f.write(head + begin + "\n" + text + end + tail)
