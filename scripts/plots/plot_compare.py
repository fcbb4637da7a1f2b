#!/usr/bin/python3
"""Plots of `roifem compare`.

usage: /usr/bin/python3 plot_compare.py DIR
reads DIR/compare.csv; writes DIR/work_precision.png (max error against wall time, log-log, one
line per integrator and mode) and DIR/error_vs_dt.png (fixed-step error against dt with the
observed order of the last two stable points in the legend).
"""
import csv
import math
import os
import sys
from collections import defaultdict

from plotting import plt, save


def main(directory):
    series = defaultdict(list)
    with open(os.path.join(directory, "compare.csv")) as f:
        for row in csv.DictReader(f):
            if row["stable"] != "1" or not row["err_max_mm"]:
                continue
            err = float(row["err_max_mm"])
            if err <= 0:
                continue
            series[(row["integrator"], row["mode"])].append((float(row["dt_or_tol"]), float(row["wall_s"]), err))

    fig, ax = plt.subplots(figsize=(8, 6))
    ax.set_prop_cycle(color=plt.cm.tab20.colors)  # one colour per series (up to 20)
    for (name, mode), points in sorted(series.items()):
        points.sort(key=lambda p: p[1])
        ax.plot([p[1] for p in points], [p[2] for p in points], "o-" if mode == "fixed" else "s--", ms=3,
                label=f"{name} ({mode})")
    ax.axhline(0.1, color="k", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("max error against the exact modal solution (mm)")
    ax.set_title("Work-precision")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6, ncol=2)
    save(fig, os.path.join(directory, "work_precision.png"))

    fig, ax = plt.subplots(figsize=(8, 6))
    ax.set_prop_cycle(color=plt.cm.tab20.colors)
    for (name, mode), points in sorted(series.items()):
        if mode != "fixed" or len(points) < 2:
            continue
        points.sort(key=lambda p: p[0])
        (dt1, _, e1), (dt2, _, e2) = points[0], points[1]
        order = math.log(e2 / e1) / math.log(dt2 / dt1) if dt2 != dt1 else float("nan")
        ax.plot([p[0] for p in points], [p[2] for p in points], "o-", ms=3, label=f"{name}: order {order:.2f}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time step dt (s)")
    ax.set_ylabel("max error (mm)")
    ax.set_title("Fixed-step error against dt (observed order from the two smallest steps)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6, ncol=2)
    save(fig, os.path.join(directory, "error_vs_dt.png"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
