#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A picture of a tetrahedral mesh's surface, coloured by its named surface sets, or of a cut mesh.

usage: /usr/bin/python3 plot_mesh.py MESH.msh OUT.png [SET ...]
       /usr/bin/python3 plot_mesh.py results.h5 OUT.png [STEP] [--magnify K]
The first reads a Gmsh MSH 4.1 ASCII file (as `roifem mesh` writes it); draws its boundary
triangles (those of the 'surface' set, else every triangle in the file) from the left, from above
and from behind, shaded by the light on them, with the named 2D sets given (default: every 2D set
but 'surface') in colour. The second draws a run's mesh as its cuts left it (the tetrahedra after
the last cut at or before STEP, default the run's last; `roifem run` with [[cut]]s), deformed by
the last displacement field at or before that step (times K, default 1: the title says which), its
faces coloured by the displacement's magnitude (the colour bar in mm), with the faces the cuts laid
open in red (removed tetrahedra gone, or split nodes parted: their copies are the mesh's last nodes;
a separated face opens as two boundary faces, one on each side, so that their count is not the run's
count of separated faces), and a close-up of the cut: the
surface within 12 mm of the opened faces, seen from above and in front. Axes are in mm.
"""
import os
import sys

import numpy as np

from plotting import plt, save


def read_msh(path):
    with open(path) as f:
        lines = f.read().split("\n")
    names = {}
    i = lines.index("$PhysicalNames")
    for k in range(int(lines[i + 1])):
        dim, tag, name = lines[i + 2 + k].split(maxsplit=2)
        names[(int(dim), int(tag))] = name.strip('"')
    entity_groups = {}
    i = lines.index("$Entities")
    counts = [int(x) for x in lines[i + 1].split()]
    row = i + 2
    for dim, count in enumerate(counts):
        for _ in range(count):
            fields = lines[row].split()
            row += 1
            tag = int(fields[0])
            start = 4 if dim == 0 else 7
            n = int(fields[start])
            entity_groups[(dim, tag)] = [names.get((dim, int(t)), "") for t in fields[start + 1:start + 1 + n]]
    nodes = {}
    i = lines.index("$Nodes")
    blocks = int(lines[i + 1].split()[0])
    row = i + 2
    for _ in range(blocks):
        n = int(lines[row].split()[3])
        tags = [int(t) for t in lines[row + 1:row + 1 + n]]
        for k, t in enumerate(tags):
            nodes[t] = [float(x) for x in lines[row + 1 + n + k].split()[:3]]
        row += 1 + 2 * n
    triangles = {}
    i = lines.index("$Elements")
    blocks = int(lines[i + 1].split()[0])
    row = i + 2
    for _ in range(blocks):
        dim, tag, kind, n = (int(x) for x in lines[row].split())
        if kind == 2:
            for name in entity_groups.get((dim, tag), []):
                triangles.setdefault(name, []).extend(
                    [int(x) for x in lines[row + 1 + k].split()[1:4]] for k in range(n))
        row += 1 + n
    return nodes, triangles


def draw(ax, tri, face, title, elev, azim):
    """The triangles `tri` in colours `face` on a 3D axis, to scale (axes in mm), seen from (elev, azim)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    ax.add_collection3d(Poly3DCollection(tri, facecolors=face, edgecolors=(0, 0, 0, 0.15), linewidths=0.2))
    lo, hi = tri.reshape(-1, 3).min(axis=0), tri.reshape(-1, 3).max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for axis, setter in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        setter(centre[axis] - half, centre[axis] + half)
    ax.view_init(elev=elev, azim=azim)
    for label, setter in zip(("x (mm)", "y (mm)", "z (mm)"), (ax.set_xlabel, ax.set_ylabel, ax.set_zlabel)):
        setter(label, fontsize=7, labelpad=-6)
    ax.tick_params(labelsize=6, pad=-2)
    ax.set_title(title)


def main(path, out, wanted):
    nodes, sets = read_msh(path)
    surface = sets.get("surface") or [t for ts in sets.values() for t in ts]
    coloured = wanted or [name for name in sets if name != "surface"]
    colours = plt.get_cmap("tab10")
    views = [("from the left", (0, 180)), ("from above", (90, -90)), ("from behind", (0, -90))]
    fig = plt.figure(figsize=(15, 5.4))
    light = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    for v, (title, (elev, azim)) in enumerate(views):
        ax = fig.add_subplot(1, 3, v + 1, projection="3d")
        tri = np.array([[nodes[n] for n in t] for t in surface])
        normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        shade = 0.35 + 0.6 * np.clip(np.abs(normal @ light), 0, 1)
        face = np.stack([shade, shade, shade * 0.97, np.ones_like(shade)], axis=1)
        key = {tuple(sorted(t)): k for k, t in enumerate(surface)}
        for c, name in enumerate(coloured):
            for t in sets.get(name, []):
                k = key.get(tuple(sorted(t)))
                if k is not None:
                    face[k, :3] = np.array(colours(c % 10)[:3]) * (0.5 + 0.5 * shade[k])
        draw(ax, tri, face, title, elev, azim)
    handles = [plt.Rectangle((0, 0), 1, 1, color=colours(c % 10)) for c in range(len(coloured))]
    fig.legend(handles, coloured, loc="lower center", ncol=max(1, len(coloured)))
    fig.suptitle(f"{os.path.basename(path)}: {len(nodes)} nodes, {len(surface)} boundary triangles; lengths in mm")
    save(fig, out)
    print(out)


