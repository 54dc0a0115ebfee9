"""The example in python/README.md runs and prints what its comments say."""

import contextlib
import io
import pathlib
import re

README = pathlib.Path(__file__).resolve().parent.parent / "README.md"


def test_readme_example_runs_and_prints_its_comments():
    text = README.read_text()
    block = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(block, str(README), "exec"), {})
    lines = out.getvalue().splitlines()
    assert lines[0] == "separated 2.0 [1. 0. 0.]"
    assert lines[1:5] == ["never", "False", "1.0", "1.0"]
    assert lines[6] == "[ 2.  1.  0. -1.  0.  1.  2.]"
