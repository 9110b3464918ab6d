"""particula.run_case and particula.resume: the CLI's `particula run` and `particula resume`,
the same C++ code called in-process (the run directory is the one the CLI writes)."""
import os
import sys
import tomllib

from . import _core
from . import errors
from .arguments import threads_argument
from .case import case_source
from .overrides import override_list
from .progress import Progress


class RunResult:
    """How a run ended: run_dir (str), exit_code (the CLI's: 0, or 3 for a numerical failure
    with check=False), message (what the CLI printed on standard error)."""

    def __init__(self, run_dir, exit_code, message):
        self.run_dir = run_dir
        self.exit_code = exit_code
        self.message = message

    def read(self):
        """The run directory's content (particula.read_run)."""
        from .reader import read_run
        return read_run(self.run_dir)

    def __repr__(self):
        return "RunResult(run_dir=%r, exit_code=%d)" % (self.run_dir, self.exit_code)


_ERRORS = {2: errors.InputError, 3: errors.NumericalFailure, 4: errors.IoFailure, 130: errors.Interrupted}


def _error_line(text):
    """The CLI's error message: the lines starting with "error: ", without that prefix."""
    lines = [ln[len("error: "):] for ln in text.splitlines() if ln.startswith("error: ")]
    return "\n".join(lines) if lines else text.strip()


def _finish(code, text, run_dir, quiet, check):
    """Echoes the runner's messages (unless quiet) and raises for a failed run (when check)."""
    if text and (not quiet or code != 0):
        sys.stderr.write(text)
        sys.stderr.flush()
    if code == 0 or (not check and code == 3):
        return RunResult(run_dir, code, text)
    message = _error_line(text)
    if code == 130:
        message = text.strip().splitlines()[-1] if text.strip() else "interrupted"
    raise _ERRORS.get(code, errors.InternalError)(message, run_dir=run_dir)


def load_case(case, overrides=None):
    """The case as particula resolves it (every default filled in, overrides applied), as a
    dict: what a run directory's case.toml holds. case: a case file's path or a particula.Case.
    Raises CaseError with the CLI's message."""
    source, text = case_source(case)
    if text is not None:
        return tomllib.loads(_core.resolved_case_text(text, source, override_list(overrides)))
    return tomllib.loads(_core.resolved_case(source, override_list(overrides)))


def run_case(case, out=None, overrides=None, *, threads=None, backend="cpu", overwrite=False, quiet=True,
             plots=True, check=True, progress=None):
    """Runs a case into a run directory exactly as
    `particula run CASE --out OUT --set k=v ... [--threads N] [--backend B] [--overwrite]` does
    (same files, same exit codes, same rules for --overwrite), and returns a RunResult.

    out: the run directory (default runs/<case name>, relative to the working directory);
    overrides: {key: value} or ["key=value", ...] (particula.overrides.toml_value);
    quiet: no progress line (the runner's messages are printed when it is False or on failure);
    case: a case file's path, or a particula.Case (or a dict of a case file's keys);
    plots: draw DIR/plots/*.png at the end (tools/plot_run.py), as the CLI does;
    progress: True for a progress bar (tqdm when installed; the default unless quiet), False for
    none, or a callable progress(time, t_end, step) called every quarter second of wall time
    and after the last step; an exception it raises stops the run as Ctrl-C does (outputs and a
    checkpoint written: particula.resume continues it) and is then raised;
    threads: as Simulation's (None: OpenMP's default; else 1 .. particula.MAX_THREADS).
    A failed run raises the exception of its exit code (particula.errors; with check=False a
    numerical failure returns a RunResult with exit_code 3 instead). One run at a time per
    process: run cases in parallel in separate processes (concurrent.futures.ProcessPoolExecutor).
    """
    threads = threads_argument(threads)
    sets = override_list(overrides)
    source, case_text = case_source(case)
    # The case is loaded first (the runner loads it again): a mistake in it raises CaseError with
    # the file, line and key as attributes, and the default run directory is known.
    name = load_case(case, sets)["name"]
    run_dir = os.fspath(out) if out is not None else os.path.join("runs", name)
    tell = Progress.beside_captured_stderr(not quiet if progress is None else progress, name)
    try:
        code, text = _core.run_command(source, run_dir, sets, threads, backend, overwrite,
                                       quiet or progress is True or (progress is None and not quiet), plots,
                                       case_text=case_text, progress=tell.callback)
    finally:
        tell.close()
    return _finish(code, text, run_dir, quiet, check)


def resume(run_dir, overrides=None, *, threads=None, backend="cpu", quiet=True, plots=True, check=True,
           progress=None):
    """Continues a run from run_dir/checkpoint/state.bin exactly as `particula resume` does;
    overrides may change only time.end and output.* keys; progress as for run_case. Returns a
    RunResult."""
    threads = threads_argument(threads)
    sets = override_list(overrides)
    tell = Progress.beside_captured_stderr(not quiet if progress is None else progress, os.fspath(run_dir))
    try:
        code, text = _core.resume_command(os.fspath(run_dir), sets, threads, backend,
                                          quiet or progress is True or (progress is None and not quiet), plots,
                                          progress=tell.callback)
    finally:
        tell.close()
    return _finish(code, text, os.fspath(run_dir), quiet, check)

