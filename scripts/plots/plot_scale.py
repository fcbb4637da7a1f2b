#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Per-step time against brain size, from `roifem_scale_benchmark`.

usage: /usr/bin/python3 plot_scale.py DIR
reads DIR/scale.csv; writes DIR/scale.png (log-log: one curve per model, the 1998 figures of
Hansen & Larsen at 799 nodes, and the 20 Hz and 1 kHz lines), to a temporary name, then renamed.
"""
import csv
import os
import sys
from collections import defaultdict

from plotting import plt, save, uncommented

# Hansen & Larsen (1998), per step on their hardware: the 799-node brain and its two ROI setups.
PAPER_1998 = [(799, 0.440, "full"), (799, 0.071, "306-node ROI"), (799, 0.037, "228-node ROI")]


def main(directory):
    curves = defaultdict(lambda: ([], []))
    with open(os.path.join(directory, "scale.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            if row["status"] != "ok":
                continue
            nodes, step = curves[row["model"]]
            nodes.append(int(row["nodes"]))
            step.append(float(row["step_median_ms"]) * 1e-3)
    fig, ax = plt.subplots(figsize=(7, 5))
    for model, (nodes, step) in curves.items():
        order = sorted(range(len(nodes)), key=nodes.__getitem__)
        ax.loglog([nodes[i] for i in order], [step[i] for i in order], "o-", label=f"roifem {model}")
    for nodes, step, label in PAPER_1998:
        ax.loglog([nodes], [step], "k^" if label == "full" else "kv", markersize=9, markerfacecolor="none", label=f"1998: {label}")
    ax.axhline(0.05, color="tab:green", linestyle="--", label="20 Hz (real time at dt = 0.05 s)")
    ax.axhline(0.001, color="tab:red", linestyle="--", label="1 kHz (haptic)")
    ax.set_xlabel("brain nodes")
    ax.set_ylabel("time per step (s), median")
    ax.set_title("Trapezoidal step: full and condensed brains")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    save(fig, os.path.join(directory, "scale.png"))


if __name__ == "__main__":
    main(sys.argv[1])
