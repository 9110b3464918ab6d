"""particula.Simulation: a case built into the solver and stepped from Python.

Particle fields are NumPy *views* of the solver's own arrays (no copy), read-only:

- a view stays valid memory as long as it exists (it keeps the simulation alive), and shows
  the current state: after step() or run_to() it holds the new values;
- fluid particles are reordered by cell every `numerics.reorder_interval` steps (50 by
  default), so row i may be another particle after a step: follow particles by `id`, or copy
  (np.array(view)) what you keep between steps;
- boundary particles (walls, body surfaces, dummies) are rows [0, n_boundary) in a fixed order;
- with backend="cuda" the state lives on the GPU and the host copy is refreshed when a field is
  read: get the field again after each step.

body_states(), wall_states(), body_index and wall_index are copies.

One thread at a time: while a thread is in step(), run_to() or write_checkpoint(), any other use
of the same Simulation from another thread raises RuntimeError (separate Simulations may step in
parallel threads). After a NumericalFailure the Simulation refuses to step (NumericalFailure
again): start again from a checkpoint.
"""
import os
import tomllib

from . import _core
from .arguments import seconds_argument, threads_argument
from .case import case_source
from .overrides import override_list
from .progress import Progress

KIND_FLUID = 0
KIND_BOUNDARY = 1  # a wall or body surface particle
KIND_DUMMY = 2  # a dummy particle of the baseline boundary (numerics.boundary = "dummy")


