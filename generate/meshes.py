"""The round and anthropomorphic hand meshes, made from a few numbers.

Every part is a *loft*: closed rings of points stacked one above the other, joined by
triangles, closed by a flat cap or a pole at each end. Flat faces (the cuts of the
connector sides, the caps, the palm's front and back) are white, curved ones blue, as in
1.0's files, so a round hand can recolour the blue to grey. Sizes are the bounding boxes
of 1.0's files (``server.core.model.part_figures.MESH_BOUNDS``); the shapes are our own.

``make generate`` writes ``assets/gltf/*.glb``; ``build(name)`` makes one mesh.
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import numpy as np
import trimesh

from server.core.model.part_figures import MESH_BOUNDS, MESH_BLUE, MESH_WHITE

GLTF_DIR = Path(__file__).resolve().parents[1] / "assets" / "gltf"
AROUND = 48  # points per ring
FLAT = 1e-9  # how far from a cutting plane a point still lies on it

Rings = list[np.ndarray]  # each (AROUND, 3)


def loft(rings: Rings, bottom: str, top: str) -> trimesh.Trimesh:
    """Rings joined in order; each end closed by a 'cap' (flat fan) or a 'pole' (a point)."""
    n = len(rings[0])
    vertices = np.concatenate(rings)
    faces = []
    for k in range(len(rings) - 1):
        a, b = k * n, (k + 1) * n
        for j in range(n):
            j2 = (j + 1) % n
            faces += [(a + j, a + j2, b + j2), (a + j, b + j2, b + j)]
    for ring_index, kind in ((0, bottom), (len(rings) - 1, top)):
        centre = len(vertices)
        point = rings[ring_index].mean(axis=0)
        vertices = np.vstack([vertices, point])
        base = ring_index * n
        step = 1 if ring_index == 0 else -1  # the top fan turns the other way round
        faces += [(centre, base + (j + step) % n, base + j) for j in range(n)]
        if kind == "pole":  # the ring is a point already: the fan is degenerate, drop it
            faces = faces[:-n]
            vertices = vertices[:-1]
    mesh = trimesh.Trimesh(vertices, np.array(faces), process=True)
    mesh.remove_unreferenced_vertices()
    mesh.update_faces(mesh.nondegenerate_faces())
    if mesh.volume < 0:  # rings turning the other way: faces inside out
        mesh.invert()
    return mesh


def clamp_ring(radius_x: float, radius_z: float, y: float, half_x: float,
               half_z: float) -> np.ndarray:
    """An ellipse at height ``y`` with its sides cut flat at |x| = half_x and |z| = half_z."""
    angles = np.linspace(0, 2 * np.pi, AROUND, endpoint=False)
    x = np.clip(radius_x * np.cos(angles), -half_x, half_x)
    z = np.clip(radius_z * np.sin(angles), -half_z, half_z)
    return np.column_stack([x, np.full(AROUND, y), z])


def superellipse(t: np.ndarray, power: float) -> np.ndarray:
    """|t|^power-rounded profile: 1 in the middle (t = 0), 0 at |t| = 1."""
    return np.clip(1 - np.abs(t) ** power, 0, 1) ** (1 / power)


def segment(low: float, high: float, half: float, tip: bool) -> trimesh.Trimesh:
    """A finger segment from y=low to y=high: rounded, four flat sides, flat connector ends.

    The section is a circle of radius 1.3·half cut to a square of side 2·half; along y it
    narrows towards the ends (a superellipse), leaving flat discs where neighbours join.
    A tip's top is a dome (a pole) instead.
    """
    centre, reach = (low + high) / 2, (high - low) / 2
    ys = centre + reach * np.sin(np.linspace(-np.pi / 2, np.pi / 2, 33))
    overshoot = 1.0 if tip else 1.12  # the profile reaches 0 past the ends: flat discs
    rings = []
    for y in ys:
        t = (y - centre) / (reach * overshoot)
        if tip and y < centre:  # a tip keeps a flat connector at its base only
            t = (y - centre) / (reach * 1.12)
        r = 1.3 * half * superellipse(t, 3.0)
        rings.append(clamp_ring(r, r, float(y), half, half))
    return loft(rings, "cap", "pole" if tip else "cap")


def palm_outline(cut: tuple[float, float, float] | None) -> Callable[[float], np.ndarray]:
    """The palm's outline in XY (a rounded, slightly tapered square), shrunk by ``inset``.

    ``cut`` (nx, ny, c) cuts the outline flat along nx·x + ny·y = c (the thumb's seat).
    """
    (x0, x1), (y0, y1), _ = MESH_BOUNDS["round-palm.glb"]
    cx, cy, a, b = (x0 + x1) / 2, (y0 + y1) / 2, (x1 - x0) / 2, (y1 - y0) / 2
    angles = np.linspace(0, 2 * np.pi, AROUND * 2, endpoint=False)

    def ring(inset: float) -> np.ndarray:
        c, s = np.cos(angles), np.sin(angles)
        x = np.sign(c) * np.abs(c) ** (2 / 3.5) * (a - inset)
        y = np.sign(s) * np.abs(s) ** (2 / 3.5) * (b - inset)
        x *= 1 - 0.22 * np.clip(y / b, 0, 1) ** 2 - 0.3 * np.clip(-y / b, 0, 1) ** 3
        points = np.column_stack([cx + x, cy + y])
        if cut is not None:
            normal, limit = np.array(cut[:2]), cut[2]
            over = points @ normal - limit
            points -= np.outer(np.clip(over, 0, None), normal)
        return points
    return ring


def slab(outline: Callable[[float], np.ndarray], half_z: float) -> trimesh.Trimesh:
    """A flat plate of the outline, |z| ≤ half_z, its rim rounded (a half-round edge)."""
    rings = []
    for phi in np.linspace(-np.pi / 2, np.pi / 2, 17):
        z = half_z * np.sin(phi)
        inset = half_z * 0.9 * (1 - np.cos(phi))
        xy = outline(inset)
        rings.append(np.column_stack([xy[:, 0], xy[:, 1], np.full(len(xy), z)]))
    return loft(rings, "cap", "cap")


def thumb() -> trimesh.Trimesh:
    """The thumb's base: a rounded body along z, flat at its sides (x) and its front (z)."""
    (x0, x1), (y0, y1), (z0, z1) = MESH_BOUNDS["anthro-thumb.glb"]
    half_x, cy, ry = (x1 - x0) / 2, (y0 + y1) / 2, (y1 - y0) / 2
    rings = []
    for z in z0 + (z1 - z0) * (1 - np.cos(np.linspace(0, np.pi, 29))) / 2:
        t = (z - (z0 + z1) / 2) / ((z1 - z0) / 2 * 1.08)
        scale = superellipse(t, 2.6)
        ring = clamp_ring(1.35 * half_x * scale, ry * scale, 0.0, half_x, ry)
        rings.append(np.column_stack([ring[:, 0] + (x0 + x1) / 2, ring[:, 2] + cy,
                                      np.full(AROUND, z)]))
    return loft(rings, "cap", "cap")


def fit(mesh: trimesh.Trimesh, name: str) -> trimesh.Trimesh:
    """Scale and move ``mesh`` so that its bounding box is exactly the one of ``name``."""
    target = np.array(MESH_BOUNDS[name], dtype=float)  # (3, 2): low, high per axis
    low, high = mesh.bounds
    scale = (target[:, 1] - target[:, 0]) / (high - low)
    mesh.vertices = (mesh.vertices - low) * scale + target[:, 0]
    return mesh


def painted(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """Flat faces white, curved faces blue; vertices split where colours or planes meet.

    A face is flat when a neighbour across each of its edges has the same normal; the
    blue part keeps smooth normals, every flat face its own plane's normal.
    """
    normals = mesh.face_normals
    adjacency = mesh.face_adjacency
    same = np.einsum("ij,ij->i", normals[adjacency[:, 0]], normals[adjacency[:, 1]]) > 1 - 1e-9
    flat_neighbours = np.zeros(len(mesh.faces), int)
    np.add.at(flat_neighbours, adjacency[same].ravel(), 1)
    flat = flat_neighbours >= 2
    smooth = mesh.vertex_normals
    parts = []
    for face_indices, colour in ((np.nonzero(~flat)[0], MESH_BLUE), (np.nonzero(flat)[0], MESH_WHITE)):
        if len(face_indices) == 0:
            continue
        groups = [face_indices] if colour is MESH_BLUE else _by_plane(normals, face_indices)
        for group in groups:
            part = mesh.submesh([group], append=True)
            rgba = np.round(np.array([*colour, 1.0]) * 255)
            part.visual = trimesh.visual.ColorVisuals(part, vertex_colors=np.tile(rgba, (len(part.vertices), 1)).astype(np.uint8))
            part.vertex_normals = (np.tile(normals[group[0]], (len(part.vertices), 1))
                                   if colour is MESH_WHITE else _smooth_at(mesh, smooth, part))
            parts.append(part)
    return _joined(parts)


def _by_plane(normals: np.ndarray, faces: np.ndarray) -> list[np.ndarray]:
    keys = np.round(normals[faces], 6)
    _, inverse = np.unique(keys, axis=0, return_inverse=True)
    return [faces[inverse.ravel() == k] for k in range(inverse.max() + 1)]


def _smooth_at(mesh: trimesh.Trimesh, smooth: np.ndarray, part: trimesh.Trimesh) -> np.ndarray:
    _, index = mesh.kdtree.query(part.vertices)
    return smooth[index]


def _joined(parts: list[trimesh.Trimesh]) -> trimesh.Trimesh:
    vertices, faces, colours, normals, offset = [], [], [], [], 0
    for part in parts:
        vertices.append(part.vertices)
        faces.append(part.faces + offset)
        colours.append(part.visual.vertex_colors)
        normals.append(part.vertex_normals)
        offset += len(part.vertices)
    mesh = trimesh.Trimesh(np.vstack(vertices), np.vstack(faces), process=False,
                           vertex_colors=np.vstack(colours))
    mesh.vertex_normals = np.vstack(normals)
    return mesh


def build(name: str) -> trimesh.Trimesh:
    """The mesh of one bundled file, in the file's own frame, coloured."""
    (x0, x1), (y0, y1), _ = MESH_BOUNDS[name]
    half = (x1 - x0) / 2
    shapes: dict[str, Callable[[], trimesh.Trimesh]] = {
        "round-finger-8.glb": lambda: segment(y0, y1, half, tip=False),
        "round-finger-5.glb": lambda: segment(y0, y1, half, tip=False),
        "round-tip.glb": lambda: segment(y0, y1, half, tip=True),
        "round-palm.glb": lambda: slab(palm_outline(None), 0.15),
        "anthro-palm.glb": lambda: slab(palm_outline((0.7071, -0.7071, 0.63)), 0.15),
        "anthro-thumb.glb": thumb,
    }
    return painted(fit(shapes[name](), name))


def outputs() -> dict[Path, bytes]:
    """What this generator writes: every bundled mesh as GLB."""
    return {GLTF_DIR / name: trimesh.exchange.gltf.export_glb(trimesh.Scene(build(name)),
                                                             include_normals=True)
            for name in MESH_BOUNDS}
