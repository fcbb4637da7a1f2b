#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""usage: results_agree.py A.h5 B.h5 RTOL [PREFIX] -- passes when every floating-point dataset of
two `roifem run` results files (the measured wall times apart; with PREFIX, those whose path starts
with it: "fields" for the motion alone, where the methods' counters differ) agrees to RTOL of its
largest value: two laws, or two forms of one law, that must give the same motion."""
import sys

import h5py
import numpy as np


def float_datasets(f, prefix=""):
    names = []
    f.visititems(lambda name, obj: names.append(name)
                 if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f" else None)
    return sorted(n for n in names if not n.endswith("wall_time_s") and n.startswith(prefix))


def main(a, b, rtol, prefix=""):
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names = float_datasets(fa, prefix)
        assert names and names == float_datasets(fb, prefix), "the files hold different datasets"
        worst, where = 0.0, ""
        for name in names:
            x, y = fa[name][()], fb[name][()]
            assert x.shape == y.shape, f"{name}: shapes differ"
            scale = np.max(np.abs(x)) if x.size else 0.0
            if scale == 0:
                assert np.max(np.abs(y), initial=0.0) == 0, f"{name}: zero in {a}, not in {b}"
                continue
            d = np.max(np.abs(x - y)) / scale
            if d > worst:
                worst, where = d, name
        print(f"{len(names)} datasets agree to {worst:.2e} of their largest value (worst: {where or '-'})")
        assert worst <= rtol, f"{where}: {worst:.2e} > {rtol}"
        print("ok: the results agree")


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]), *sys.argv[4:])
