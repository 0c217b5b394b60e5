# SPDX-License-Identifier: BSD-3-Clause
"""Builds the ladrc package: the Python files, plus the shared library built
by CMake from the repository this directory belongs to (pip builds a local
directory in place, so the parent directory is the repository), plus
ladrc/_version.py with the CMake project version.

LADRC_CMAKE_ARGS (environment, split like a shell) adds CMake options, for
instance -DLADRC_REAL_DOUBLE=ON."""
import importlib.util
import os
import shlex
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py
from wheel.bdist_wheel import bdist_wheel

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
CMAKELISTS = os.path.join(REPO, "CMakeLists.txt")
# Names of the shared library, per platform (the ones ladrc/__init__.py looks for).
LIBRARY_NAMES = ("libladrc.so", "libladrc.dylib")


def _project_version():
    # Loaded by path: importing the package itself would need NumPy and the library.
    spec = importlib.util.spec_from_file_location(
        "_project_version", os.path.join(HERE, "ladrc", "_project_version.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    if not os.path.exists(CMAKELISTS):
        raise RuntimeError(f"{CMAKELISTS} not found: the package is built from a checkout of the "
                           "ladrc repository (pip install ./python from its top directory)")
    return module.read(CMAKELISTS)


VERSION = _project_version()


class BuildWithLibrary(build_py):
    """build_py, then the shared library (CMake, Release) and _version.py
    into the built package."""

    def run(self):
        super().run()
        cmake = shutil.which("cmake")
        if not cmake:
            raise RuntimeError("cmake not found: it builds the ladrc shared library (Debian: apt-get install cmake)")
        tree = os.path.join(self.get_finalized_command("build").build_temp, "cmake")
        # --fresh: options of an earlier LADRC_CMAKE_ARGS do not linger in the cache.
        configure = [cmake, "--fresh", "-S", REPO, "-B", tree, "-DCMAKE_BUILD_TYPE=Release", "-DBUILD_SHARED_LIBS=ON",
                     "-DLADRC_BUILD_TESTS=OFF", "-DLADRC_INSTALL=OFF"]
        subprocess.run(configure + shlex.split(os.environ.get("LADRC_CMAKE_ARGS", "")), check=True)
        subprocess.run([cmake, "--build", tree, "--target", "ladrc"], check=True)
        built = [n for n in LIBRARY_NAMES if os.path.exists(os.path.join(tree, n))]
        if len(built) != 1:
            raise RuntimeError(f"{tree}: expected one of {LIBRARY_NAMES} after the build, found {built}")
        package = os.path.join(self.build_lib, "ladrc")
        # copyfile follows the libladrc.so -> .so.N -> .so.N.M.P links: one real file.
        shutil.copyfile(os.path.join(tree, built[0]), os.path.join(package, built[0]))
        with open(os.path.join(package, "_version.py"), "w", encoding="utf-8") as f:
            f.write(f'# Written by setup.py from project(ladrc VERSION ...) in CMakeLists.txt.\n'
                    f'__version__ = "{VERSION}"\n')


class PlatformWheel(bdist_wheel):
    """The wheel carries a native library, loaded through ctypes: for this
    platform, any Python 3 (no extension module, so no CPython ABI tag)."""

    def finalize_options(self):
        super().finalize_options()
        self.root_is_pure = False

    def get_tag(self):
        return ("py3", "none", super().get_tag()[2])


setup(version=VERSION, packages=["ladrc"],
      cmdclass={"build_py": BuildWithLibrary, "bdist_wheel": PlatformWheel})