def boundary(tets):
    """The faces that belong to one tetrahedron only, as sorted node triples, each with its tetrahedron's order."""
    faces = {}
    for t in tets:
        for f in ((t[0], t[1], t[2]), (t[0], t[3], t[1]), (t[1], t[3], t[2]), (t[0], t[2], t[3])):
            key = tuple(sorted(f))
            faces[key] = None if key in faces else f
    return {k: f for k, f in faces.items() if f is not None}


def main_cut(path, out, step, magnify):
    import h5py
    with h5py.File(path, "r") as h5:
        nodes = h5["mesh/nodes_mm"][:]
        uncut = h5["mesh/tets"][:]
        cuts = sorted(int(k.rsplit("_", 1)[1]) for k in h5["mesh"] if k.startswith("tets_from_step_"))
        steps = h5["time_s"].shape[0] - 1
        step = steps if step is None else step
        at = [k for k in cuts if k <= step]
        if not at:
            sys.exit(f"{path}: no cut at or before step {step} (cuts at steps {cuts or 'none'})")
        tets = h5[f"mesh/tets_from_step_{at[-1]:06d}"][:]
        fields = sorted(int(k.rsplit("_", 1)[1]) for k in h5.get("fields", {}) if int(k.rsplit("_", 1)[1]) <= step)
        displacement = h5[f"fields/displacement_mm_{fields[-1]:06d}"][:] if fields else np.zeros_like(nodes)
        shown = nodes + magnify * displacement
        split_mode = "cuts/split_nodes" in h5
        if split_mode:
            split = int((h5["cuts/split_at_step"][:] <= step).sum())
            what = f"{split} node splits"
        else:
            removed = len(h5["cuts/removed_elements"]) if "cuts/removed_elements" in h5 else len(uncut) - len(tets)
            what = f"{removed} tetrahedra removed"
    before = boundary(uncut)
    after = boundary(tets)
    opened = [f for k, f in after.items() if k not in before]
    surface = list(after.values())
    tri = shown[np.array(surface)]
    is_open = np.array([k not in before for k in after])
    views = [("from the left", (0, 180)), ("from above", (90, -90)), ("from behind", (0, -90))]
    fig = plt.figure(figsize=(20, 5.4))
    light = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1)[:, None], 1e-300)
    shade = 0.35 + 0.6 * np.clip(np.abs(normal @ light), 0, 1)
    magnitude = np.linalg.norm(displacement[np.array(surface)], axis=2).mean(axis=1)  # per face, mm
    top = max(float(magnitude.max()), 1e-12)
    colour_map = plt.get_cmap("viridis")
    face = colour_map(magnitude / top)
    face[:, :3] *= (0.55 + 0.45 * shade)[:, None]
    face[is_open, :3] = np.array([0.85, 0.2, 0.15]) * (0.5 + 0.5 * shade[is_open, None])
    for v, (title, (elev, azim)) in enumerate(views):
        draw(fig.add_subplot(1, 4, v + 1, projection="3d"), tri, face, title, elev, azim)
    if is_open.any():  # the close-up: every surface triangle whose centre lies near the opened faces
        centres = tri.mean(axis=1)
        lo, hi = centres[is_open].min(axis=0) - 12, centres[is_open].max(axis=0) + 12
        near = ((centres >= lo) & (centres <= hi)).all(axis=1)
        draw(fig.add_subplot(1, 4, 4, projection="3d"), tri[near], face[near], "the cut, close up", 50, -60)
    # Not the run's count of separated faces: a face the cuts separate opens as two boundary faces,
    # and a surface face at a split node is a new one too.
    opened_said = (f"{len(opened)} boundary faces the splits made (each separated face opens as two, and a surface "
                   "face at a split node is new too)" if split_mode else f"{len(opened)} boundary faces laid open by the removal")
    fig.legend([plt.Rectangle((0, 0), 1, 1, color=(0.85, 0.2, 0.15))], [opened_said], loc="lower center")
    bar = fig.colorbar(plt.cm.ScalarMappable(norm=plt.Normalize(0, top), cmap=colour_map), ax=fig.axes, shrink=0.6,
                       pad=0.02)
    bar.set_label("displacement magnitude (mm)")
    deformed = (f", deformed as at step {fields[-1]}" + (f" (x{magnify:g})" if magnify != 1 else " (true scale)")
                if fields else ", undeformed (no field stored)")
    fig.suptitle(f"{os.path.basename(path)}: {what} by step {step}{deformed}; lengths in mm")
    save(fig, out)
    print(out)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    if sys.argv[1].endswith(".h5"):
        args = sys.argv[3:]
        magnify = 1.0
        if "--magnify" in args:
            k = args.index("--magnify")
            magnify = float(args[k + 1])
            del args[k:k + 2]
        main_cut(sys.argv[1], sys.argv[2], int(args[0]) if args else None, magnify)
    else:
        main(sys.argv[1], sys.argv[2], sys.argv[3:])
