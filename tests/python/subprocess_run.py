"""Runs Python code or the CLI in a child process, so that a crash (a signal) is a test failure
and not the end of the test runner."""
import os
import signal
import subprocess
import sys

from conftest import ROOT

BINARY = os.environ.get("PARTICULA_BINARY", os.path.join(ROOT, "build", "release", "particula"))


def _environment(env):
    e = dict(os.environ)
    e.setdefault("PYTHONPATH", os.path.join(ROOT, "build", "release", "python"))
    e.update(env or {})
    return e


def _check_no_signal(proc, what):
    if proc.returncode < 0:
        name = signal.Signals(-proc.returncode).name
        raise AssertionError("%s ended by %s\n%s%s" % (what, name, proc.stdout, proc.stderr))
    return proc


def run_python(code, env=None, timeout=60):
    """Runs `code` with `python3 -c` from the repository root; the finished process (text output)."""
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=_environment(env), capture_output=True,
                          text=True, timeout=timeout)
    return _check_no_signal(proc, "python3 -c")


def run_cli(args, env=None, timeout=60):
    """Runs the particula binary with `args` from the repository root; the finished process."""
    proc = subprocess.run([BINARY] + list(args), cwd=ROOT, env=_environment(env), capture_output=True, text=True,
                          timeout=timeout)
    return _check_no_signal(proc, "particula " + " ".join(args))
