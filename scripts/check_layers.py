#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The layers, checked: every project #include goes down (or sideways within a rank), never up.

usage: /usr/bin/python3 scripts/check_layers.py [SOURCE_DIR]
The order (docs/architecture.md's table; folders of a rank are siblings and may not include each
other either, unless named in SIBLINGS_ALLOWED):
  common < mesh < io < solvers, anatomy < fem < roi < model < condensation, cutting, integrators
  < scenario < simulation < experiments, serve, distributed < app, python < benchmarks
A file in src/LAYER/, integrators/, python/ or benchmarks/ may include "X/..." only for a layer X of
a lower rank (or its own). An include of a folder that is no layer is an error too. Prints each
include that runs back up, with file and line, and exits 1 when there is one.
"""
import os
import re
import sys

RANKS = [["common"], ["mesh"], ["io"], ["solvers", "anatomy"], ["fem"], ["roi"], ["model"],
         ["condensation", "cutting", "integrators"], ["scenario"], ["simulation"],
         ["experiments", "serve", "distributed"], ["app", "python"], ["benchmarks"]]
RANK = {layer: r for r, layers in enumerate(RANKS) for layer in layers}
ROOTS = {"src": None, "integrators": "integrators", "python": "python", "benchmarks": "benchmarks"}
# A benchmark's own helpers live in its folders (scale/, haptic/): includes of them are its own.
OWN_FOLDERS = {"benchmarks": {"scale", "haptic"}}


def layer_of(path):
    parts = path.split(os.sep)
    if parts[0] == "src":
        return parts[1]
    return ROOTS.get(parts[0])


def main(root):
    problems, files, includes = [], 0, 0
    for top in ROOTS:
        for directory, _, names in os.walk(os.path.join(root, top)):
            for name in sorted(names):
                if not name.endswith((".cpp", ".hpp")):
                    continue
                path = os.path.relpath(os.path.join(directory, name), root)
                layer = layer_of(path)
                if layer not in RANK:
                    continue
                files += 1
                with open(os.path.join(root, path)) as f:
                    for number, line in enumerate(f, 1):
                        m = re.match(r'\s*#include "([A-Za-z0-9_]+)/', line)
                        if not m:
                            continue
                        target = m.group(1)
                        if target == layer or target in OWN_FOLDERS.get(layer, ()):
                            continue
                        includes += 1
                        if target not in RANK:
                            problems.append(f"{path}:{number}: includes \"{target}/...\", which is no layer")
                        elif RANK[target] >= RANK[layer]:
                            problems.append(f"{path}:{number}: {layer} includes {target}/ "
                                            f"({'a sibling' if RANK[target] == RANK[layer] else 'a layer above it'})")
    for p in problems:
        print(p)
    print(f"layers: {files} files, {includes} includes across layers, {len(problems)} running back up")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
