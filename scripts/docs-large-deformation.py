#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The tables of docs/large-deformation.md, printed from a run's CSV files instead of typed.

usage: /usr/bin/python3 scripts/docs-large-deformation.py DIR
DIR: the --out of `roifem paper --material-model neo-hookean` (large_deformation.csv,
large_deformation_timing.csv). Prints, per drive, the three models' errors against the full
neo-Hookean model (peak over the run of the largest nodal error / steady mean after step 100, mm;
"-" where the run stopped before step 101, with the step it stopped at), the spatulas' force
errors, and Table 2 at large deformation (medians of this machine's step times).
"""
import csv
import os
import sys
from collections import defaultdict

MODELS = ("hybrid", "linear condensed", "full linear")


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def curves(directory):
    out = defaultdict(list)
    for r in rows(os.path.join(directory, "large_deformation.csv")):
        out[(r["drive"], r["setup"], r["model"], float(r["ramp_s"]))].append(r)
    return out


def figure(c, steps):
    peak = max(float(r["max_mm"]) for r in c)
    after = [float(r["mean_mm"]) for r in c if int(r["step"]) > 100]
    if len(c) < steps:
        return f"{peak:.3f} / - (stopped at step {len(c) + 1})"
    return f"{peak:.3f} / {sum(after) / len(after):.3f}" if after else f"{peak:.3f} / -"


def main(directory):
    runs = curves(directory)
    steps = max(len(c) for c in runs.values())
    for drive in ("forces", "spatulas"):
        keys = sorted({(s, ramp) for (d, s, _, ramp) in runs if d == drive})
        if not keys:
            continue
        force = drive == "spatulas"
        print(f"Driven by {drive} (peak max error over the run / steady mean after step 100, mm):\n")
        head = "| setup | ramp | " + " | ".join(MODELS) + (" | force error: hybrid | linear condensed |" if force else " |")
        print(head)
        print("|" + "---|" * (head.count("|") - 1))
        for setup, ramp in keys:
            cells = [figure(runs[(drive, setup, m, ramp)], steps) for m in MODELS]
            if force:
                for m in MODELS[:2]:
                    c = runs[(drive, setup, m, ramp)]
                    peak_full = max(float(r["force_full_mN"]) for r in c)
                    cells.append(f"{100 * max(float(r['force_err_mN']) for r in c) / peak_full:.1f}%")
            print(f"| {setup} | {ramp:.1f} s | " + " | ".join(cells) + " |")
        print()
    timing = rows(os.path.join(directory, "large_deformation_timing.csv"))
    by = {(r["drive"], r["model"]): r for r in timing}
    print("Table 2 at large deformation (ramp 0.5 s; medians of the step time on this machine):\n")
    print("| model | dofs (forces / spatulas) | forces: ms/step, Newton/step | spatulas: ms/step, Newton/step |")
    print("|---|---|---|---|")
    for model in dict.fromkeys(r["model"] for r in timing):
        cells = []
        for drive in ("forces", "spatulas"):
            r = by.get((drive, model))
            if r is None:
                cells.append("-")
                continue
            ms = 1e3 * float(r["step_s_median"])
            newton = float(r["newton_per_step"])
            indefinite = int(r["indefinite_steps"])
            cells.append(f"{ms:.2f}" + (f", {newton:.2f}" if newton > 0 else "") +
                         (f" ({indefinite} steps by LU)" if indefinite else ""))
        dofs = " / ".join(by[(d, model)]["dofs"] for d in ("forces", "spatulas") if (d, model) in by)
        print(f"| {model} | {dofs} | {cells[0]} | {cells[1]} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
