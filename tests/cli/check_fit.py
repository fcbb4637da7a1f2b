#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks `roifem fit DATA --out DIR` against code that shares nothing with it.

usage: check_fit.py DATA DIR MAX_RMSE_KPA
For each Ogden row of DIR/fit.csv: the incompressible one-term Ogden closed forms (uniaxial
P = 2 mu / alpha (l^(alpha-1) - l^(-alpha/2-1)); simple shear with principal stretch
l = g/2 + sqrt(1 + g^2/4), P12 = 2 mu / alpha (l^alpha - l^-alpha) / (l + 1/l)) at the fitted
parameters, their RMSE against DATA per mode, which must equal the reported RMSE within 2e-3 kPa
(roifem's law is nearly incompressible, kappa = bulk_ratio mu). Each mode's RMSE must be at most
MAX_RMSE_KPA, or, where no one-term Ogden law can meet it, within 5% of the best any can do: the
least worst-mode RMSE over a grid of (mu, alpha) (mu from 0.5 to 2 times the fit's, alpha from
-40 to -2), by the same closed forms. Each neo-Hookean row (alpha = 2) must fit worse than the
same region's Ogden. The PNG and the [material] tables must be there. Prints the table and 'ok: ...'.
"""
import csv
import math
import os
import sys
from collections import defaultdict

import numpy as np


def rows_of(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def uniaxial(mu, alpha, l):
    return 2 * mu / alpha * (l ** (alpha - 1) - l ** (-alpha / 2 - 1))


def shear(mu, alpha, g):
    l = g / 2 + math.sqrt(1 + g * g / 4)
    return 2 * mu / alpha * (l ** alpha - l ** -alpha) / (l + 1 / l)


def least_worst_mode_rmse(points, region, mu_fit):
    """min over a (mu, alpha) grid of the largest of a region's mode RMSEs (kPa), closed forms."""
    mu = np.linspace(0.5, 2.0, 301)[:, None, None] * mu_fit
    alpha = np.linspace(-40, -2, 381)[None, :, None]
    worst = np.zeros((mu.shape[0], alpha.shape[1]))
    for mode in ("tension", "compression", "shear"):
        pts = points.get((region, mode), [])
        if not pts:
            continue
        x = np.array([p[0] for p in pts])[None, None, :]
        y = np.array([p[1] for p in pts])[None, None, :]
        if mode == "shear":
            l = x / 2 + np.sqrt(1 + x * x / 4)
            model = 2 * mu / alpha * (l ** alpha - l ** -alpha) / (l + 1 / l)
        else:
            model = 2 * mu / alpha * (x ** (alpha - 1) - x ** (-alpha / 2 - 1))
        worst = np.maximum(worst, np.sqrt(np.mean((model - y) ** 2, axis=2)))
    return float(worst.min())


def main(data, directory, limit):
    points = defaultdict(list)
    for row in rows_of(data):
        points[(row["region"], row["mode"])].append((float(row["deformation"]), float(row["nominal_stress_kPa"])))
    fits = rows_of(os.path.join(directory, "fit.csv"))
    failures = []
    ogden_rmse = {}
    for fit in fits:
        region, law = fit["region"], fit["law"]
        mu, alpha = float(fit["mu_Pa"]) / 1e3, float(fit["alpha"])
        total, count = 0.0, 0
        for mode in ("tension", "compression", "shear"):
            pts = points.get((region, mode), [])
            if not pts:
                continue
            model = shear if mode == "shear" else uniaxial
            sq = sum((model(mu, alpha, x) - y) ** 2 for x, y in pts)
            total, count = total + sq, count + len(pts)
            closed = math.sqrt(sq / len(pts))
            reported = float(fit[f"rmse_{mode}_kPa"])
            print(f"{region:16s} {law:12s} {mode:12s} RMSE {reported:.4f} kPa (closed form: {closed:.4f})")
            if abs(closed - reported) > 2e-3:
                failures.append(f"{region} {law} {mode}: reported RMSE {reported} against the closed form's {closed}")
            if law == "ogden" and reported > limit:
                bound = least_worst_mode_rmse(points, region, mu)
                print(f"  {region}: above {limit} kPa; no one-term Ogden law does better than {bound:.4f} kPa in its worst mode")
                if reported > 1.05 * bound:
                    failures.append(f"{region} ogden {mode}: RMSE {reported} kPa above {limit} and 5% above the bound {bound}")
        if fit["converged"] != "yes":
            failures.append(f"{region} {law}: not converged")
        if law == "ogden":
            ogden_rmse[region] = float(fit["rmse_kPa"])
        for name in (f"material-{region}-{law}.toml", f"fit-{region}.png"):
            if not os.path.isfile(os.path.join(directory, name)):
                failures.append(f"{name} missing")
    for fit in fits:
        if fit["law"] == "neo-hookean" and fit["region"] in ogden_rmse and \
                float(fit["rmse_kPa"]) <= ogden_rmse[fit["region"]]:
            failures.append(f"{fit['region']}: neo-Hookean fits as well as Ogden")
    if failures or not ogden_rmse:
        print("FAIL: " + "; ".join(failures or ["no Ogden row"]))
        sys.exit(1)
    print(f"ok: {len(fits)} fits, every Ogden mode within {limit} kPa or at the one-term law's bound, the closed forms agree")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]))
