#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots a `roifem run` directory: DIR/results.h5 -> DIR/run.png.

Three panels: the displacement over time (the ROI nodes' largest and mean displacement for a
condensed run, the whole mesh's from the stored fields for a full one), the energy ledger
(kinetic, strain, dissipated, the loads' work, the tools' and the cuts' where the run has them,
and the balance E + D + E_cut - W - W_tools, which closes to round-off for the trapezoidal rule),
and each step's wall time.
Run with Debian's /usr/bin/python3 (python3-h5py, python3-matplotlib).
"""
import sys
from pathlib import Path

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main(directory: Path) -> Path:
    with h5py.File(directory / "results.h5", "r") as h5:
        t = h5["time_s"][()]
        energy = {name: h5["energy/" + name][()] for name in ("kinetic_J", "strain_J", "dissipated_J", "external_work_J",
                                                                "tool_work_J", "cut_J") if "energy/" + name in h5}
        wall = h5["step_wall_time_s"][()]
        status = h5.attrs.get("status", "")
        status = status.decode() if isinstance(status, bytes) else str(status)
        if "roi/displacement_mm" in h5:
            magnitude = np.linalg.norm(h5["roi/displacement_mm"][()], axis=2)  # steps x ROI nodes
            where, t_disp = "ROI nodes", t
        else:
            names = sorted(h5["fields"].keys()) if "fields" in h5 else []
            magnitude = np.array([np.linalg.norm(h5["fields/" + n][()], axis=1) for n in names])
            t_disp = np.array([t[int(n.rsplit("_", 1)[1])] for n in names])
            where = "all nodes (stored fields)"
    fig, (a, b, c) = plt.subplots(3, 1, figsize=(8, 10), sharex=True)
    if magnitude.size:
        a.plot(t_disp, magnitude.max(axis=1), label="largest")
        a.plot(t_disp, magnitude.mean(axis=1), label="mean")
    a.set_ylabel("displacement (mm)")
    a.set_title(f"{directory.name}: displacement of the {where}" + (f" [{status}]" if status and status != "complete" else ""))
    a.legend()
    for name, values in energy.items():
        b.plot(t, values, label=name.replace("_J", "").replace("_", " "))
    zero = np.zeros_like(t)
    balance = (energy["kinetic_J"] + energy["strain_J"] + energy["dissipated_J"] + energy.get("cut_J", zero)
               - energy["external_work_J"] - energy.get("tool_work_J", zero))
    terms = "E + D" + (" + E_cut" if "cut_J" in energy else "") + " - W" + (" - W_tools" if "tool_work_J" in energy else "")
    b.plot(t, balance, "k:", label=f"{terms} (the balance)")
    b.set_ylabel("energy (J)")
    b.legend()
    c.plot(t[1:], 1e3 * wall[1:], ".", markersize=2)
    c.set_ylabel("step wall time (ms)")
    c.set_xlabel("t (s)")
    fig.tight_layout()
    out = directory / "run.png"
    fig.savefig(out, dpi=120)
    return out


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: plot_run.py RUN_DIRECTORY (the --out of roifem run)")
    print(main(Path(sys.argv[1])))
