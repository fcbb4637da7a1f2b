# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared helpers of roifem's plot scripts."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported for the scripts)


def save(fig, path):
    """Writes a PNG under a temporary name and renames it into place when complete."""
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".partial.png")
    fig.savefig(tmp, dpi=120, bbox_inches="tight")
    plt.close(fig)
    os.replace(tmp, path)


def uncommented(lines):
    """The lines of a roifem CSV file without its comment lines (the first: '# roifem VERSION')."""
    return (line for line in lines if not line.startswith("#"))

