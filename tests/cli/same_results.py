#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""usage: same_results.py A.h5 B.h5 -- passes when every dataset of two `roifem run` results files is
bit-identical, except the measured wall time per step."""
import sys

import h5py
import numpy as np


def datasets(f):
    names = []
    f.visititems(lambda name, obj: names.append(name) if isinstance(obj, h5py.Dataset) else None)
    return sorted(n for n in names if n != "step_wall_time_s")


def main(a, b):
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names = datasets(fa)
        assert names == datasets(fb), "the files hold different datasets"
        for name in names:
            x, y = fa[name][()], fb[name][()]
            assert x.dtype == y.dtype and x.shape == y.shape, f"{name}: shapes or types differ"
            assert x.tobytes() == y.tobytes(), f"{name}: data differ (max |diff| {np.max(np.abs(x - y))})"
        for key in fa.attrs:
            assert fa.attrs[key] == fb.attrs[key], f"attribute {key} differs"
        print(f"{len(names)} datasets bit-identical")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
