# SPDX-License-Identifier: GPL-3.0-or-later
"""roifem.Simulation against `roifem run` (bit for bit), views, energies, reactions, Ctrl-C."""
import gc
import signal
import subprocess

import h5py
import numpy as np
import pytest

import roifem


def run_cli(cli, scenario, out):
    subprocess.run([cli, "run", str(scenario), "--out", str(out)], check=True, capture_output=True)
    return h5py.File(out / "results.h5", "r")


@pytest.mark.parametrize("name", ["paper-setup1.toml", "paper-setup2.toml"])
def test_roi_displacements_and_energies_equal_the_cli_bit_for_bit(cli, scenarios, tmp_path, name):
    with run_cli(cli, scenarios / name, tmp_path) as h5:
        recorded = h5["roi/displacement_mm"][()]
        strain = h5["energy/strain_J"][()]
        kinetic = h5["energy/kinetic_J"][()]
        nodes = h5["roi/nodes"][()]
    sim = roifem.Simulation(scenarios / name)
    np.testing.assert_array_equal(sim.roi_nodes, nodes)
    steps, energies = [sim.roi_displacement_mm], [(0.0, 0.0)]
    sim.run(observer=lambda s: (steps.append(s.roi_displacement_mm),
                                energies.append((s.energy["strain_J"], s.energy["kinetic_J"]))))
    assert sim.step_index == 200 and len(steps) == 201
    ours = np.stack(steps)
    assert ours.shape == recorded.shape
    assert np.array_equal(ours, recorded)  # bit for bit
    assert np.array_equal(np.array(energies)[:, 0], strain)
    assert np.array_equal(np.array(energies)[:, 1], kinetic)
    assert np.abs(recorded).max() > 1.0  # mm: the walls moved


def test_the_full_models_field_equals_the_cli_bit_for_bit(cli, scenarios, tmp_path):
    with run_cli(cli, scenarios / "paper-full.toml", tmp_path) as h5:
        field = h5["fields/displacement_mm_000200"][()]
    sim = roifem.Simulation(scenarios / "paper-full.toml", energy=False)
    assert sim.run() == 200
    assert sim.energy is None
    assert np.array_equal(sim.displacement() / 1e-3, field)


def test_a_scenario_from_a_dict_equals_the_file(scenarios):
    import tomllib
    with open(scenarios / "paper-setup1.toml", "rb") as f:
        d = tomllib.load(f)
    from_dict = roifem.Scenario.from_dict(d, directory=scenarios)
    from_file = roifem.Scenario(scenarios / "paper-setup1.toml")
    assert from_dict.to_toml() == from_file.to_toml()
    a, b = roifem.Simulation(from_dict), roifem.Simulation(from_file)
    a.run(60)
    b.run(60)
    assert np.array_equal(a.u, b.u) and np.array_equal(a.v, b.v)
    assert a.energy == b.energy


def test_overrides_select_the_roi_reduction_and_integrator(scenarios):
    setup2 = roifem.Scenario(scenarios / "paper-setup2.toml")
    assert roifem.Scenario(scenarios / "paper-setup1.toml", roi={"nodes": 228}).to_toml() == setup2.to_toml()
    assert setup2.replace().to_toml() == setup2.to_toml()
    full = roifem.Scenario(scenarios / "paper-setup1.toml", roi=None)
    assert not full.has_roi
    guyan = roifem.Simulation(setup2, roi={"reduction": "guyan"}, integrator="arkode-sdirk2-schur", rtol=1e-4, steps=4)
    assert guyan.scenario.reduction == "guyan" and guyan.integrator == "arkode-sdirk2-schur"
    assert guyan.run() == 4
    assert guyan.stats["steps"] > 0 and guyan.stats["lin_setups"] > 0
    names = [i["name"] for i in roifem.integrators()]
    assert "trapezoid" in names and "ida-roi-dae" in names


def test_views_keep_their_owner_alive_and_a_closed_simulation_refuses(scenarios):
    sim = roifem.Simulation(scenarios / "paper-setup2.toml")
    u = sim.u
    assert not u.flags.writeable and u.base is not None
    with pytest.raises(ValueError):
        u[0] = 1.0
    sim.step_to(0.5)
    assert np.array_equal(u, sim.u) and np.abs(u).max() > 0  # a view: it follows the steps
    snapshot = u.copy()
    nodes = sim.mesh.nodes
    sim.close()
    with pytest.raises(ValueError, match="closed"):
        sim.u
    with pytest.raises(ValueError, match="closed"):
        sim.step()
    del sim
    gc.collect()
    # still valid: the view holds the stepper. tobytes() copies with memcpy, which ASan checks even
    # from NumPy (not instrumented): a freed state is a heap-use-after-free report there
    assert u.tobytes() == snapshot.tobytes() and nodes.tobytes() == nodes.copy().tobytes()
    assert nodes.shape == (806, 3) and np.isfinite(nodes).all()


def test_an_observer_that_closes_the_simulation_ends_its_run(scenarios):
    sim = roifem.Simulation(scenarios / "paper-setup2.toml")
    assert sim.run(observer=lambda s: s.close() if s.step_index == 3 else None) == 3
    assert sim.closed


def test_energy_balance_holds_to_round_off_for_the_trapezoidal_rule(scenarios):
    sim = roifem.Simulation(scenarios / "paper-setup1.toml")
    residuals = []
    sim.run(observer=lambda s: residuals.append(abs(s.energy["balance_residual_J"]) / abs(s.energy["external_work_J"])))
    assert max(residuals) < 1e-9


