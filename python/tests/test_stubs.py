"""The shipped type stubs (python/mddual-stubs/__init__.pyi) describe this module.

Every public name of the module and of each class is in the stub, and with the
planning layer built the stub is exactly what scripts/gen_stubs.py writes, so
it cannot go stale silently: after changing the bindings, regenerate it with

    PYTHONPATH=build/release/python python3 scripts/gen_stubs.py
"""

import ast
import importlib.util
import inspect
import pathlib

import pytest

import mddual

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
STUB = ROOT / "python" / "mddual-stubs" / "__init__.pyi"
REGENERATE = "regenerate it: PYTHONPATH=<build>/python python3 scripts/gen_stubs.py"


def load_generator():
    spec = importlib.util.spec_from_file_location("gen_stubs", ROOT / "scripts" / "gen_stubs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def stub_names():
    """{top-level name: set of member names (classes) or None}."""
    tree = ast.parse(STUB.read_text(), str(STUB))
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names[node.name] = ({n.name for n in node.body if isinstance(n, ast.FunctionDef)} |
                                {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)})
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = None
        elif isinstance(node, ast.AnnAssign):
            names[node.target.id] = None
    return names


def public(names):
    return {n for n in names if not n.startswith("_")}


def test_stub_lists_every_public_name():
    names = stub_names()
    missing = sorted(public(dir(mddual)) - set(names))
    assert not missing, f"{STUB.name} lacks {missing}; {REGENERATE}"
    assert "__version__" in names


def test_stub_lists_every_public_member_of_each_class():
    names = stub_names()
    for n in public(dir(mddual)):
        cls = getattr(mddual, n)
        if not inspect.isclass(cls) or issubclass(cls, BaseException):
            continue
        missing = sorted(public(cls.__dict__) - names[n])
        assert not missing, f"{STUB.name}: class {n} lacks {missing}; {REGENERATE}"


def test_stub_names_only_what_the_module_has():
    # The stub is generated with the planning layer, so a module without it has fewer names.
    extra = sorted(public(stub_names()) - public(dir(mddual)))
    if not hasattr(mddual, "ArmScene"):
        pytest.skip("mddual was built without the planning layer")
    assert not extra, f"{STUB.name} has {extra}, which the module does not; {REGENERATE}"


def test_stub_is_what_the_generator_writes():
    if not hasattr(mddual, "ArmScene"):
        pytest.skip("mddual was built without the planning layer (the stub describes the module with it)")
    generated = load_generator().generate(mddual)
    assert STUB.read_text() == generated, f"{STUB.name} is stale (signatures or docstrings changed); {REGENERATE}"


def test_help_shows_signatures_and_docs():
    # pybind11 puts the signature, with the py::arg names, in the docstring's first line.
    doc = mddual.toi.__doc__
    assert doc.startswith("toi(a: mddual.ConvexPolytope, X_WA: object, b: mddual.ConvexPolytope, X_WB: object, "
                          "direction: object, *, max_distance: float = inf, exact: bool = True")
    assert "How far B can translate" in doc
    for n in public(dir(mddual)):
        obj = getattr(mddual, n)
        if callable(obj) and not inspect.isclass(obj):
            lines = obj.__doc__.splitlines()
            assert lines[0].startswith(n + "(") and "arg0" not in lines[0], (n, lines[0])
            assert len(lines) > 2 and lines[2].strip(), f"{n} has no docstring"
