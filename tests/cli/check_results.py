#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks a results file written by `roifem run` that was stopped before its end.

usage: check_results.py FILE.h5 STATUS_PREFIX MIN_STEPS
Every per-step dataset must hold the same number of steps (>= MIN_STEPS), on the time grid
t_k = k dt, with finite values; the status attribute must start with STATUS_PREFIX ('-' to skip,
for a file cut off by kill -9, which has none).

A kill -9 may land inside a flush (every FLUSH_EVERY steps): HDF5 writes each dataset's new extent
on its own, so the flush it cut may have reached some per-step datasets and not others. What the
writer promises is every step up to the last completed flush (steps 0 .. a multiple of
FLUSH_EVERY), in every dataset: such a file is checked over those steps, and no dataset may be more
than one flush ahead of another.
"""
import sys

import h5py
import numpy as np

FLUSH_EVERY = 50  # src/simulation/scenario_run.cpp

def main(path, status_prefix, min_steps):
    killed = status_prefix == "-"
    with h5py.File(path, "r") as f:
        per_step = [name for name in ["time_s", "step_wall_time_s", "energy/kinetic_J", "energy/strain_J",
                                      "energy/dissipated_J", "energy/external_work_J", "roi/displacement_mm"]
                    if name in f]
        rows = {name: f[name].shape[0] for name in per_step}
        n = min(rows.values())
        if killed:
            assert max(rows.values()) - n <= FLUSH_EVERY, f"per-step datasets more than one flush apart: {rows}"
            n = 1 + FLUSH_EVERY * ((n - 1) // FLUSH_EVERY)  # records 0 .. k, k the last flushed step
        else:
            assert max(rows.values()) == n, f"per-step datasets of different lengths: {rows}"
        for name in per_step:
            assert np.all(np.isfinite(f[name][:n])), f"{name}: non-finite values"
        t = f["time_s"][:n]
        assert n >= min_steps, f"only {n} steps kept (expected >= {min_steps})"
        if n > 1:
            assert np.allclose(np.diff(t), t[1] - t[0], rtol=1e-9), "time_s is not a uniform grid"
        if status_prefix != "-":
            status = f.attrs["status"]
            status = status.decode() if isinstance(status, bytes) else str(status)
            assert status.startswith(status_prefix), f"status '{status}' does not start with '{status_prefix}'"
        print(f"{path}: {n} steps readable, t = {t[0]:g} .. {t[-1]:g} s")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