def test_reactions_carry_the_weight_of_the_free_tissue_at_rest(scenarios, source_dir):
    # The full brain under gravity, ramped over 2 s, then held for 18 s until the damping (alpha =
    # 0.8/s) has settled it: the base's reactions carry the weight of every node that is not fixed
    # (a fixed node's own weight goes straight into its support). The masses are computed here,
    # independently: a quarter of each tetrahedron's volume to each of its nodes, times rho.
    mesh = roifem.read_mesh(source_dir / "meshes/brain-800.msh")
    x = mesh.nodes[mesh.tets]  # E x 4 x 3
    volumes = np.abs(np.linalg.det(x[:, 1:] - x[:, :1])) / 6
    node_volume = np.zeros(mesh.num_nodes)
    np.add.at(node_volume, mesh.tets, volumes[:, None] / 4)
    free = np.ones(mesh.num_nodes, bool)
    free[mesh.set("base")["nodes"]] = False
    sim = roifem.Simulation(scenarios / "paper-full.toml", energy=False, steps=400,
                            load=[{"gravity_m_s2": [0.0, 0.0, -9.81], "ramp_s": 2.0}])
    rho = float(next(line for line in sim.scenario.to_toml().splitlines() if line.startswith("rho_kg_m3")).split("=")[1])
    weight = rho * 9.81 * node_volume[free].sum()
    sim.run()
    r = sim.reaction_forces()
    assert r["forces_N"].shape == (len(r["nodes"]), 3)
    np.testing.assert_array_equal(r["nodes"], np.flatnonzero(~free))
    np.testing.assert_allclose(r["total_N"], r["forces_N"].sum(axis=0))
    assert r["total_N"][2] == pytest.approx(weight, rel=1e-3)
    assert np.abs(r["total_N"][:2]).max() < 1e-3 * weight


def test_ctrl_c_stops_a_run_between_two_steps(scenarios):
    sim = roifem.Simulation(scenarios / "paper-setup2.toml")

    def observer(s):
        if s.step_index == 5:
            signal.raise_signal(signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        sim.run(observer=observer)
    assert sim.step_index == 5
    sim.step()  # the simulation is whole
    assert sim.step_index == 6


def test_errors_cross_with_their_class_and_message(scenarios, tmp_path):
    with pytest.raises(roifem.InputError, match="unknown key 'time.dt'") as e:
        roifem.Scenario(scenarios / "paper-setup1.toml", time={"dt": 0.01})
    assert isinstance(e.value, ValueError) and isinstance(e.value, roifem.Error)
    with pytest.raises(roifem.InputError, match="trapezium"):
        roifem.Simulation(scenarios / "paper-setup1.toml", integrator="trapezium")
    with pytest.raises(roifem.InputError, match="cannot go into a scenario"):
        roifem.Scenario(scenarios / "paper-setup1.toml", time={"dt_s": object()})
    with pytest.raises(roifem.ModelError, match="no node is fixed"):
        roifem.Simulation(scenarios / "paper-full.toml", boundary={"fixed": []})
    with pytest.raises(roifem.SolverError, match="step"):
        roifem.Simulation(scenarios / "paper-full.toml", integrator="arkode-erk2", dt=0.05).run(20)
    bad = tmp_path / "bad.msh"
    bad.write_text("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
    with pytest.raises(roifem.InputError, match="bad.msh"):
        roifem.read_mesh(bad)


def test_a_mesh_shows_its_nodes_tets_and_sets(source_dir):
    mesh = roifem.read_mesh(source_dir / "meshes/brain-800.msh")
    assert mesh.nodes.shape == (806, 3) and mesh.tets.shape[1] == 4 and mesh.tets.dtype == np.int32
    assert "opening_left" in mesh.set_names
    left = mesh.set("opening_left")
    assert left["dim"] == 2 and left["triangles"].shape[1] == 3
    assert np.all(np.abs(mesh.nodes[left["nodes"], 0] + 0.002) < 1e-9)  # the wall x = -w/2
    with pytest.raises(roifem.InputError, match="opening_left"):
        mesh.set("no_such_set")


def test_an_error_says_what_the_cli_says(cli, scenarios, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((scenarios / "paper-setup1.toml").read_text()
                   .replace('"../meshes/', '"' + str(scenarios.parent / "meshes") + "/").replace("dt_s = 0.05", "dt_s = -0.05"))
    cli_run = subprocess.run([cli, "run", str(bad), "--out", str(tmp_path / "out")], capture_output=True, text=True)
    assert cli_run.returncode == 1
    with pytest.raises(roifem.InputError) as e:
        roifem.Simulation(bad)
    assert "time.dt_s" in str(e.value) and str(e.value) in cli_run.stderr


def test_stats_hold_every_counter_of_the_one_table(scenarios):
    # The counters' names are integrators/stats.hpp's table: Python had three fewer than the C++.
    sim = roifem.Simulation(scenarios / "paper-setup2.toml", steps=2)
    sim.run()
    names = {"steps", "rhs_evals", "jac_evals", "lin_setups", "lin_solves", "failed_steps", "lin_iterations",
             "nonlinear_iterations", "indefinite_steps", "system_changes", "factorization_s"}
    assert set(sim.stats) == names
    assert sim.stats["steps"] == 2
