"""`pip install .`: CMake builds the Python module (particula._core) and the `particula` command;
setuptools packs them with the pure-Python modules of python/particula into a wheel. The
metadata is in pyproject.toml. Offline with Debian's setuptools and wheel:

    python3 -m venv --system-site-packages venv && venv/bin/pip install --no-build-isolation .

The CMake build directory is build/pip (a second install rebuilds only what changed); CMAKE_ARGS
adds configure options (e.g. CMAKE_ARGS="-DPARTICULA_CUDA=OFF -DPARTICULA_NATIVE=OFF"),
CMAKE_BUILD_PARALLEL_LEVEL sets the number of compile jobs (default: all cores).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
BUILD_DIR = os.path.join("build", "pip")  # relative: setuptools wants data_files relative to setup.py
CLI = os.path.join(BUILD_DIR, "particula")


def project_version():
    """The version of CMakeLists.txt's project(), its one source."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        found = re.search(r"project\(particula VERSION ([0-9.]+)", f.read())
    if not found:
        sys.exit("setup.py: no 'project(particula VERSION ...)' in CMakeLists.txt")
    return found.group(1)


class CMakeBuild(build_ext):
    """Configures the release preset into build/pip (no tests, no benchmarks) with this Python and
    builds the CLI and the extension; the extension goes where setuptools packs it, the CLI is
    installed into the environment's bin/ as data_files."""

    def run(self):
        build_dir = os.path.join(ROOT, BUILD_DIR)
        configure = ["cmake", "--preset", "release", "-B", build_dir, "-DPARTICULA_BUILD_TESTS=OFF",
                     "-DPARTICULA_BUILD_BENCH=OFF", "-DPARTICULA_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"]
        configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        build = ["cmake", "--build", build_dir, "-j", jobs, "--target", "particula", "particula_python"]
        for cmd in (configure, build):
            print(" ".join(shlex.quote(c) for c in cmd), flush=True)
            subprocess.run(cmd, cwd=ROOT, check=True)
        package = os.path.join(build_dir, "python", "particula")
        core = [f for f in os.listdir(package) if f.startswith("_core.") and f.endswith(".so")]
        if len(core) != 1:
            sys.exit(f"setup.py: expected one _core*.so in {package}, found {core}")
        for ext in self.extensions:
            target = self.get_ext_fullpath(ext.name)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copyfile(os.path.join(package, core[0]), target)


setup(
    version=project_version(),
    package_dir={"": "python"},
    packages=["particula"],
    ext_modules=[Extension("particula._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    data_files=[("bin", [CLI])],
)
