# SPDX-License-Identifier: GPL-3.0-or-later
"""roifem.paper, roifem.compare and roifem.roi_size: their tables as NumPy structured arrays,
equal to the CSV files the same run wrote (the CLI's writers)."""
import csv

import numpy as np
import pytest

import roifem


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def test_paper_returns_its_tables_as_the_csv_has_them(source_dir, tmp_path):
    r = roifem.paper(source_dir / "meshes/brain-800.msh", tmp_path, steps=40, ramps_s=[0.5], setup_nodes=[306, 228],
                     reductions=["static", "guyan"], timing_steps=50, plots=False, error_budget=False, verbose=False)
    assert r["force_N"] == pytest.approx(0.0160, rel=0.01)  # the 4 mm opening of the shipped brain
    errors = r["errors"]
    assert set(errors["setup"]) == {"setup1", "setup2"} and set(errors["reduction"]) == {"static", "guyan"}
    assert len(errors) == 2 * 2 * 40
    rows = read_csv(tmp_path / "errors.csv")
    assert len(rows) == len(errors)
    for ours, theirs in zip(errors, rows):
        assert (ours["setup"], ours["reduction"], ours["step"]) == (theirs["setup"], theirs["reduction"], int(theirs["step"]))
        assert ours["max_mm"] == pytest.approx(float(theirs["max_mm"]), rel=1e-5, abs=1e-9)
    # Guyan keeps the static part's inertia: its peak error is below static condensation's.
    red = r["reductions"]
    for setup in ("setup1", "setup2"):
        static = red[(red["setup"] == setup) & (red["reduction"] == "static")]["peak_max_mm"][0]
        guyan = red[(red["setup"] == setup) & (red["reduction"] == "guyan")]["peak_max_mm"][0]
        assert 0 < guyan < static
    timing = r["timing"]
    assert list(timing["model"][:1]) == ["full"] and np.all(timing["step_s_median"] > 0)


def test_compare_returns_its_rows_and_marks_unfinished_runs(scenarios, tmp_path):
    sc = roifem.Scenario(scenarios / "paper-setup2.toml")
    r = roifem.compare(sc, tmp_path, integrators=["trapezoid", "arkode-erk2"], t_end=1.0, fixed_levels=4,
                       tolerances=[1e-4], plots=False, verbose=False)
    rows = r["rows"]
    assert set(rows["integrator"]) == {"trapezoid", "arkode-erk2"}
    csv_rows = read_csv(tmp_path / "compare.csv")
    assert len(csv_rows) == len(rows)
    # one column list writes both: the same names, in the same order, and the same figures
    assert list(rows.dtype.names) == list(csv_rows[0].keys())
    for ours, theirs in zip(rows, csv_rows):
        assert ours["integrator"] == theirs["integrator"] and ours["steps"] == int(theirs["steps"])
        if theirs["err_max_mm"]:
            assert ours["err_max_mm"] == pytest.approx(float(theirs["err_max_mm"]), rel=1e-6)
    stability = r["stability"]
    assert list(stability.dtype.names) == list(read_csv(tmp_path / "stability.csv")[0].keys())
    finished = rows[rows["status"] == "ok"]
    assert len(finished) > 0 and np.all(np.isfinite(finished["err_max_mm"]))
    assert np.all(np.isnan(rows[rows["status"] != "ok"]["err_max_mm"]))
    trapezoid = rows[rows["integrator"] == "trapezoid"]
    # second order: halving dt divides the error by about four once dt resolves the ramp's kink
    # (0.456, 0.238, 0.0745, 0.0202 mm at dt = 0.05 .. 0.00625 s)
    ratio = trapezoid["err_max_mm"][-2] / trapezoid["err_max_mm"][-1]
    assert 3.0 < ratio < 5.0
    assert r["omega_max"] > 0


def test_roi_size_returns_the_answer_and_every_probe(scenarios, tmp_path):
    sc = tmp_path / "short.toml"
    sc.write_text((scenarios / "paper-setup2.toml").read_text()
                  .replace('"../meshes/', '"' + str(scenarios.parent / "meshes") + "/").replace("steps = 200", "steps = 30"))
    r = roifem.roi_size(sc, max_error_mm=0.2, reductions=["static"], coarse=1.0, resolution=0.2, timing_steps=20,
                        verbose=False)
    row = r["rows"][0]
    assert row["reduction"] == "static" and row["found"]
    probes = r["probes"]["static"]
    # every size tried from the answer up holds; the answer's own error is within the budget
    assert np.all(probes[probes["nodes"] >= row["nodes"]]["peak_max_mm"] <= 0.2)
    assert row["peak_max_mm"] <= 0.2 and row["nodes"] <= r["free_nodes"]


def test_ctrl_c_stops_a_study_and_gives_python_its_handler_back(source_dir, tmp_path):
    import os
    import signal
    import subprocess
    import time

    handler = signal.getsignal(signal.SIGINT)
    # Ctrl-C from outside, one second into the study (as a terminal sends it)
    sender = subprocess.Popen(["sh", "-c", f"sleep 1; kill -INT {os.getpid()}"])
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt, match="signal 2"):
        roifem.paper(source_dir / "meshes/brain-800.msh", tmp_path, steps=100000, ramps_s=[0.5], setup_nodes=[306],
                     reductions=["static"], plots=False, error_budget=False, verbose=False)
    sender.wait()
    assert time.perf_counter() - start < 30  # stopped between two steps, not at the end
    assert signal.getsignal(signal.SIGINT) is handler
    assert not (tmp_path / "errors.csv").exists()  # nothing half-written in place of a result
