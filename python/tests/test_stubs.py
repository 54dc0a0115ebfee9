"""The shipped type stubs (python/mddual-stubs/__init__.pyi) describe this module.

Every public name of the module and of each class is in the stub, and with the
planning layer and the hull-cast peer (Bullet) built the stub is exactly what
scripts/gen_stubs.py writes, so it cannot go stale silently: after changing
the bindings, regenerate it with

    PYTHONPATH=build/release/python python3 scripts/gen_stubs.py

The annotations are checked too: none is a bare `object` or `Any` (the
bindings name the types of the objects they convert themselves, see
python/src/typed.h), each evaluates against typing, NumPy and the module, and
the calls give what their annotations say.
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
# The stub describes the module with the planning layer and the hull-cast peer (Bullet).
COMPLETE = hasattr(mddual, "ArmScene") and hasattr(mddual, "HullCastScene")
WITHOUT = "mddual was built without the planning layer or the hull-cast peer (the stub describes it with them)"


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
    # The stub is generated with the planning layer and Bullet, so a module without them has fewer names.
    extra = sorted(public(stub_names()) - public(dir(mddual)))
    if not COMPLETE:
        pytest.skip(WITHOUT)
    assert not extra, f"{STUB.name} has {extra}, which the module does not; {REGENERATE}"


def test_stub_is_what_the_generator_writes():
    if not COMPLETE:
        pytest.skip(WITHOUT)
    generated = load_generator().generate(mddual)
    assert STUB.read_text() == generated, f"{STUB.name} is stale (signatures or docstrings changed); {REGENERATE}"


def test_help_shows_signatures_and_docs():
    # pybind11 puts the signature, with the py::arg names, in the docstring's first line.
    doc = mddual.toi.__doc__
    assert doc.startswith("toi(a: mddual.ConvexPolytope, X_WA: numpy.typing.ArrayLike | None, "
                          "b: mddual.ConvexPolytope, X_WB: numpy.typing.ArrayLike | None, "
                          "direction: numpy.typing.ArrayLike, *, max_distance: float = inf, exact: bool = True")
    assert "How far B can translate" in doc
    for n in public(dir(mddual)):
        obj = getattr(mddual, n)
        if callable(obj) and not inspect.isclass(obj):
            lines = obj.__doc__.splitlines()
            assert lines[0].startswith(n + "(") and "arg0" not in lines[0], (n, lines[0])
            assert len(lines) > 2 and lines[2].strip(), f"{n} has no docstring"


# --- the annotations themselves ---------------------------------------------------

# (function, argument or "return") -> why a bare `object` or `Any` is right there.
# Arrays, links, paths and the other objects the bindings convert themselves
# are named in the bindings (python/src/typed.h): none of them belongs here.
BARE_ANNOTATIONS_ALLOWED = {}
BARE = {"object", "Any"}


def stub_functions():
    """(qualified name, ast.FunctionDef) for every function and method of the stub."""
    tree = ast.parse(STUB.read_text(), str(STUB))
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            yield node.name, node
        elif isinstance(node, ast.ClassDef):
            for f in node.body:
                if isinstance(f, ast.FunctionDef):
                    yield f"{node.name}.{f.name}", f


def annotations(f):
    """(argument name or "return", annotation node) of a function, `self` excepted."""
    a = f.args
    for arg in a.posonlyargs + a.args + a.kwonlyargs + [a.vararg, a.kwarg]:
        if arg is not None and arg.annotation is not None:
            yield arg.arg, arg.annotation
    if f.returns is not None:
        yield "return", f.returns


def union_members(node):
    """The members of `A | B | C` (the node itself when it is no union)."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitOr):
        return union_members(node.left) + union_members(node.right)
    return [node]


def test_no_argument_or_result_is_a_bare_object():
    # A binding that takes or gives py::object without a name (typed.h) shows
    # up as `object` in help() and the stub: a NumPy argument typed so takes
    # anything in a type checker. Any alone is as vague.
    found = []
    for name, f in stub_functions():
        for arg, node in annotations(f):
            for member in union_members(node):
                if isinstance(member, ast.Name) and member.id in BARE and (name, arg) not in BARE_ANNOTATIONS_ALLOWED:
                    found.append(f"{name}({arg}: {ast.unparse(node)})")
    assert not found, f"{STUB.name}: bare object/Any annotations {found}: name the type in the binding (typed.h)"
    known = {(name, arg) for name, f in stub_functions() for arg, _ in annotations(f)}
    stale = sorted(set(BARE_ANNOTATIONS_ALLOWED) - known)
    assert not stale, f"BARE_ANNOTATIONS_ALLOWED names what the stub does not have: {stale}"


