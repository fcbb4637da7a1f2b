#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Hansen & Larsen's Fig. 5 from Python: the condensed ROI models' mean error against the step.

Run (after building; README.md):
    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/paper_fig5.py --out results/fig5

The full dynamic model and the two condensed ROI models of scenarios/paper-*.toml are stepped side
by side for load ramps of 0.5, 1 and 2 s; after each step the paper's error is measured: the
distance between the condensed and the full displacement at each ROI node, averaged over the ROI
(and its maximum). Writes OUT/fig5.png (a panel per setup, a curve per ramp) and prints the peaks.
"""
import argparse
import pathlib
import tomllib

import matplotlib
import numpy as np

import roifem

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENARIOS = pathlib.Path(__file__).resolve().parents[2] / "scenarios"


def scenario_with_ramp(name, ramp_s):
    """The shipped scenario with every load ramped over ramp_s, as a dict."""
    with open(SCENARIOS / name, "rb") as f:
        d = tomllib.load(f)
    for load in d["load"]:
        load["ramp_s"] = ramp_s
    return roifem.Scenario.from_dict(d, directory=SCENARIOS)


def error_curves(ramp_s):
    """Per setup: mean and max error (mm) at each step, condensed against full."""
    full = roifem.Simulation(scenario_with_ramp("paper-full.toml", ramp_s), energy=False)
    setups = {name: roifem.Simulation(scenario_with_ramp(f"paper-{name}.toml", ramp_s), energy=False)
              for name in ("setup1", "setup2")}
    curves = {name: ([], []) for name in setups}
    for _ in range(full.scenario.steps):
        full.step()
        u_full_mm = full.displacement() / 1e-3  # N x 3
        for name, sim in setups.items():
            sim.step()
            distance = np.linalg.norm(sim.roi_displacement_mm - u_full_mm[sim.roi_nodes], axis=1)
            curves[name][0].append(distance.mean())
            curves[name][1].append(distance.max())
    return curves


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, required=True, help="output directory")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    ramps = (0.5, 1.0, 2.0)
    results = {ramp: error_curves(ramp) for ramp in ramps}
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, (setup, title) in zip(axes, (("setup1", "setup 1 (306-node ROI)"), ("setup2", "setup 2 (228-node ROI)"))):
        for ramp in ramps:
            mean = results[ramp][setup][0]
            ax.plot(np.arange(1, len(mean) + 1), mean, label=f"ramp {ramp:g} s")
        ax.set_title(title)
        ax.set_xlabel("iteration (dt = 0.05 s)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("mean error (mm)")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(args.out / "fig5.png", dpi=120)

    print(f"{'setup':8} {'ramp (s)':>8} {'peak mean (mm)':>15} {'peak max (mm)':>14}")
    for setup in ("setup1", "setup2"):
        for ramp in ramps:
            mean, worst = results[ramp][setup]
            print(f"{setup:8} {ramp:8g} {max(mean):15.4f} {max(worst):14.4f}")
    print(f"wrote {args.out / 'fig5.png'}")


if __name__ == "__main__":
    main()
