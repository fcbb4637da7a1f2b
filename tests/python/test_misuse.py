# SPDX-License-Identifier: GPL-3.0-or-later
"""Misuse from Python (issue 35): each case is refused with an error that names the cause, or
stopped, and never runs on quietly or for ever."""
import math
import os
import subprocess
import time

import numpy as np
import pytest

import roifem


def test_an_explicit_method_past_its_stability_limit_stops_naming_the_step(scenarios):
    # gsl-rk4 at the paper's dt ran 200 steps to 1e211 m without a word.
    sim = roifem.Simulation(scenarios / "paper-setup2.toml", integrator="gsl-rk4")
    with pytest.raises(roifem.SolverError, match=r"gsl-rk4: the solution diverged \(.*\) by t = 0\.05 s, step 1"):
        sim.run()
    assert sim.step_index == 0


def test_step_to_refuses_a_time_that_is_not_finite_or_not_ahead(scenarios):
    sim = roifem.Simulation(scenarios / "paper-setup2.toml")
    for t in (math.inf, -math.inf, math.nan):
        with pytest.raises(roifem.InputError, match="is not a time to step to"):
            sim.step_to(t)
    assert sim.step_to(0.5) == 10
    for t in (0.5, 0.2, -1.0):
        with pytest.raises(roifem.InputError, match=r"is not ahead of the simulation, which is at t = 0\.5 s \(step 10\)"):
            sim.step_to(t)
    assert sim.step_to(0.52) == 0 and sim.step_to(0.55) == 1  # the grid's last point not beyond t


def test_ctrl_c_from_outside_stops_a_long_step_to_within_a_second(scenarios):
    sim = roifem.Simulation(scenarios / "paper-setup2.toml", energy=False)
    sender = subprocess.Popen(["sh", "-c", f"sleep 0.5; kill -INT {os.getpid()}"])
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        sim.step_to(1e6)  # 2e7 steps: about 20 minutes
    sender.wait()
    assert time.monotonic() - start < 2.0
    assert 0 < sim.step_index < 20_000_000
    sim.step()  # the simulation is whole


def test_counts_beyond_64_bits_are_named(scenarios):
    with pytest.raises(roifem.InputError, match=r"key 'time\.steps' = 9223372036854775808 does not fit"):
        roifem.Simulation(scenarios / "paper-setup2.toml", steps=2**63)
    sim = roifem.Simulation(scenarios / "paper-setup2.toml")
    with pytest.raises(roifem.InputError, match=r"run: steps = 9223372036854775808 does not fit a 64-bit count"):
        sim.run(2**63)
    with pytest.raises(TypeError, match="run: steps must be an int"):
        sim.run(2.5)


def test_a_simulation_of_nothing_names_what_it_takes():
    with pytest.raises(TypeError, match=r"expected a roifem\.Scenario or a scenario file's path .* got NoneType"):
        roifem.Simulation(None)
    with pytest.raises(TypeError, match="got int"):
        roifem.Simulation(42)


def test_an_observer_that_cannot_be_called_is_refused_before_any_step(scenarios):
    sim = roifem.Simulation(scenarios / "paper-setup2.toml")
    with pytest.raises(TypeError, match=r"run: observer must be callable.*got int"):
        sim.run(2, observer=3)
    assert sim.step_index == 0


def test_the_time_keywords_take_the_scenario_files_names(scenarios):
    # dt_s as in the file's [time] table (the keyword dt= is its short form).
    a = roifem.Simulation(scenarios / "paper-setup2.toml", dt_s=0.01, steps=3)
    b = roifem.Simulation(scenarios / "paper-setup2.toml", dt=0.01, steps=3)
    assert a.run() == 3 and b.run() == 3
    assert a.t == pytest.approx(0.03) and a.t == b.t


@pytest.mark.parametrize("given", [dict(dt_s=0.05, dt=0.01), dict(time={"dt_s": 0.05}, dt=0.01),
                                   dict(time={"steps": 4}, steps=3)])
def test_a_time_key_given_twice_is_refused(scenarios, given):
    # Simulation(sc, dt_s=0.05, dt=0.01) ran at 0.01 without a word.
    with pytest.raises(roifem.InputError, match=r"Simulation: \[time\] (dt_s|steps) is given twice, as .* give it once"):
        roifem.Simulation(scenarios / "paper-setup2.toml", **given)


def test_the_time_table_and_a_time_keyword_combine(scenarios):
    sim = roifem.Simulation(scenarios / "paper-setup2.toml", time={"steps": 3}, dt=0.01)
    assert sim.run() == 3 and sim.t == pytest.approx(0.03)


@pytest.mark.parametrize("cls", [roifem.Simulation, roifem.Mesh, roifem.Scenario])
def test_help_explains_every_public_attribute(cls):
    # help(roifem.Simulation) listed closed, integrator, scenario and others without a word.
    undocumented = [name for name in dir(cls) if not name.startswith("_")
                    and not (getattr(cls, name).__doc__ or "").strip()]
    assert undocumented == [], f"{cls.__name__}: {undocumented}"


def test_every_array_names_its_unit_and_mm_variants_agree(scenarios, source_dir):
    units = {"u": "(m", "v": "(m/s", "roi_displacement_mm": "mm", "displacement": "m)", "displacement_mm": "mm",
             "t": "(s)"}
    for name, unit in units.items():
        assert unit in roifem.Simulation.__dict__[name].__doc__, name
    assert "(m)" in roifem.Mesh.nodes.__doc__ and "(mm" in roifem.Mesh.nodes_mm.__doc__
    sim = roifem.Simulation(scenarios / "paper-setup2.toml")
    sim.run(20)
    np.testing.assert_allclose(sim.displacement_mm(), sim.displacement() * 1e3, rtol=1e-15, atol=0)
    mesh = roifem.read_mesh(source_dir / "meshes/brain-800.msh")
    np.testing.assert_allclose(mesh.nodes_mm, mesh.nodes * 1e3, rtol=1e-15, atol=0)


def test_the_version_is_the_clis_and_every_results_file_carries_it(cli, scenarios, tmp_path):
    import subprocess

    import h5py
    printed = subprocess.run([cli, "--version"], capture_output=True, text=True, check=True).stdout.strip()
    assert printed == f"roifem {roifem.__version__}"
    subprocess.run([cli, "run", str(scenarios / "paper-setup2.toml"), "--out", str(tmp_path)], check=True, capture_output=True)
    with h5py.File(tmp_path / "results.h5", "r") as f:
        stored = f.attrs["roifem_version"]
        assert (stored.decode() if isinstance(stored, bytes) else stored) == roifem.__version__


def test_a_restart_table_is_refused_not_left_out(scenarios, tmp_path):
    # roifem run goes on an earlier run ([restart]); a Simulation steps from rest and says so.
    text = (scenarios / "paper-setup2.toml").read_text().replace('"../meshes/', f'"{scenarios.parent / "meshes"}/')
    (tmp_path / "restart.toml").write_text(text + '\n[restart]\nfrom = "earlier/results.h5"\n')
    with pytest.raises(roifem.InputError, match=r"\[restart\]: roifem.Simulation steps from rest"):
        roifem.Simulation(tmp_path / "restart.toml")
