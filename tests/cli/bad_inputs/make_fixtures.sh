#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The meshes of the bad-input suite: make_meshes.py writes the MSH 2.2 ASCII ones; Gmsh itself
# (msh_convert) rewrites the good box as MSH 4.1 and as binary, and each of those four files is
# cut in half. A binary MSH 4.1 file whose $Nodes header claims 10^15 nodes tests the header bound.
# usage: make_fixtures.sh MSH_CONVERT OUT_DIR
set -euo pipefail
convert=$1 out=$2
here=$(dirname "$0")
rm -rf "$out"
/usr/bin/python3 "$here/make_meshes.py" "$out"
"$convert" "$out/box.msh" "$out/box-4.1.msh" 4.1 0
"$convert" "$out/box.msh" "$out/box-2.2-binary.msh" 2.2 1
"$convert" "$out/box.msh" "$out/box-4.1-binary.msh" 4.1 1
for name in box box-4.1 box-2.2-binary box-4.1-binary; do
  size=$(stat -c %s "$out/$name.msh")
  head -c $((size / 2)) "$out/$name.msh" > "$out/truncated-$name.msh"
done
/usr/bin/python3 - "$out/box-4.1-binary.msh" "$out/huge-count-4.1-binary.msh" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
at = data.index(b"$Nodes\n") + len(b"$Nodes\n")
blocks, count = struct.unpack_from("<QQ", data, at)
struct.pack_into("<QQ", data, at, blocks, 10**15)
open(sys.argv[2], "wb").write(data)
PY
mkdir -p "$out/box-dir"  # a directory where a mesh file is expected
echo "fixtures in $out: $(ls "$out" | tr '\n' ' ')"
