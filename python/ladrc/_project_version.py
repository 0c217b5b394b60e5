# SPDX-License-Identifier: BSD-3-Clause
"""The project's version as CMake declares it: the project(ladrc VERSION ...)
line of the repository's CMakeLists.txt, the one place it is written.

Read by setup.py (package metadata, and ladrc/_version.py in the built
package) and by ladrc/__init__.py in a source checkout. Standard library
only: setup.py loads this file before the package can be imported."""
import re

_PROJECT = re.compile(r"^\s*project\s*\(\s*ladrc\s+VERSION\s+([0-9]+(?:\.[0-9]+)*)[\s)]", re.M | re.I)


def read(cmakelists):
    """The VERSION of project(ladrc ...) in the file cmakelists."""
    with open(cmakelists, encoding="utf-8") as f:
        m = _PROJECT.search(f.read())
    if not m:
        raise RuntimeError(f"{cmakelists}: no 'project(ladrc VERSION x.y.z ...)' line")
    return m.group(1)
