#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plot of `roifem energy`.

usage: /usr/bin/python3 plot_energy.py DIR
reads DIR/energy.csv and DIR/energy_summary.csv; writes DIR/energy_error.png: each method's
energy error |E + D - W - E_0| / max |W| against time (log scale), one line per method; a run
that stopped early ends with an x. Errors at rounding (below 1e-16) are drawn at 1e-16.
"""
import csv
import os
import sys
from collections import defaultdict

from plotting import plt, save, uncommented

FLOOR = 1e-16


def main(directory):
    scale, stopped = {}, set()
    with open(os.path.join(directory, "energy_summary.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            scale[row["integrator"]] = float(row["work_scale_J"]) if row["work_scale_J"] else 0.0
            if row["status"] != "ok":
                stopped.add(row["integrator"])
    series = defaultdict(list)
    with open(os.path.join(directory, "energy.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            name = row["integrator"]
            if scale.get(name, 0) > 0:
                error = abs(float(row["balance_J"])) / scale[name]
                series[name].append((float(row["t_s"]), max(error, FLOOR)))
    fig, ax = plt.subplots(figsize=(8, 5))
    palette = plt.cm.tab10.colors + plt.cm.Dark2.colors
    for i, (name, points) in enumerate(sorted(series.items())):
        colour = palette[i % len(palette)]
        ax.plot([p[0] for p in points], [p[1] for p in points], "-", lw=1.2, color=colour,
                label=name + (" (stopped)" if name in stopped else ""))
        if name in stopped and points:
            ax.plot([points[-1][0]], [points[-1][1]], "x", color=colour, ms=8, mew=2)
    ax.set_yscale("log")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("|E + D - W - E0| / max |W|")
    ax.set_title("Energy error of each method (E kinetic + strain, D damped, W the loads' work)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, ncol=2)
    save(fig, os.path.join(directory, "energy_error.png"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
