#!/usr/bin/python3
"""Checks a results file written by `roifem run` that was stopped before its end.

usage: check_results.py FILE.h5 STATUS_PREFIX MIN_STEPS
Every per-step dataset must hold the same number of steps (>= MIN_STEPS), on the time grid
t_k = k dt, with finite values; the status attribute must start with STATUS_PREFIX ('-' to skip,
for a file cut off by kill -9, which has none).
"""
import sys

import h5py
import numpy as np


def main(path, status_prefix, min_steps):
    with h5py.File(path, "r") as f:
        t = f["time_s"][:]
        n = len(t)
        per_step = ["step_wall_time_s", "energy/kinetic_J", "energy/strain_J", "energy/dissipated_J",
                    "energy/external_work_J", "roi/displacement_mm"]
        for name in per_step:
            if name in f:
                assert f[name].shape[0] == n, f"{name}: {f[name].shape[0]} rows, time_s has {n}"
                assert np.all(np.isfinite(f[name][:])), f"{name}: non-finite values"
        assert n >= min_steps, f"only {n} steps kept (expected >= {min_steps})"
        dt = t[1] - t[0]
        assert np.allclose(np.diff(t), dt, rtol=1e-9), "time_s is not a uniform grid"
        if status_prefix != "-":
            status = f.attrs["status"]
            status = status.decode() if isinstance(status, bytes) else str(status)
            assert status.startswith(status_prefix), f"status '{status}' does not start with '{status_prefix}'"
        print(f"{path}: {n} steps readable, t = {t[0]:g} .. {t[-1]:g} s")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
