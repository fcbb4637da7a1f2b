#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plot of `roifem fit`.

usage: /usr/bin/python3 plot_fit.py DIR
reads DIR/fit_data.csv, DIR/fit_curves.csv and DIR/fit.csv; writes DIR/fit-REGION.png for each
region: left, tension and compression (nominal stress against stretch), right, simple shear
(against the amount of shear); the measured points as dots, each law's fit as a line labelled with
its parameters and RMSE.
"""
import csv
import os
import re
import sys
from collections import defaultdict

from plotting import plt, save, uncommented


def main(directory):
    data = defaultdict(list)
    with open(os.path.join(directory, "fit_data.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            data[(row["region"], row["mode"])].append((float(row["deformation"]), float(row["nominal_stress_kPa"])))
    curves = defaultdict(list)
    with open(os.path.join(directory, "fit_curves.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            curves[(row["region"], row["law"], row["mode"])].append(
                (float(row["deformation"]), float(row["nominal_stress_kPa"])))
    fits = defaultdict(list)
    with open(os.path.join(directory, "fit.csv")) as f:
        for row in csv.DictReader(uncommented(f)):
            fits[row["region"]].append(row)
    for region, rows in fits.items():
        fig, (uniaxial, shear) = plt.subplots(1, 2, figsize=(10, 4))
        for mode, axes, marker in (("tension", uniaxial, "o"), ("compression", uniaxial, "s"), ("shear", shear, "o")):
            points = data.get((region, mode), [])
            if points:
                axes.plot([p[0] for p in points], [p[1] for p in points], marker, color="black", markersize=3,
                          label="measured" if mode != "compression" else None)
        for k, row in enumerate(rows):
            law = row["law"]
            label = f"{law}: mu {float(row['mu_Pa']) / 1e3:.3g} kPa"
            if law == "ogden":
                label += f", alpha {float(row['alpha']):.3g}"
            label += f", RMSE {float(row['rmse_kPa']):.3f} kPa"
            color = f"C{k}"
            for mode, axes in (("tension", uniaxial), ("compression", uniaxial), ("shear", shear)):
                line = curves.get((region, law, mode), [])
                if line:
                    axes.plot([p[0] for p in line], [p[1] for p in line], "-", color=color,
                              label=label if mode in ("tension", "shear") else None)
        uniaxial.set_xlabel("stretch lambda")
        uniaxial.set_ylabel("nominal stress P11 (kPa)")
        uniaxial.set_title(f"{region}: tension and compression")
        shear.set_xlabel("amount of shear gamma")
        shear.set_ylabel("nominal stress P12 (kPa)")
        shear.set_title(f"{region}: simple shear")
        for axes in (uniaxial, shear):
            axes.grid(True, alpha=0.3)
            axes.legend(fontsize=7)
        save(fig, os.path.join(directory, "fit-" + re.sub(r"[^A-Za-z0-9_-]", "_", region) + ".png"))


if __name__ == "__main__":
    main(sys.argv[1])
