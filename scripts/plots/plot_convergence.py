#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots of `roifem convergence`.

usage: /usr/bin/python3 plot_convergence.py DIR
reads DIR/convergence.csv and DIR/probe_history.csv; writes DIR/convergence.png: left, each
quantity's relative error against the Richardson-extrapolated value over the mesh size h (log-log,
with slopes 1 and 2 for reference); right, the probe's displacement over the run on every mesh and
extrapolated.
"""
import csv
import os
import sys
from collections import defaultdict

from matplotlib.ticker import FixedFormatter, FixedLocator, NullFormatter

from plotting import plt, save, uncommented


def read_series(directory):
    """Per quantity, its (h_mm, rel_error_pct, nodes) on each mesh."""
    series = defaultdict(list)
    with open(os.path.join(directory, "convergence.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            series[row["quantity"]].append((float(row["h_mm"]), float(row["rel_error_pct"]), int(row["nodes"])))
    return series


def draw_errors(ax, series):
    """Each quantity's error over h (log-log, slopes 1 and 2), a tick per mesh with its node count."""
    h_all = []
    for name, points in series.items():
        points = [p for p in points if p[1] > 0]
        if not points:
            continue
        h = [p[0] for p in points]
        h_all += h
        style = "-" if name in ("opening", "opening c3d10", "probe", "dynamic peak") else ":"
        ax.loglog(h, [p[1] for p in points], style, marker="o", label=name)
    if h_all:
        h0, h1 = min(h_all), max(h_all)
        for order, y in ((1, 30.0), (2, 10.0)):
            ax.loglog([h0, h1], [y * (h0 / h1) ** order, y], "k--", lw=0.8, alpha=0.5)
            ax.text(h0, y * (h0 / h1) ** order, f"slope {order}", fontsize=8, alpha=0.7)
    # One tick per mesh, labelled by its size and node count: log ticks within one decade read 1.1x10^1.
    meshes = sorted({(p[0], p[2]) for points in series.values() for p in points})
    ax.xaxis.set_major_locator(FixedLocator([h for h, _ in meshes]))
    ax.xaxis.set_major_formatter(FixedFormatter([f"{h:.3g}\n{n} nodes" for h, n in meshes]))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("mesh size h (mm), and the mesh's node count")
    ax.set_ylabel("error against the extrapolated value (%)")
    ax.set_title("Spatial convergence")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def main(directory):
    series = read_series(directory)
    history_path = os.path.join(directory, "probe_history.csv")
    fig, axes = plt.subplots(1, 2 if os.path.exists(history_path) else 1, figsize=(12, 4.8), squeeze=False)
    draw_errors(axes[0][0], series)
    if os.path.exists(history_path):
        ax = axes[0][1]
        with open(history_path) as f:
            rows = list(csv.DictReader(uncommented(f)))
        t = [float(r["t_s"]) for r in rows]
        for key in rows[0]:
            if key == "t_s":
                continue
            label = "extrapolated" if key == "extrapolated_mm" else key[1:-3] + " nodes"
            ax.plot(t, [float(r[key]) for r in rows], "k--" if key == "extrapolated_mm" else "-", label=label)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("|u| at the probe (mm)")
        ax.set_title("The probe over the run, per mesh")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    save(fig, os.path.join(directory, "convergence.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
