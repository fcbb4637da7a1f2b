#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A scenario whose resolved text is over HDF5's 64 KiB attribute limit, and its check.

usage: many_cuts.py write SCENARIO_DIR OUT.toml   (paper-setup1-cut.toml with 400 copies of its
                                                  blade, 12 steps: about 80 KB resolved)
       many_cuts.py check results.h5              (the scenario stored whole, as the dataset
                                                  /scenario, the attribute saying so)
"""
import pathlib
import re
import sys


def write(scenarios, out):
    text = (pathlib.Path(scenarios) / "paper-setup1-cut.toml").read_text()
    text = text.replace('mesh = "../meshes/', f'mesh = "{pathlib.Path(scenarios).resolve().parent}/meshes/')
    text = re.sub(r"^steps = .*$", "steps = 12", text, flags=re.M)
    head, blade = text[:text.index("[[cut]]")], text[text.index("[[cut]]"):]
    cuts = [blade.replace('name = "incision"', f'name = "incision{k}"')
                 .replace("start_s = 0.5", f"start_s = {0.05 + k * 1e-4:.4f}").replace("duration_s = 2.0", "duration_s = 0.3")
            for k in range(400)]
    pathlib.Path(out).write_text(head + "\n".join(cuts))


def check(results):
    import h5py
    with h5py.File(results, "r") as f:
        said = f.attrs["scenario"]
        said = said.decode() if isinstance(said, bytes) else str(said)
        text = f["scenario"][()].decode()
    assert "beyond an attribute's 64 KiB: in the dataset /scenario" in said, said
    assert len(text) > 65536 and text.count("[[cut]]") == 400, (len(text), text.count("[[cut]]"))
    print(f"ok: the resolved scenario, {len(text)} bytes with 400 [[cut]] tables, stored whole in /scenario")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "write":
        write(sys.argv[2], sys.argv[3])
    elif len(sys.argv) == 3 and sys.argv[1] == "check":
        check(sys.argv[2])
    else:
        sys.exit(__doc__)
