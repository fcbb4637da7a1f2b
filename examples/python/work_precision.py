#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A work-precision diagram of a few integrators, from Python.

Run (after building; README.md):
    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/work_precision.py --out results/wp

roifem.compare runs each integrator on the paper's setup 2 over 1 s (fixed steps dt = 0.05 s down
to dt / 8, and tolerances 1e-3 to 1e-7 for the adaptive ones) against the exact modal solution; its
rows come back as a NumPy structured array. Plotted: the largest error over the ROI against the
wall time, one curve per integrator and mode. Writes OUT/work_precision.png and prints the table.
"""
import argparse
import pathlib

import matplotlib
import numpy as np

import roifem

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENARIOS = pathlib.Path(__file__).resolve().parents[2] / "scenarios"
INTEGRATORS = ["trapezoid", "arkode-sdirk2-schur", "arkode-esdirk4-schur", "ida-bdf5"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, required=True, help="output directory")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    scenario = roifem.Scenario(SCENARIOS / "paper-setup2.toml")
    r = roifem.compare(scenario, args.out, integrators=INTEGRATORS, t_end=1.0, fixed_levels=4,
                       tolerances=[1e-3, 1e-4, 1e-5, 1e-6, 1e-7], plots=False, verbose=False)
    rows = r["rows"][r["rows"]["status"] == "ok"]

    print(f"{'integrator':22} {'mode':9} {'dt or tol':>10} {'steps':>6} {'wall (ms)':>10} {'max error (mm)':>15}")
    for row in rows:
        print(f"{row['integrator']:22} {row['mode']:9} {row['dt_or_tol']:10.3g} {row['steps']:6d} "
              f"{row['wall_s'] * 1e3:10.2f} {row['err_max_mm']:15.3e}")

    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for name in INTEGRATORS:
        for mode, marker in (("fixed", "o-"), ("adaptive", "s--")):
            sel = rows[(rows["integrator"] == name) & (rows["mode"] == mode)]
            if len(sel):
                order = np.argsort(sel["dt_or_tol"])
                ax.loglog(sel["wall_s"][order], sel["err_max_mm"][order], marker, label=f"{name} ({mode})")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("max error over the ROI (mm)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.out / "work_precision.png", dpi=120)
    print(f"wrote {args.out / 'work_precision.png'}")


if __name__ == "__main__":
    main()
