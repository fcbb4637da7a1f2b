#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots of `roifem paper` in the manner of Hansen & Larsen (1998), Figs. 5 and 6.

usage: /usr/bin/python3 plot_paper.py DIR
reads DIR/errors.csv and DIR/timing.csv; writes DIR/mean_error.png, DIR/max_error.png (the
paper's static condensation), DIR/step_time.png and DIR/reductions.png (static condensation, Guyan
and Craig-Bampton at the fastest ramp) and, driven by spatulas (DIR/force_errors.csv),
DIR/force_error.png, each written to a temporary name, then renamed (the error budget's plot:
plot_error_budget.py).
"""
import csv
import os
import sys
from collections import defaultdict

from plotting import plt, save, uncommented

PAPER_STEP_S = {"full": 0.440, "setup1": 0.071, "setup2": 0.037}


def main(directory):
    every = defaultdict(lambda: ([], [], []))  # (setup, reduction, ramp) -> steps, mean, max
    reductions = []
    with open(os.path.join(directory, "errors.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            steps, mean, worst = every[(row["setup"], row["reduction"], float(row["ramp_s"]))]
            steps.append(int(row["step"]))
            mean.append(float(row["mean_mm"]))
            worst.append(float(row["max_mm"]))
            if row["reduction"] not in reductions:
                reductions.append(row["reduction"])
    curves = {(s, r): data for (s, red, r), data in every.items() if red == "static"}
    setups = sorted({s for s, _ in curves})
    ramps = sorted({r for _, r in curves})
    titles = {"setup1": "setup 1 (306-node ROI)", "setup2": "setup 2 (228-node ROI)"}

    for column, name, label in ((1, "mean_error.png", "mean error (mm)"), (2, "max_error.png", "max error (mm)")):
        fig, axes = plt.subplots(1, len(setups), figsize=(5.5 * len(setups), 4), sharey=True, squeeze=False)
        for ax, setup in zip(axes[0], setups):
            for ramp in ramps:
                data = curves[(setup, ramp)]
                ax.plot(data[0], data[column], label=f"ramp {ramp:g} s")
            ax.set_title(titles.get(setup, setup))
            ax.set_xlabel("iteration (dt = 0.05 s)")
            ax.grid(alpha=0.3)
            ax.legend()
        axes[0][0].set_ylabel(label)
        fig.suptitle(f"Condensed ROI model vs full dynamic model: {label.split(' (')[0]} over the ROI nodes")
        save(fig, os.path.join(directory, name))

    fig, axes = plt.subplots(1, len(setups), figsize=(5.5 * len(setups), 4), sharey=True, squeeze=False)
    for ax, setup in zip(axes[0], setups):
        for reduction in reductions:
            data = every[(setup, reduction, ramps[0])]
            ax.semilogy(data[0], data[2], label=reduction)
        ax.set_title(f"{titles.get(setup, setup)}, ramp {ramps[0]:g} s")
        ax.set_xlabel("iteration (dt = 0.05 s)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("max error over the ROI nodes (mm)")
    fig.suptitle("Static part reduced with inertia: Guyan, Craig-Bampton and POD vs static condensation")
    save(fig, os.path.join(directory, "reductions.png"))

    models, ours = [], []
    with open(os.path.join(directory, "timing.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            models.append(row["model"])
            ours.append(float(row["step_s_median"]))
    fig, ax = plt.subplots(figsize=(6, 4))
    x = range(len(models))
    ax.bar([i - 0.2 for i in x], [PAPER_STEP_S.get(m, float("nan")) for m in models], 0.4, label="Hansen & Larsen 1998")
    ax.bar([i + 0.2 for i in x], ours, 0.4, label="roifem (median, this machine)")
    ax.axhline(0.05, color="k", lw=0.8, ls="--")
    ax.text(len(models) - 0.5, 0.05, " real time (dt = 0.05 s)", va="bottom", ha="right", fontsize=8)
    ax.set_yscale("log")
    ax.set_xticks(list(x), models)
    ax.set_ylabel("time per step (s)")
    ax.legend()
    ax.grid(alpha=0.3, which="both", axis="y")
    save(fig, os.path.join(directory, "step_time.png"))

    forces = os.path.join(directory, "force_errors.csv")
    if os.path.exists(forces):
        plot_force_errors(forces, titles, os.path.join(directory, "force_error.png"))


def plot_force_errors(path, titles, out):
    """The force the surgeon feels: the spatulas' force error (mN and % of the full model's peak)."""
    every = defaultdict(lambda: ([], [], []))  # (setup, ramp) -> steps, error, full force
    with open(path) as f:
        for row in csv.DictReader(uncommented(f)):
            if row["reduction"] != "static":
                continue
            steps, error, full = every[(row["setup"], float(row["ramp_s"]))]
            steps.append(int(row["step"]))
            error.append(float(row["force_err_mN"]))
            full.append(float(row["force_full_mN"]))
    setups = sorted({s for s, _ in every})
    ramps = sorted({r for _, r in every})
    fig, axes = plt.subplots(1, len(setups), figsize=(5.5 * len(setups), 4), sharey=True, squeeze=False)
    for ax, setup in zip(axes[0], setups):
        for ramp in ramps:
            steps, error, full = every[(setup, ramp)]
            ax.plot(steps, error, label=f"ramp {ramp:g} s (peak {100 * max(error) / max(full):.2f}% of the force)")
        ax.set_title(titles.get(setup, setup))
        ax.set_xlabel("iteration (dt = 0.05 s)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("spatula force error (mN)")
    fig.suptitle("The force the surgeon feels: condensed ROI model vs full model, larger of the two spatulas")
    save(fig, out)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
