"""particula from Python: the solver of the `particula` command (weakly compressible SPH, rigid
bodies in viscous flow) as a module, and a reader of its run directories.

    import particula
    sim = particula.Simulation("cases/couette.toml", {"resolution.d0": 1e-4})
    sim.run_to(0.1)
    sim.positions, sim.velocity, sim.pressure     # NumPy views of the solver's arrays
    sim.write_checkpoint("state.bin")

    particula.run_case("cases/falling_cylinder.toml", "runs/fc", {"resolution.d0": 2.5e-4})
    case = particula.Case.from_file("cases/dkt.toml")   # or particula.Case({...}): a case as data
    case.add_body(shape="circle", radius=1e-3, center=[0.01, 0.05], density=1010)
    particula.run_case(case, "runs/dkt3", progress=True)
    run = particula.read_run("runs/fc")           # bodies, walls, probes, snapshots, summary

Errors are the exceptions of particula.errors, one per exit code of the CLI, with its messages.
"""
from . import errors
from .arguments import MAX_THREADS
from .case import Case
from .commands import RunResult, load_case, resume, run_case
from .errors import (CaseError, InputError, InternalError, Interrupted, IoFailure, NumericalFailure,
                     ParticulaError)
from .reader import Run, Snapshot, Table, read_csv, read_pvd, read_run, read_vtp
from .simulation import KIND_BOUNDARY, KIND_DUMMY, KIND_FLUID, Simulation

__all__ = ["Simulation", "Case", "MAX_THREADS", "run_case", "resume", "load_case", "RunResult", "read_run", "read_csv", "read_vtp",
           "read_pvd", "Run", "Snapshot", "Table", "KIND_FLUID", "KIND_BOUNDARY", "KIND_DUMMY", "errors",
           "ParticulaError", "InputError", "CaseError", "NumericalFailure", "IoFailure", "Interrupted",
           "InternalError"]