def test_help_names_no_argument_object():
    # The same on the module itself (this build, with or without the planning layer).
    for n in public(dir(mddual)):
        obj = getattr(mddual, n)
        members = [obj] if not inspect.isclass(obj) else [m for m in vars(obj).values() if callable(m)]
        for m in members:
            for line in (m.__doc__ or "").splitlines():
                if "(" in line and ") -> " in line:
                    assert ": object" not in line and "-> object" not in line, line


def test_annotations_name_real_types():
    # Every annotation of the stub evaluates against typing, NumPy and the
    # module (a misspelt numpy.bool or a class the module lacks fails), and
    # the array arguments are NumPy's array-likes.
    if not COMPLETE:
        pytest.skip(WITHOUT)
    import os
    import typing

    import numpy
    import numpy.typing

    namespace = {n: getattr(typing, n) for n in ("Any", "Callable", "Iterable", "Iterator", "Literal", "Optional",
                                                 "Sequence", "Union")}
    namespace.update(os=os, pathlib=pathlib, numpy=numpy)
    namespace.update({n: getattr(mddual, n) for n in public(dir(mddual)) if inspect.isclass(getattr(mddual, n))})
    count = 0
    for _, f in stub_functions():
        for _, node in annotations(f):
            eval(ast.unparse(node), dict(namespace))  # the stub is this repository's
            count += 1
    assert count > 100
    by_name = dict(stub_functions())
    init = {a: ast.unparse(n) for a, n in annotations(by_name["ConvexPolytope.__init__"])}
    assert init["points"] == "numpy.typing.ArrayLike"
    toi = {a: ast.unparse(n) for a, n in annotations(by_name["toi"])}
    assert toi["X_WA"] == "numpy.typing.ArrayLike | None" and toi["direction"] == "numpy.typing.ArrayLike"


def test_results_have_the_stub_types():
    # What the stub promises the calls give, on a small arm and a small scene:
    # Python scalars for one item, arrays of the named dtype for a batch.
    if not hasattr(mddual, "ArmScene"):
        pytest.skip("mddual was built without the planning layer")
    import numpy as np

    from conftest import cube_points

    model = mddual.RobotModel.from_urdf(ROOT / "configs" / "arm7" / "arm7.urdf")
    cube = mddual.ConvexPolytope(cube_points(0.05, (0.3, 0.0, 0.37)))
    arm = mddual.ArmScene(model, [cube], mddual.Srdf.load(ROOT / "configs" / "arm7" / "arm7.srdf"))
    q = model.default_configuration()
    Q = np.stack([q, q])
    assert type(arm.collides(q)) is bool and arm.collides(Q).dtype == np.bool_
    assert type(arm.clearance(q)) is float and arm.clearance(Q).dtype == np.float64
    c, f = arm.check_edges(q, q)
    assert type(c) is bool and type(f) is float
    c, f = arm.check_edges(Q, Q)
    assert c.dtype == np.bool_ and f.dtype == np.float64
    bent = q.copy()
    bent[1] = 1.5
    hit = arm.contact(bent)
    assert arm.contact(q) is None and all(v is None or type(v) in (str, int) for v in hit.values())
    assert model.forward_kinematics(q, links=["base", 1]).dtype == np.float64
    files = mddual.ArmProblemFiles("scene0001.yaml", "request0001.yaml")
    assert isinstance(files.scene, pathlib.Path) and isinstance(files.request, pathlib.Path)
    scene = mddual.Scene.from_polytopes([cube], [cube], space="R3", bounds=[[-1, -1, -1], [1, 1, 1]])
    assert type(scene.collides(np.eye(4))) is bool and scene.collides(np.stack([np.eye(4)] * 2)).dtype == np.bool_
    assert type(scene.is_valid([0.0, 0.0, 0.0])) is bool
    for d in (scene.check_edges([0.0, 0, 0], [0.5, 0, 0]), scene.directed_clearance(np.eye(4), [1.0, 0, 0]),
              mddual.mdd_batch(cube, None, cube, None, [[1.0, 0, 0]])):
        assert all(type(k) is str and isinstance(v, np.ndarray) for k, v in d.items()), d
