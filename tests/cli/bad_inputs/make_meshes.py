# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the meshes of the bad-input suite (MSH 2.2 ASCII) into OUT_DIR.

usage: make_meshes.py OUT_DIR

box.msh is good: a 20 mm cube of 3x3x3 nodes, 48 tetrahedra, with the physical groups 'base'
(triangles on z = 0), 'top' (triangles on z = 20 mm) and 'brain' (the tetrahedra). Each other
file breaks it in one way, named after the way.
"""
import pathlib
import sys

SIZE = 20.0  # mm
N = 3  # nodes per edge
# Kuhn's six tetrahedra of a cube, positively oriented, by corner (i, j, k) offsets.
CUBE_TETS = [
    ((0, 0, 0), (1, 0, 0), (1, 1, 0), (1, 1, 1)),
    ((0, 0, 0), (1, 0, 0), (1, 1, 1), (1, 0, 1)),
    ((0, 0, 0), (1, 0, 1), (1, 1, 1), (0, 0, 1)),
    ((0, 0, 0), (1, 1, 0), (0, 1, 0), (1, 1, 1)),
    ((0, 0, 0), (0, 1, 0), (0, 1, 1), (1, 1, 1)),
    ((0, 0, 0), (0, 1, 1), (0, 0, 1), (1, 1, 1)),
]


def box(offset=(0.0, 0.0, 0.0), first_tag=1):
    """Nodes {tag: (x, y, z)}, tetrahedra [tags], and the base and top triangles of one cube."""
    tag = {}
    nodes = {}
    h = SIZE / (N - 1)
    for k in range(N):
        for j in range(N):
            for i in range(N):
                t = first_tag + len(nodes)
                tag[i, j, k] = t
                nodes[t] = (offset[0] + i * h, offset[1] + j * h, offset[2] + k * h)
    tets = []
    for k in range(N - 1):
        for j in range(N - 1):
            for i in range(N - 1):
                for corners in CUBE_TETS:
                    tets.append([tag[i + a, j + b, k + c] for a, b, c in corners])
    def face(k):
        tris = []
        for j in range(N - 1):
            for i in range(N - 1):
                a, b, c, d = tag[i, j, k], tag[i + 1, j, k], tag[i + 1, j + 1, k], tag[i, j + 1, k]
                tris += [[a, b, c], [a, c, d]]
        return tris
    return nodes, tets, face(0), face(N - 1)


def write_msh(path, nodes, tets, base, top, ghost=()):
    """ghost: triangles of a fourth surface group 'ghost' (written only when given)."""
    names = ['2 1 "base"', '2 2 "top"', '3 3 "brain"'] + (['2 4 "ghost"'] if ghost else [])
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat",
             "$PhysicalNames", str(len(names)), *names, "$EndPhysicalNames",
             "$Nodes", str(len(nodes))]
    lines += [f"{t} {x!r} {y!r} {z!r}" for t, (x, y, z) in sorted(nodes.items())]
    lines += ["$EndNodes", "$Elements", str(len(base) + len(top) + len(tets) + len(ghost))]
    e = 0
    for group, kind, elements in ((1, 2, base), (2, 2, top), (3, 4, tets), (4, 2, ghost)):
        for element in elements:
            e += 1
            lines.append(f"{e} {kind} 2 {group} {group} " + " ".join(map(str, element)))
    lines += ["$EndElements", ""]
    pathlib.Path(path).write_text("\n".join(lines))


def main():
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    nodes, tets, base, top = box()
    write_msh(out / "box.msh", nodes, tets, base, top)
    write_msh(out / "no-tetrahedra.msh", nodes, [], base, top)
    # A fifth corner of the bottom face makes a flat tetrahedron with three others.
    write_msh(out / "zero-volume.msh", nodes, tets + [[1, 2, 4, 5]], base, top)
    # The tetrahedra of the upper layer get their own copies of the mid-plane nodes: a seam.
    seam_nodes = dict(nodes)
    copy = {}
    for t, (x, y, z) in nodes.items():
        if z == SIZE / 2:
            copy[t] = max(seam_nodes) + 1
            seam_nodes[copy[t]] = (x, y, z)
    upper = lambda tet: min(nodes[t][2] for t in tet) >= SIZE / 2
    seam_tets = [[copy.get(t, t) for t in tet] if upper(tet) else tet for tet in tets]
    seam_top = [[copy.get(t, t) for t in tri] for tri in top]
    write_msh(out / "duplicate-nodes.msh", seam_nodes, seam_tets, base, seam_top)
    # A second cube 40 mm along x sharing nothing with the first and held by nothing.
    nodes2, tets2, _, _ = box(offset=(2 * SIZE, 0.0, 0.0), first_tag=len(nodes) + 1)
    write_msh(out / "two-pieces.msh", {**nodes, **nodes2}, tets + tets2, base, top)
    # The second tetrahedron with two nodes swapped: negative volume.
    write_msh(out / "inverted.msh", nodes, [tets[0], [tets[1][1], tets[1][0]] + tets[1][2:]] + tets[2:], base, top)
    write_msh(out / "nan-coordinate.msh", {**nodes, 14: (10.0, float("nan"), 10.0)}, tets, base, top)
    # What deleting tetrahedra leaves: triangles of 'top' and 'base' over a node no tetrahedron
    # uses (28 and 29 lie beside the cube), and a group 'ghost' of such a triangle alone.
    loose = {**nodes, 28: (30.0, 10.0, 20.0), 29: (30.0, 10.0, 0.0)}
    write_msh(out / "orphan-triangles.msh", loose, tets, base + [[3, 6, 29]], top + [[21, 24, 28]], ghost=[[21, 28, 24]])
    (out / "malformed.msh").write_text("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 zero 0 0\n")


main()
