#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The error budget's plot of `roifem paper` (experiments/error_budget.hpp).

usage: /usr/bin/python3 plot_error_budget.py DIR
reads DIR/error_budget.csv; writes DIR/error_budget.png: the largest error over the ROI from space,
time and reduction (and, from `roifem paper --material-model neo-hookean`, the dynamic model error
and the hybrid's) per setup (rows) and ramp (columns) over the run, log scale, the model error as a
level; written to a temporary name, then renamed.
"""
import csv
import os
import sys
from collections import defaultdict

from plotting import plt, save, uncommented


def plot_error_budget(directory, path):
    """Space, time, reduction (and model) error per setup (rows) and ramp (columns), log scale."""
    curves = defaultdict(lambda: defaultdict(list))  # (setup, ramp) -> column -> values
    with open(path) as f:
        for row in csv.DictReader(uncommented(f)):
            c = curves[(row["setup"], float(row["ramp_s"]))]
            for key, value in row.items():
                if key not in ("setup", "ramp_s"):
                    c[key].append(float(value) if value else float("nan"))
    setups = sorted({s for s, _ in curves})
    ramps = sorted({r for _, r in curves})
    fig, axes = plt.subplots(len(setups), len(ramps), figsize=(4.5 * len(ramps), 3.4 * len(setups)), sharey=True,
                             squeeze=False)
    for i, setup in enumerate(setups):
        for j, ramp in enumerate(ramps):
            ax, c = axes[i][j], curves[(setup, ramp)]
            for key, label in (("space_max_mm", "space"), ("time_max_mm", "time"), ("reduction_max_mm", "reduction"),
                               ("model_dynamic_max_mm", "model (dynamic)"), ("hybrid_max_mm", "hybrid")):
                if key in c and any(v == v and v > 0 for v in c[key]):
                    ax.semilogy(c["t_s"], c[key], label=label)
            model = [v for v in c["model_max_mm"] if v == v]
            if model:
                ax.axhline(model[0], color="k", ls="--", lw=1, label="model (static, full load)")
            ax.set_title(f"{setup}, ramp {ramp:g} s", fontsize=10)
            ax.grid(alpha=0.3, which="both")
            if i == len(setups) - 1:
                ax.set_xlabel("t (s)")
        axes[i][0].set_ylabel("largest error over the ROI (mm)")
    axes[0][0].legend(fontsize=8)
    fig.suptitle("Error budget: where the error on the ROI nodes comes from")
    save(fig, os.path.join(directory, "error_budget.png"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    plot_error_budget(sys.argv[1], os.path.join(sys.argv[1], "error_budget.csv"))