class Simulation:
    """A case file loaded with its overrides and built into particles and a solver, as
    `particula run` does, without a run directory.

    Simulation("cases/couette.toml", {"resolution.d0": 1e-4}) raises CaseError (a ValueError)
    with the CLI's message for a mistake in the file or an override. The case is a case file's
    path or a particula.Case (or a dict of a case file's keys). backend: "cpu" or "cuda";
    threads: OpenMP threads for the whole process, an integer in [1, particula.MAX_THREADS]
    (None: as set before, by default OMP_NUM_THREADS or all cores; an OMP_NUM_THREADS beyond
    that range raises InputError). A wrong type raises TypeError, a count out of range ValueError.
    """

    def __init__(self, case, overrides=None, *, backend="cpu", threads=None):
        source, text = case_source(case)
        self._sim = _core.Simulation.from_case(source, override_list(overrides), backend, threads_argument(threads),
                                               case_text=text)

    @classmethod
    def from_checkpoint(cls, file, overrides=None, *, backend="cpu", threads=None):
        """A simulation restarted from a checkpoint (one written by write_checkpoint or a run's
        checkpoint/state.bin) exactly as `particula resume` restarts it: stepping it gives
        bitwise the state an uninterrupted simulation reaches. Only time.end and output.* may be
        overridden. A damaged checkpoint or one that does not fit its case raises InputError."""
        self = cls.__new__(cls)
        self._sim = _core.Simulation.from_checkpoint(os.fspath(file), override_list(overrides), backend,
                                                     threads_argument(threads))
        return self

    def write_checkpoint(self, file):
        """Writes the complete state (the format of checkpoint/state.bin) to `file`, atomically,
        creating its directory. `file` is a new file or a particula checkpoint, which is replaced;
        anything else there (a file that is not a checkpoint, a symbolic link, a directory, a
        device) is left alone and IoFailure names it. Raises IoFailure when it cannot be
        written."""
        self._sim.write_checkpoint(os.fspath(file))

    # ---- time stepping

    def step(self, max_dt=0.0):
        """One time step, of at most max_dt seconds when max_dt > 0; returns the step taken.
        Raises NumericalFailure (with time, step, particle_id, position) when the state is no
        longer sound after it, and from then on. max_dt: 0 (the stable step) or a finite
        positive number that advances the time (else ValueError; not a number: TypeError)."""
        return self._sim.step(seconds_argument("max_dt", max_dt))

    def run_to(self, t, progress=False):
        """Steps until time t (s), the last step shortened to land on t; returns the number of
        steps taken (0 when t is the current time). Ctrl-C stops it between two steps
        (KeyboardInterrupt; the state is that after the last whole step: write_checkpoint keeps
        it). t: finite and not before the current time (else ValueError; not a number:
        TypeError). progress: True for a progress bar (tqdm when installed), or a callable
        progress(time, t, step) called every quarter second of wall time and after the last
        step (an exception it raises stops run_to between two steps and is raised)."""
        t = seconds_argument("t", t)
        tell = Progress(progress, "%s to t = %g s" % (self.name, t))
        try:
            return self._sim.run_to(t, progress=tell.callback)
        finally:
            tell.close()

    @property
    def time(self):
        """Simulated time (s)."""
        return self._sim.time

    @property
    def step_count(self):
        return self._sim.step_count

    @property
    def dt(self):
        """The last time step taken (s); 0 before the first."""
        return self._sim.dt

    # ---- the case

    @property
    def case_toml(self):
        """The fully resolved case (every default filled in, overrides applied), the text a run
        directory's case.toml holds."""
        return self._sim.case_toml

    @property
    def case(self):
        """The resolved case as a dict (tomllib)."""
        return tomllib.loads(self._sim.case_toml)

    @property
    def name(self):
        return self.case["name"]

    @property
    def d0(self):
        """Particle spacing (m)."""
        return self._sim.d0

    @property
    def h(self):
        """Smoothing length (m)."""
        return self._sim.h

    @property
    def backend(self):
        return self._sim.backend

    @property
    def guard_events(self):
        """The guard counters summary.json reports (dict)."""
        return self._sim.guard_events

    # ---- particles (views, see the module's docstring)

    @property
    def n_particles(self):
        return self._sim.n_particles

    @property
    def n_boundary(self):
        """Boundary particles come first: rows [0, n_boundary); fluid particles follow."""
        return self._sim.n_boundary

    @property
    def positions(self):
        """(n, 2) float64 positions (m). View."""
        return self._sim.positions

    @property
    def velocity(self):
        """(n, 2) float64 velocity (m/s). View."""
        return self._sim.velocity

    @property
    def density(self):
        """(n,) float64 density (kg/m^3). View."""
        return self._sim.density

    @property
    def pressure(self):
        """(n,) float64 pressure (Pa), as the snapshots write it. View."""
        return self._sim.pressure

    @property
    def mass(self):
        """(n,) float64 mass per unit depth (kg/m). View."""
        return self._sim.mass

    @property
    def kind(self):
        """(n,) uint8: KIND_FLUID (0), KIND_BOUNDARY (1, wall or body surface), KIND_DUMMY (2). View."""
        return self._sim.kind

    @property
    def id(self):
        """(n,) int64 stable particle identity (follows particles across reorderings). View."""
        return self._sim.id

    @property
    def group(self):
        """(n,) int32 rigid group of a boundary particle in the solver's numbering (walls first in
        case order, then bodies in case order), -1 for fluid. View. The snapshots' `body` and
        `wall` arrays are body_index and wall_index."""
        return self._sim.group

    @property
    def normals(self):
        """(n_boundary, 2) float64 unit normals of the boundary particles. View."""
        return self._sim.normals

    @property
    def body_index(self):
        """(n,) int32: the case index of the body ([[body]] order) a particle belongs to, -1 for
        fluid and wall particles (the snapshots' `body` array, bodies.csv's `body`). Copy."""
        return self._sim.body_index

    @property
    def wall_index(self):
        """(n,) int32: the case index of the wall ([[wall]] order), -1 otherwise (the snapshots'
        `wall` array, walls.csv's `wall`). Copy."""
        return self._sim.wall_index

    # ---- rigid bodies and walls (copies)

    def body_states(self):
        """The bodies in case order as a dict of arrays (copies): name, motion, position (nb, 2),
        velocity (nb, 2), angle, omega, force (hydrodynamic, per unit depth, N/m; = force_pressure
        + force_viscous), force_pressure, force_viscous, force_collision, torque,
        torque_collision, mass, inertia, area, force_damping (the odd-even damping's momentum
        sink next to the body, not part of force): the columns of bodies.csv at this instant; and
        removed (a list of bools: taken out of the run at an outlet with bodies = "removed", its
        state frozen at zero velocity)."""
        return self._sim.body_states()

    def wall_states(self):
        """The walls in case order (name, motion, position, velocity, angle, omega, force,
        force_pressure, force_viscous, torque, force_damping): the columns of walls.csv at this
        instant."""
        return self._sim.wall_states()

    def __repr__(self):
        return "<particula.Simulation '%s': %d particles, t = %.6g s, step %d>" % (
            self.name, self.n_particles, self.time, self.step_count)
