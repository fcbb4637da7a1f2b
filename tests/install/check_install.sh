#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# check_install.sh BUILD_DIR SOURCE_DIR: installs the build into a temporary prefix, builds the
# consumer project against it with find_package(roifem) and runs it, and runs the installed CLI.
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$source/tests/install/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/consumer"
"$work/prefix/bin/roifem" info "$work/prefix/share/roifem/meshes/brain-800.msh" | head -2
# The Python package, from the prefix alone (no build tree on the path): Debian's interpreter finds
# it under PREFIX/lib/python3.X/dist-packages, and its RPATH finds the installed libraries.
site=$(echo "$work"/prefix/lib/python3*/dist-packages)
env -u PYTHONPATH PYTHONPATH="$site" /usr/bin/python3 -c "
import roifem
mesh = roifem.read_mesh('$work/prefix/share/roifem/meshes/brain-800.msh')
print('python', roifem.__file__.startswith('$site'), mesh.num_nodes, 'nodes')"
