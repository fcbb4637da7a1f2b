#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""usage: restart_difference.py UNBROKEN.h5 RESTARTED.h5 STEP -- how far a restarted run is from the
run that never stopped: the largest difference of the ROI's displacement (else of the stored fields)
over the steps after STEP, relative to the largest displacement of the unbroken run there. Prints
"difference D" (0 for a restart that goes on bit for bit); the steps up to STEP must be identical."""
import sys

import h5py
import numpy as np


def series(f):
    if "roi/displacement_mm" in f:
        return f["roi/displacement_mm"][()]
    names = sorted(k for k in f["fields"])
    return np.array([f["fields/" + k][()] for k in names])


def main(a, b, step):
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        assert np.array_equal(fa["time_s"][()], fb["time_s"][()]), "the time grids differ"
        x, y = series(fa), series(fb)
        assert x.shape == y.shape, f"shapes differ: {x.shape} and {y.shape}"
        k = step + 1 if "roi/displacement_mm" in fa else 0
        if "roi/displacement_mm" in fa:
            assert np.array_equal(x[:k], y[:k]), "the steps up to the restart point differ"
        scale = np.max(np.abs(x[k:]))
        print(f"difference {np.max(np.abs(x[k:] - y[k:])) / scale:.3e} of the largest displacement {scale:.4g} mm after step {step}")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
