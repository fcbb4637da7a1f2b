#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots of `roifem compare`.

usage: /usr/bin/python3 plot_compare.py DIR [--reference TEXT]
TEXT: what the errors are measured against (roifem compare passes it: the exact modal solution,
or a tight run of its --reference method); reads DIR/compare.csv; writes DIR/work_precision.png (max error against wall time, log-log, one
line per integrator and mode) and DIR/error_vs_dt.png (fixed-step error against dt, with the
observed order of the two smallest steps beside the method's own). Each integrator keeps one
colour in both plots and a marker of its own (solid: fixed steps, dashed: adaptive), so that
methods that agree (energy-momentum on the trapezoidal rule) stay visible. Runs without figures are
marked: x at the top of the plot for a run that diverged, a triangle for one stopped by
--max-run-seconds, and the legend names every method whose runs did not finish, with why.
"""
import csv
import math
import os
import sys
from collections import defaultdict

from plotting import plt, save, uncommented


def read(directory):
    finished, left_out, theory = defaultdict(list), defaultdict(list), {}
    with open(os.path.join(directory, "compare.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            key = (row["integrator"], row["mode"])
            theory[row["integrator"]] = int(row["theoretical_order"])
            if row["status"] == "ok" and row["stable"] == "1" and row["err_max_mm"] and float(row["err_max_mm"]) > 0:
                finished[key].append((float(row["dt_or_tol"]), float(row["wall_s"]), float(row["err_max_mm"])))
            else:
                left_out[key].append((float(row["dt_or_tol"]), float(row["wall_s"]), row["status"]))
    return finished, left_out, theory


MARKERS = "osD^v<>phX*P8d"


def colours(names):
    palette = plt.cm.tab10.colors + plt.cm.Dark2.colors  # distinct hues first
    return {name: palette[i % len(palette)] for i, name in enumerate(sorted(names))}


def markers(names):
    return {name: MARKERS[i % len(MARKERS)] for i, name in enumerate(sorted(names))}


def why_left_out(points):
    """The first status of runs without figures, in a few words."""
    status = points[0][2]
    return "stopped (--max-run-seconds)" if status.startswith("stopped") else (status.split(":")[0] or "no figures")


def mark_left_out(ax, points, colour, x_of):
    """Marks runs without figures at the top of the axes (x: diverged, triangle: stopped)."""
    for p in points:
        x = x_of(p)
        if x and x > 0:
            ax.plot([x], [0.97], "v" if p[2].startswith("stopped") else "x", color=colour, ms=7, mew=2,
                    transform=ax.get_xaxis_transform(), clip_on=False)


def main(directory, reference):
    finished, left_out, theory = read(directory)
    names = {name for name, _ in list(finished) + list(left_out)}
    colour, marker = colours(names), markers(names)

    fig, ax = plt.subplots(figsize=(9, 7))
    for (name, mode), points in sorted(finished.items()):
        points.sort(key=lambda p: p[1])
        ax.plot([p[1] for p in points], [p[2] for p in points], marker[name] + ("-" if mode == "fixed" else "--"), ms=5,
                mfc="none", color=colour[name], label=f"{name} ({mode})")
    for (name, mode), points in sorted(left_out.items()):
        mark_left_out(ax, points, colour[name], lambda p: p[1])
        if (name, mode) not in finished:
            ax.plot([], [], "v" if points[0][2].startswith("stopped") else "x", color=colour[name], ls="none",
                    label=f"{name} ({mode}): no run finished, {why_left_out(points)}")
    ax.axhline(0.1, color="k", lw=0.8, ls=":")
    ax.annotate("0.1 mm", xy=(0.005, 0.1), xycoords=("axes fraction", "data"), va="bottom", fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the run (s)")
    ax.set_ylabel(f"max error against {reference} (mm)")
    ax.set_title("Work-precision (marks at the top: x diverged, v stopped by --max-run-seconds)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, ncol=2)
    save(fig, os.path.join(directory, "work_precision.png"))

    fig, ax = plt.subplots(figsize=(8, 6))
    for (name, mode), points in sorted(finished.items()):
        if mode != "fixed" or len(points) < 2:
            continue
        points.sort(key=lambda p: p[0])
        (dt1, _, e1), (dt2, _, e2) = points[0], points[1]
        order = math.log(e2 / e1) / math.log(dt2 / dt1) if dt2 != dt1 else float("nan")
        ax.plot([p[0] for p in points], [p[2] for p in points], marker[name] + "-", ms=5, mfc="none", color=colour[name],
                label=f"{name}: order {order:.2f} (theory {theory[name]})")
    for (name, mode), points in sorted(left_out.items()):
        if mode == "fixed":
            mark_left_out(ax, points, colour[name], lambda p: p[0])
            if (name, mode) not in finished:
                ax.plot([], [], "v" if points[0][2].startswith("stopped") else "x", color=colour[name], ls="none",
                        label=f"{name}: no run finished, {why_left_out(points)}")
    ax.axhline(0.1, color="k", lw=0.8, ls=":")
    ax.annotate("0.1 mm", xy=(0.005, 0.1), xycoords=("axes fraction", "data"), va="bottom", fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time step dt (s)")
    ax.set_ylabel(f"max error against {reference} (mm)")
    ax.set_title("Fixed-step error against dt (observed order from the two smallest steps)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, ncol=2)
    save(fig, os.path.join(directory, "error_vs_dt.png"))


if __name__ == "__main__":
    if len(sys.argv) == 2:
        main(sys.argv[1], "the reference")
    elif len(sys.argv) == 4 and sys.argv[2] == "--reference":
        main(sys.argv[1], sys.argv[3])
    else:
        sys.exit(__doc__)
