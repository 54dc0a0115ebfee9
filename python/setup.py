"""Builds the mddual wheel: CMake builds the module, setuptools packs it.

    pip install --no-build-isolation ./python

configures the repository (this folder's parent) in build/ here with the
tests, benchmarks and command-line tool off, builds the target mddual_python
for the interpreter pip runs under, and puts the module in the wheel with its
type stubs (mddual-stubs/__init__.pyi, the PEP 561 place a type checker looks
for a compiled single-file module's stubs, and mddual.pyi beside the module).

Environment variables:
  MDDUAL_BUILD_DIR       use this existing CMake build tree of the repository
                         instead (its module is brought up to date with
                         `cmake --build DIR --target mddual_python`; it must
                         have been configured for the same Python version)
  MDDUAL_BUILD_PLANNING  ON or OFF; unset: ON when the planning layer's
                         libraries (OMPL, urdfdom, assimp, FCL) are found, so
                         the module has Scene and the arm bindings, else OFF
  MDDUAL_CMAKE_ARGS      more arguments for the configure step
  CMAKE_BUILD_PARALLEL_LEVEL  build jobs (default: all cores)
"""

import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
STUB = HERE / "mddual-stubs" / "__init__.pyi"


def project_version():
    if not (ROOT / "CMakeLists.txt").is_file() or not (ROOT / "lib").is_dir():
        sys.exit(f"{HERE}/setup.py builds from a clone of mddual (the repository root, {ROOT}, is not one): "
                 "pip install ./python from the repository root, not from an sdist or a copy of python/")
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(\s*mddual\s+VERSION\s+([0-9.]+)", text).group(1)


def run(cmd, **kwargs):
    print("setup.py: " + " ".join(shlex.quote(str(c)) for c in cmd), flush=True)
    subprocess.run([str(c) for c in cmd], check=True, **kwargs)


class CMakeBuild(build_ext):
    """build_ext for the one extension, mddual: CMake's target mddual_python."""

    def build_extension(self, ext):
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        existing = os.environ.get("MDDUAL_BUILD_DIR")
        if existing:
            build_dir = pathlib.Path(existing).resolve()
            if not (build_dir / "CMakeCache.txt").is_file():
                sys.exit(f"MDDUAL_BUILD_DIR={existing}: not a configured CMake build tree (no CMakeCache.txt)")
        else:
            build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
            self.configure(build_dir)
        cmd = ["cmake", "--build", build_dir, "--target", "mddual_python"]
        if "CMAKE_BUILD_PARALLEL_LEVEL" not in os.environ:
            cmd += ["--parallel", str(os.cpu_count() or 1)]
        run(cmd)

        built = build_dir / "python" / ("mddual" + suffix)
        if not built.is_file():
            found = sorted(p.name for p in (build_dir / "python").glob("mddual*.so"))
            sys.exit(f"{built} was not built: the build tree has {found or 'no module'}; it was configured for "
                     f"another Python than {sys.executable} (suffix {suffix})")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)
        # The stubs beside the module too (editors that look there).
        shutil.copyfile(STUB, target.parent / "mddual.pyi")

    def configure(self, build_dir):
        args = [
            "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython_EXECUTABLE={sys.executable}",
            "-DMDDUAL_BUILD_PYTHON=ON",
            "-DMDDUAL_BUILD_TESTS=OFF",
            "-DMDDUAL_BUILD_BENCHMARKS=OFF",
            "-DMDDUAL_BUILD_CLI=OFF",
        ] + shlex.split(os.environ.get("MDDUAL_CMAKE_ARGS", ""))
        planning = os.environ.get("MDDUAL_BUILD_PLANNING", "").upper()
        if planning:
            run(["cmake", "-S", ROOT, "-B", build_dir, *args, f"-DMDDUAL_BUILD_PLANNING={planning}"])
            return
        try:
            run(["cmake", "-S", ROOT, "-B", build_dir, *args, "-DMDDUAL_BUILD_PLANNING=ON"])
        except subprocess.CalledProcessError:
            print("setup.py: WARNING: the planning layer's libraries were not found (see CMake's message above): "
                  "building the module without Scene and the arm bindings; set MDDUAL_BUILD_PLANNING=ON to make "
                  "this an error", file=sys.stderr, flush=True)
            run(["cmake", "-S", ROOT, "-B", build_dir, *args, "-DMDDUAL_BUILD_PLANNING=OFF"])


def setuptools_dirs():
    """With MDDUAL_BUILD_DIR, setuptools' own build files go into that tree, not into the sources."""
    existing = os.environ.get("MDDUAL_BUILD_DIR")
    if not existing:
        return {}
    base = pathlib.Path(existing).resolve() / "pip-build"
    base.mkdir(parents=True, exist_ok=True)
    return {"build": {"build_base": str(base)}, "egg_info": {"egg_base": str(base)}}


setup(
    version=project_version(),
    ext_modules=[Extension("mddual", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    packages=["mddual-stubs"],
    package_data={"mddual-stubs": ["__init__.pyi"]},
    zip_safe=False,
    options=setuptools_dirs(),
)
