#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A sweep of ROI size against error and step cost, from Python.

Run (after building; README.md):
    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/roi_size_sweep.py --out results/roi-sweep

The paper's setup with the ROI grown from 40 to 600 nodes around the opening (static condensation
of the rest, 0.5 s ramp, 200 steps). The error is measured where the surgeon works, on a fixed set:
the 228 nodes of setup 2, recovered from the static part when a small ROI leaves them outside it;
the cost is the median wall time of a step. Writes OUT/roi_size_sweep.png and prints the table.
"""
import argparse
import pathlib
import time

import matplotlib
import numpy as np

import roifem

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENARIOS = pathlib.Path(__file__).resolve().parents[2] / "scenarios"
SIZES = (40, 80, 150, 228, 306, 450, 600)


def trajectory(sim, nodes):
    """Displacement (mm) of `nodes` after every step of the scenario's run."""
    out = []
    sim.run(observer=lambda s: out.append(s.displacement()[nodes] / 1e-3))
    return np.stack(out)


def median_step_s(scenario, steps=200):
    sim = roifem.Simulation(scenario, energy=False)
    times = []
    for _ in range(steps):
        start = time.perf_counter()
        sim.step()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, required=True, help="output directory")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    base = roifem.Scenario(SCENARIOS / "paper-setup1.toml")
    site = roifem.Simulation(base, roi={"nodes": 228}).roi_nodes  # where the error is measured
    full = trajectory(roifem.Simulation(base, roi=None, energy=False), site)
    rows = []
    for n in SIZES:
        scenario = base.replace(roi={"nodes": n})
        error = np.linalg.norm(trajectory(roifem.Simulation(scenario, energy=False), site) - full, axis=2).max()
        rows.append((n, error, median_step_s(scenario)))
    full_step = median_step_s(base.replace(roi=None))

    print(f"{'ROI nodes':>9} {'max error (mm)':>15} {'step (ms)':>10}")
    for n, error, step in rows:
        print(f"{n:9d} {error:15.4f} {step * 1e3:10.4f}")
    print(f"{'full':>9} {0.0:15.4f} {full_step * 1e3:10.4f}")

    fig, ax = plt.subplots(figsize=(6, 4))
    sizes, errors, steps = zip(*rows)
    ax.plot(sizes, errors, "o-", color="C0")
    ax.set_xlabel("ROI nodes")
    ax.set_ylabel("max error at the surgical site (mm)", color="C0")
    cost = ax.twinx()
    cost.plot(sizes, np.array(steps) * 1e3, "s--", color="C1")
    cost.axhline(full_step * 1e3, color="C1", lw=0.8, ls=":", label="full model")
    cost.set_ylabel("median step (ms)", color="C1")
    cost.legend(loc="upper center")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out / "roi_size_sweep.png", dpi=120)
    print(f"wrote {args.out / 'roi_size_sweep.png'}")


if __name__ == "__main__":
    main()
