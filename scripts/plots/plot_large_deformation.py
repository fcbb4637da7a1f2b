#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The plot of `roifem paper --material-model neo-hookean` (experiments/paper_large_deformation.hpp).

usage: /usr/bin/python3 plot_large_deformation.py DIR
reads DIR/large_deformation.csv; writes DIR/large_deformation.png: per drive (rows) and setup
(columns), the largest error over the ROI against the full neo-Hookean model at the fastest ramp,
over the run, for the hybrid ROI, the linear condensed model and the full linear model (log scale);
written to a temporary name, then renamed.
"""
import csv
import os
import sys
from collections import defaultdict

from plotting import plt, save, uncommented


def plot_large_deformation(directory, path):
    """Each model's max error over the ROI against the full neo-Hookean model, per drive and setup."""
    curves = defaultdict(lambda: defaultdict(list))  # (drive, setup) -> model -> [(t, max)]
    ramps = set()
    with open(path) as f:
        rows = list(csv.DictReader(uncommented(f)))
    for row in rows:
        ramps.add(float(row["ramp_s"]))
    fastest = min(ramps)
    for row in rows:
        if float(row["ramp_s"]) == fastest:
            curves[(row["drive"], row["setup"])][row["model"]].append((float(row["time_s"]), float(row["max_mm"])))
    drives = sorted({d for d, _ in curves})
    setups = sorted({s for _, s in curves})
    fig, axes = plt.subplots(len(drives), len(setups), figsize=(4.8 * len(setups), 3.4 * len(drives)), sharey=True,
                             squeeze=False)
    for i, drive in enumerate(drives):
        for j, setup in enumerate(setups):
            ax = axes[i][j]
            for model, style in (("hybrid", "-"), ("linear condensed", "--"), ("full linear", ":")):
                points = curves[(drive, setup)].get(model, [])
                if points:
                    ax.semilogy([t for t, _ in points], [max(e, 1e-6) for _, e in points], style, label=model)
            ax.set_title(f"{drive}, {setup}, ramp {fastest:g} s", fontsize=10)
            ax.grid(alpha=0.3, which="both")
            if i == len(drives) - 1:
                ax.set_xlabel("t (s)")
        axes[i][0].set_ylabel("largest error over the ROI (mm)")
    axes[0][0].legend(fontsize=8)
    fig.suptitle("Against the full neo-Hookean model: hybrid ROI, linear condensed, full linear")
    save(fig, os.path.join(directory, "large_deformation.png"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    plot_large_deformation(sys.argv[1], os.path.join(sys.argv[1], "large_deformation.csv"))
