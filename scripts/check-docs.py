#!/usr/bin/env python3
"""Checks the repository's documentation; exits non-zero naming each problem.

- Every relative link (and image) in README.md, docs/**/*.md and the other
  Markdown files of the repository resolves to a file or folder inside the
  repository, and a `#section` part names a heading of the Markdown file it
  points to (GitHub's anchors).
- Nothing refers to the developers' shared folder beside the repository
  (a path into the folder named shared next to the clone) or links to a path outside the repository.
- README.md has at most 300 lines.

Web links (http, https, mailto) are not followed. Links inside code blocks
and code spans are not links. Standard library only:

    scripts/check-docs.py [--root DIR]
"""

import argparse
import os
import re
import subprocess
import sys

README_MAX_LINES = 300
SHARED = ".." + "/shared"  # split so that this file does not match itself
SKIP_DIRS = {".git", "out", "__pycache__"}
TEXT_EXTENSIONS = {".md", ".h", ".hpp", ".cpp", ".cc", ".py", ".sh", ".txt", ".cmake", ".cfg", ".in", ".toml",
                   ".yml", ".yaml", ".json", ".pyi"}

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$")
FENCE = re.compile(r"^\s{0,3}(```|~~~)")
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
WEB = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def repository_files(root):
    """The repository's files, relative to root: git's tracked and untracked-but-not-ignored
    files when root is a git checkout, otherwise every file below root (build folders skipped)."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                             check=True, capture_output=True).stdout.decode()
        files = [f for f in out.split("\0") if f]
        return [f for f in files if os.path.exists(os.path.join(root, f))]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for d, dirs, names in os.walk(root):
            dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith("build")]
            files += [os.path.relpath(os.path.join(d, n), root) for n in names]
        return files


def slug(heading):
    """GitHub's anchor for a heading: lower case, markup and punctuation dropped, spaces to hyphens."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link keeps its text
    text = text.replace("`", "").lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    """Every anchor a Markdown file defines: its headings' (numbered -1, -2 when repeated) and explicit ids."""
    found, seen, fenced = set(), {}, False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if FENCE.match(line):
                fenced = not fenced
                continue
            m = None if fenced else HEADING.match(line)
            if m:
                base = slug(m.group(2))
                n = seen.get(base, 0)
                seen[base] = n + 1
                found.add(base if n == 0 else "%s-%d" % (base, n))
            for a in re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", line):
                found.add(a)
    return found


def links(path):
    """(line number, target) of every link of a Markdown file outside code."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, start=1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if fenced:
                continue
            line = CODE_SPAN.sub("", line)
            for m in LINK.finditer(line):
                yield number, m.group(1)
            m = REFERENCE.match(line)
            if m:
                yield number, m.group(1)


def check(root):
    root = os.path.realpath(root)
    problems = []
    files = repository_files(root)
    markdown = sorted(f for f in files if f.endswith(".md"))
    anchor_cache = {}

    for rel in markdown:
        here = os.path.dirname(os.path.join(root, rel))
        for number, target in links(os.path.join(root, rel)):
            where = "%s:%d: link '%s'" % (rel, number, target)
            if WEB.match(target):
                continue
            path_part, _, fragment = target.partition("#")
            if SHARED in path_part:
                problems.append("%s points into the shared folder beside the repository" % where)
                continue
            resolved = os.path.realpath(os.path.join(here, path_part)) if path_part else os.path.join(root, rel)
            if os.path.isabs(path_part) or os.path.commonpath([root, resolved]) != root:
                problems.append("%s leaves the repository" % where)
                continue
            if not os.path.exists(resolved):
                problems.append("%s: no such file %s" % (where, os.path.relpath(resolved, root)))
                continue
            if fragment and resolved.endswith(".md") and os.path.isfile(resolved):
                if resolved not in anchor_cache:
                    anchor_cache[resolved] = anchors(resolved)
                if fragment not in anchor_cache[resolved]:
                    problems.append("%s: %s has no section with the anchor #%s"
                                    % (where, os.path.relpath(resolved, root), fragment))

    this = os.path.realpath(__file__)
    for rel in files:
        full = os.path.join(root, rel)
        if os.path.splitext(rel)[1] not in TEXT_EXTENSIONS and os.path.basename(rel) != "CMakeLists.txt":
            continue
        if os.path.realpath(full) == this or not os.path.isfile(full):
            continue
        with open(full, encoding="utf-8", errors="replace") as f:
            for number, line in enumerate(f, start=1):
                if SHARED + "/" in line or line.rstrip().endswith(SHARED):
                    problems.append("%s:%d: refers to %s, outside the repository" % (rel, number, SHARED))

    readme = os.path.join(root, "README.md")
    if not os.path.exists(readme):
        problems.append("README.md: missing")
    else:
        with open(readme, encoding="utf-8") as f:
            count = sum(1 for _ in f)
        if count > README_MAX_LINES:
            problems.append("README.md: %d lines, more than %d" % (count, README_MAX_LINES))
    return problems, len(markdown)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    args = parser.parse_args()
    problems, count = check(args.root)
    for p in problems:
        print("check-docs: " + p, file=sys.stderr)
    if problems:
        print("check-docs: %d problem(s) in %d Markdown files" % (len(problems), count), file=sys.stderr)
        return 1
    print("check-docs: %d Markdown files, every link resolves inside the repository" % count)
    return 0


if __name__ == "__main__":
    sys.exit(main())
