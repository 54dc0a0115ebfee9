"""The examples in python/README.md and the top README.md run and hold what their comments say."""

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


def test_readme_scene_example_runs_and_prints_its_comments(monkeypatch):
    import mddual
    import pytest

    if not hasattr(mddual, "Scene"):
        pytest.skip("mddual was built without the planning layer")
    monkeypatch.chdir(README.parent.parent)  # the example's paths are relative to the repository
    text = README.read_text()
    block = re.findall(r"```python\n(.*?)```", text, re.S)[1]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(block, str(README), "exec"), {"mddual": mddual})
    assert out.getvalue().splitlines() == ["R3 [1. 5. 5.]", "True", "[ True] [0.14416667]", "[2.595]"]


def test_readme_arm_example_runs_and_prints_its_comments(monkeypatch):
    import mddual
    import numpy as np
    import pytest

    if not hasattr(mddual, "ArmScene"):
        pytest.skip("mddual was built without the planning layer")
    monkeypatch.chdir(README.parent.parent)
    block = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)[2]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(block, str(README), "exec"), {"mddual": mddual, "np": np})
    assert out.getvalue().splitlines() == ["8 finger_left_joint", "[0.   0.   1.36]", "373 373", "True 0.853"]


def test_readme_hull_cast_example_runs_and_prints_its_comments():
    import mddual
    import numpy as np
    import pytest

    if not hasattr(mddual, "HullCastScene"):
        pytest.skip("mddual was built without the hull-cast peer (Bullet)")
    block = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)[3]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(block, str(README), "exec"), {"mddual": mddual, "np": np})
    assert out.getvalue().splitlines() == ["[ True]", "[ True] 50", "[False]"]


def test_top_readme_example_holds_what_its_comment_says():
    top = README.parent.parent / "README.md"
    block = re.search(r"```python\n(.*?)```", top.read_text(), re.S).group(1)
    names = {}
    exec(compile(block, str(top), "exec"), names)
    # The comment on its last line: r.status == "separated", r.distance == 2.0
    comment = block.strip().splitlines()[-1].split("#", 1)[1]
    for claim in comment.split(","):
        assert eval(claim, names), claim
