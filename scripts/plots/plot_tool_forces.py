#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The tools' forces of two or more runs side by side: the paper's comparison of a condensed ROI
model against the full dynamic model, here through the tools a scenario drives.

usage: /usr/bin/python3 plot_tool_forces.py OUT.png REFERENCE_DIR OTHER_DIR [OTHER_DIR ...]
Each DIR holds a `roifem run`'s results.h5 with the same [[tool]]s. Draws, per tool, the force on
the tissue (mN) of every run over time, and below it each other run's difference from the
reference (|F - F_ref|, mN); marks the cuts' first and last step. Prints, per tool and run, the
reference's peak |F| and the largest difference before the first cut and from it on, in mN and
relative to that peak (the reduction error before and after the cut).
"""
import os
import sys

import numpy as np

from plotting import plt, save


def read(directory):
    import h5py
    with h5py.File(os.path.join(directory, "results.h5"), "r") as h5:
        run = {"t": h5["time_s"][:], "tools": {name: h5[f"tools/{name}/force_N"][:] * 1e3 for name in h5["tools"]}}
        run["label"] = (f"condensed ROI ({len(h5['roi/nodes'])} nodes)" if "roi/nodes" in h5 else "full model")
        cut_times = [h5[f"cuts/{k}"][:] for k in ("split_at_s", "removed_at_s") if f"cuts/{k}" in h5]
        run["cuts"] = np.concatenate(cut_times) if cut_times else np.array([])
    return run


def main(out, reference_dir, others):
    ref = read(reference_dir)
    runs = [read(d) for d in others]
    for d, run in zip(others, runs):
        if set(run["tools"]) != set(ref["tools"]) or len(run["t"]) != len(ref["t"]) or not np.allclose(run["t"], ref["t"]):
            sys.exit(f"{d}: its tools or times differ from {reference_dir}'s: compare runs of one scenario")
    first_cut = ref["cuts"].min() if ref["cuts"].size else np.inf
    names = sorted(ref["tools"])
    fig, axes = plt.subplots(2, len(names), figsize=(6.5 * len(names), 7), sharex=True, squeeze=False)
    for c, name in enumerate(names):
        f_ref = ref["tools"][name]
        peak = np.linalg.norm(f_ref, axis=1).max()
        top, bottom = axes[0, c], axes[1, c]
        for k, (label, style) in enumerate((("x", "-"), ("y", ":"), ("z", "--"))):
            top.plot(ref["t"], f_ref[:, k], style, color="black", lw=1.6, label=f"{ref['label']}, F{label}")
            for r, run in enumerate(runs):
                top.plot(run["t"], run["tools"][name][:, k], style, color=f"C{r + 1}", lw=1.0,
                         label=f"{run['label']}, F{label}")
        for r, (d, run) in enumerate(zip(others, runs)):
            gap = np.linalg.norm(run["tools"][name] - f_ref, axis=1)
            before, after = gap[ref["t"] < first_cut], gap[ref["t"] >= first_cut]
            worst = lambda g: g.max() if g.size else 0.0  # noqa: E731
            print(f"{name}: {run['label']} against {ref['label']}: peak |F| {peak:.4g} mN; largest |F - F_ref| "
                  f"before the cut {worst(before):.3g} mN ({worst(before) / peak:.2%}), from it on {worst(after):.3g} mN "
                  f"({worst(after) / peak:.2%})")
            bottom.semilogy(ref["t"], np.maximum(gap, 1e-12), color=f"C{r + 1}", label=run["label"])
        for ax in (top, bottom):
            if ref["cuts"].size:
                ax.axvspan(ref["cuts"].min(), ref["cuts"].max(), color="red", alpha=0.08, label="the blade cuts")
            ax.grid(alpha=0.3)
        top.set_title(f"tool '{name}': force on the tissue")
        top.set_ylabel("force (mN)")
        bottom.set_ylabel(f"|F - F({ref['label']})| (mN)")
        bottom.set_xlabel("time (s)")
        top.legend(fontsize=7, ncol=2)
        bottom.legend(fontsize=8)
    save(fig, out)
    print(out)


if __name__ == "__main__":
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3:])
