# SPDX-License-Identifier: GPL-3.0-or-later
"""The plot scripts (scripts/plots), read back from the figures they draw."""
import sys

import pytest


@pytest.fixture
def plot_convergence(source_dir):
    sys.path.insert(0, str(source_dir / "scripts/plots"))
    import plot_convergence
    yield plot_convergence
    sys.path.pop(0)


def test_the_convergence_plot_labels_each_mesh_by_its_node_count(plot_convergence, tmp_path):
    # Sizes within one decade: matplotlib's log ticks read "1.1x10^1" there (issue 35).
    (tmp_path / "convergence.csv").write_text(
        "# roifem 0.9.0\n"
        "quantity,unit,nodes,dofs,h_mm,value,error,rel_error_pct,order,observed,extrapolated\n"
        "opening,mm,297,800,21.8,2.5,6.2,71.2,2,0,8.8\n"
        "opening,mm,503,1400,17.7,2.7,6.1,69.9,2,0,8.8\n"
        "opening,mm,806,2052,15.1,4.3,4.5,51.0,2,0,8.8\n")
    fig, ax = plot_convergence.plt.subplots()
    plot_convergence.draw_errors(ax, plot_convergence.read_series(tmp_path))
    fig.canvas.draw()
    major = [t.get_text() for t in ax.get_xticklabels()]
    minor = [t.get_text() for t in ax.get_xticklabels(minor=True) if t.get_text()]
    assert major == ["15.1\n806 nodes", "17.7\n503 nodes", "21.8\n297 nodes"]
    assert minor == []
