"""Shared set-up of the Python tests (run by CTest: tests/CMakeLists.txt puts the build tree's
package on PYTHONPATH). Run by hand from the repository root:
    PYTHONPATH=build/release/python python3 -m pytest tests/python
"""
import os
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# By hand without PYTHONPATH: the release build tree's package.
if not os.environ.get("PYTHONPATH"):
    sys.path.insert(0, os.path.join(ROOT, "build", "release", "python"))


def case(name):
    """A shipped case file."""
    return os.path.join(ROOT, "cases", name + ".toml")


# Small versions of the shipped cases: a few hundred to a few thousand particles.
HYDROSTATIC = {"resolution.d0": 5e-3}  # 20 x 20 fluid particles, 4 walls
COUETTE = {"time.end": 0.1}  # as shipped (10 x 20 fluid particles, periodic in x, a probe), shorter


@pytest.fixture(scope="session")
def particula():
    import particula as p
    return p
