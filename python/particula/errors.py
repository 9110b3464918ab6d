"""The exceptions of particula, one per exit code of the command line.

| exit code | exception | base |
|---|---|---|
| 2 (bad input) | InputError; CaseError for a case file or override (file, line, key) | ValueError |
| 3 (numerical failure) | NumericalFailure (time, step, particle) | RuntimeError |
| 4 (I/O failure while writing) | IoFailure | OSError |
| 130 (interrupted) | Interrupted | KeyboardInterrupt |
| 1 (internal error) | InternalError | RuntimeError |

The message is the CLI's (without its "error: " prefix).
"""


class ParticulaError(Exception):
    """Base of particula's errors. exit_code: the CLI's exit code for the same error;
    run_dir: the run directory of particula.run_case / resume (None for a Simulation)."""

    exit_code = 1

    def __init__(self, message, run_dir=None):
        super().__init__(message)
        self.message = message
        self.run_dir = run_dir


class InputError(ParticulaError, ValueError):
    """Bad input (exit code 2): a case file, an override, a checkpoint or a run directory that
    cannot be used. Nothing was written."""

    exit_code = 2


class CaseError(InputError):
    """A mistake in a case file or an override. file is the case file or "--set", line is
    1-based (0 when there is none), key the dotted key (may be empty); str() is the CLI's
    one line, e.g. "cases/my.toml:19: key 'fluid.nuu': unknown key (did you mean 'fluid.nu'?)"."""

    def __init__(self, text, file="", line=0, key="", message=None, run_dir=None):
        super().__init__(text, run_dir)
        self.file = file
        self.line = line
        self.key = key
        self.reason = message if message is not None else text


class NumericalFailure(ParticulaError, RuntimeError):
    """A numerical failure (exit code 3): NaN, a density out of bounds, a particle leaving the
    domain, overlapping bodies. From a Simulation: time, step, particle_id, position (x, y) and
    reason are set; run_case writes a final snapshot and checkpoint/failure.bin as the CLI does."""

    exit_code = 3

    def __init__(self, message, time=None, step=None, particle_id=None, position=None, reason=None, run_dir=None):
        super().__init__(message, run_dir)
        self.time = time
        self.step = step
        self.particle_id = particle_id
        self.position = position
        self.reason = reason


class IoFailure(ParticulaError, OSError):
    """A file or directory could not be written (exit code 4): disk full, permission denied."""

    exit_code = 4

    def __init__(self, message, run_dir=None):
        ParticulaError.__init__(self, message, run_dir)

    def __str__(self):
        return self.message


class InternalError(ParticulaError, RuntimeError):
    """An internal error of particula (exit code 1): please report it."""

    exit_code = 1


class Interrupted(KeyboardInterrupt):
    """The run was stopped by Ctrl-C or SIGTERM (exit code 130) after writing its outputs and a
    checkpoint: particula.resume(run_dir) continues it."""

    exit_code = 130

    def __init__(self, message, run_dir=None):
        super().__init__(message)
        self.message = message
        self.run_dir = run_dir
