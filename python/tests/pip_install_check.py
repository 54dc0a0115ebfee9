#!/usr/bin/env python3
"""ctest python.pip_install: `pip install ./python` as a Python user runs it.

Creates a virtual environment (--system-site-packages: NumPy, setuptools and
pip are Debian's) in a temporary folder, installs the package there with

    pip install --no-build-isolation --no-deps --no-index ./python

(no network), then, from a folder outside the source and build trees and with
no PYTHONPATH, imports mddual from the environment, runs the first example of
python/README.md and checks what it prints, the help text of mddual.toi, the
installed type stubs and the package's version.

    pip_install_check.py --source DIR [--build-dir DIR] [--keep]

--build-dir sets MDDUAL_BUILD_DIR, so python/setup.py packs the module of that
CMake build tree (brought up to date) instead of configuring and building the
library again (minutes on two cores); without it this checks the full build.
"""

import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

PROBE = r'''
import contextlib, io, importlib.metadata, pathlib, pydoc, re, sys, sysconfig
import mddual

site = pathlib.Path(sysconfig.get_paths()["platlib"]).resolve()
module = pathlib.Path(mddual.__file__).resolve()
assert module.parent == site, f"mddual imported from {module}, not from the environment's {site}"
assert sys.prefix != sys.base_prefix, "not running in the virtual environment"
for stub in (site / "mddual-stubs" / "__init__.pyi", site / "mddual.pyi"):
    assert stub.is_file() and "def toi(" in stub.read_text(), f"missing or empty stub {stub}"
assert importlib.metadata.version("mddual") == mddual.__version__, (importlib.metadata.version("mddual"),
                                                                    mddual.__version__)

text = pydoc.render_doc(mddual.toi, renderer=pydoc.plaintext)
assert "toi(a: mddual.ConvexPolytope, X_WA: numpy.typing.ArrayLike | None, b: mddual.ConvexPolytope" in text, text
assert "How far B can translate" in text, text

readme = pathlib.Path(sys.argv[1])
block = re.search(r"```python\n(.*?)```", readme.read_text(), re.S).group(1)
out = io.StringIO()
with contextlib.redirect_stdout(out):
    exec(compile(block, str(readme), "exec"), {})
lines = out.getvalue().splitlines()
assert lines[0] == "separated 2.0 [1. 0. 0.]", lines
assert lines[1:5] == ["never", "False", "1.0", "1.0"], lines
assert lines[6] == "[ 2.  1.  0. -1.  0.  1.  2.]", lines
print(f"mddual {mddual.__version__} from {module}; scene bindings: {hasattr(mddual, 'Scene')}; "
      f"README example OK")
'''


def run(cmd, **kwargs):
    print("+ " + " ".join("<probe>" if c is PROBE else str(c) for c in cmd), flush=True)
    return subprocess.run([str(c) for c in cmd], check=True, **kwargs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--source", type=pathlib.Path, required=True, help="the repository's root")
    ap.add_argument("--build-dir", type=pathlib.Path, help="a CMake build tree whose module to pack")
    ap.add_argument("--python", default=sys.executable, help="the interpreter of the environment")
    ap.add_argument("--keep", action="store_true", help="keep the temporary folder")
    args = ap.parse_args()
    source = args.source.resolve()

    tmp = pathlib.Path(tempfile.mkdtemp(prefix="mddual-pip-"))
    try:
        env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "PIP_", "MDDUAL_"))}
        env.update(PYTHONNOUSERSITE="1", PYTHONDONTWRITEBYTECODE="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
        if args.build_dir:
            env["MDDUAL_BUILD_DIR"] = str(args.build_dir.resolve())
        t0 = time.monotonic()
        venv = tmp / "venv"
        # No pip of its own: Debian's, from the system site, installs into the environment.
        run([args.python, "-m", "venv", "--system-site-packages", "--without-pip", venv], env=env)
        python = venv / "bin" / "python"
        t1 = time.monotonic()
        run([python, "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index", "--no-cache-dir",
             "-q", source / "python"], env=env, cwd=tmp)
        t2 = time.monotonic()
        work = tmp / "elsewhere"
        work.mkdir()
        run([python, "-c", PROBE, source / "python" / "README.md"], env=env, cwd=work)
        t3 = time.monotonic()
        print(f"venv {t1 - t0:.1f} s, pip install {t2 - t1:.1f} s, import and README example {t3 - t2:.1f} s")
    except subprocess.CalledProcessError as e:
        print(f"FAILED: {e}", file=sys.stderr)
        return 1
    finally:
        if args.keep:
            print(f"kept {tmp}")
        else:
            shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
