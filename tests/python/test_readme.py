"""Every code block of README.md run as written: a ```python block with this Python, a ```sh
block with bash, each in a scratch directory that holds the repository's cases/ and, as
build/release/particula, the CLI under test, so that a snippet that no longer works fails here.

The info string after the fence marks the blocks: `no-test` is not run (the two commands, the
builds, pip install: minutes each); `time.end=T` appends `--set time.end=T` to each
`particula run` of the block, for a short run of the same command. Any other language must be
marked `no-test`, and an indented code block (which this test would not see) is refused.
"""
import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT
from subprocess_run import BINARY

README = os.path.join(ROOT, "README.md")
RUNNABLE = ("python", "sh")


def code_blocks(path):
    """(first line number, language, options, text) of each fenced block of `path`."""
    blocks, fence = [], None
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if fence is None and line.startswith("```"):
                words = line[3:].split()
                fence = (number, words[0] if words else "", words[1:], [])
            elif fence is not None and line.rstrip() == "```":
                blocks.append((fence[0], fence[1], fence[2], "".join(fence[3])))
                fence = None
            elif fence is not None:
                fence[3].append(line)
    assert fence is None, "%s:%d: a code block is not closed" % (path, fence[0])
    return blocks


BLOCKS = code_blocks(README)
TESTED = [b for b in BLOCKS if "no-test" not in b[2]]


def option(options, key):
    """The value of `key=value` among a block's options, or None."""
    values = [o.split("=", 1)[1] for o in options if o.startswith(key + "=")]
    return values[0] if values else None


def shortened(text, end):
    """The block with `--set time.end=END` after each `particula run` command."""
    lines = text.splitlines()
    runs = [k for k, line in enumerate(lines) if re.match(r"\s*\S*particula run ", line)]
    assert runs, "time.end=%s on a block without a 'particula run'" % end
    for k in runs:
        lines[k] += " --set time.end=" + end
    return "\n".join(lines) + "\n"


def scratch(tmp_path):
    """A working directory with the README's paths: cases/ and build/release/particula."""
    os.symlink(os.path.join(ROOT, "cases"), tmp_path / "cases")
    (tmp_path / "build" / "release").mkdir(parents=True)
    os.symlink(BINARY, tmp_path / "build" / "release" / "particula")
    return tmp_path


def test_every_block_is_runnable_or_marked():
    assert sum(1 for b in TESTED if b[1] == "python") >= 1
    assert sum(1 for b in TESTED if b[1] == "sh") >= 2
    for number, language, options, _ in TESTED:
        assert language in RUNNABLE, "README.md:%d: a ```%s block: run it (%s) or mark it no-test" % (
            number, language, ", ".join(RUNNABLE))
        for o in options:
            assert o.startswith("time.end="), "README.md:%d: unknown option %r" % (number, o)


def test_no_indented_code_block():
    outside, inside, previous = [], False, ""
    with open(README, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if line.startswith("```"):
                inside = not inside
            elif not inside and line.startswith("    ") and not previous.strip():
                outside.append(number)
            previous = line
    assert not outside, "README.md: indented code blocks at lines %s: fence them (```sh)" % outside


@pytest.mark.parametrize("block", TESTED, ids=["README.md:%d" % b[0] for b in TESTED])
def test_readme_block(block, tmp_path):
    number, language, options, text = block
    cwd = scratch(tmp_path)
    env = dict(os.environ)
    path = env.get("PYTHONPATH") or os.path.join(ROOT, "build", "release", "python")
    env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in path.split(os.pathsep))  # from the scratch dir
    if language == "python":
        cmd = [sys.executable, "-c", text]
    else:
        end = option(options, "time.end")
        cmd = ["bash", "-euo", "pipefail", "-c", shortened(text, end) if end else text]
    proc = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, "README.md:%d failed (exit %d):\n%s%s" % (number, proc.returncode, proc.stdout,
                                                                          proc.stderr)
