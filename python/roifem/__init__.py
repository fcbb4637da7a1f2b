# SPDX-License-Identifier: GPL-3.0-or-later
"""roifem: region-of-interest finite element models of the brain, from Python.

Five lines:

    import roifem
    sim = roifem.Simulation("scenarios/paper-setup1.toml")   # the 306-node ROI, the rest condensed
    sim.run()                                                 # 200 steps of the trapezoidal rule
    print(sim.t, abs(sim.roi_displacement_mm).max())          # s, mm
    print(sim.energy, sim.stats)

What is here (help(roifem.X) for each):
    read_mesh, generate_brain_mesh, Mesh        meshes, their nodes, tetrahedra and named sets
    Scenario                                    a scenario from a file, a dict, or either with overrides
    Simulation                                  a scenario's model stepped: step, step_to, run(observer=...),
                                                u, v, roi_displacement_mm, displacement(), energy,
                                                reaction_forces(), tool_forces(), stats
    integrators()                               every integrator by name, with its traits
    paper, compare, roi_size                    the CLI's studies; their tables as NumPy structured arrays
    Error > InputError, ModelError, SolverError the errors roifem reports, with the same messages

Lengths are metres in arrays named without a unit and millimetres where the name says _mm, as in
results.h5; forces are newtons. Arrays that show roifem's own storage (Mesh.nodes, Mesh.tets,
Simulation.u and .v) are read-only views that keep their owner alive.
"""
from ._roifem import (  # noqa: F401
    __version__,
    Error,
    InputError,
    Mesh,
    ModelError,
    Scenario,
    Simulation,
    SolverError,
    compare,
    generate_brain_mesh,
    integrators,
    paper,
    read_mesh,
    roi_size,
)

__all__ = [
    "__version__",
    "Error", "InputError", "ModelError", "SolverError",
    "Mesh", "read_mesh", "generate_brain_mesh",
    "Scenario", "Simulation", "integrators",
    "paper", "compare", "roi_size",
]
