"""A robot's look as one GLB file: what takes a hand to Blender or any web page.

A robot's file is a node hierarchy (:func:`robot_glb_bytes`): its root node where the
robot is (+Y up, as glTF wants), and a node for each link of the compiled tree
(:mod:`.articulation`), named as the URDF names it, below its parent's, with its local
transform (the joint's place turned by the motor's angle now); a link's part is that
node's mesh. Parts are coloured as a viewer colours them (glTF's linear components):
spheres, boxes and hulls by a material of the part's colour; a mesh file's part by the
file's own vertex colours after its ``recolor`` calls; page triangles as drawn. trimesh
writes the file (binary glTF 2.0); the black edges a viewer draws on the edged parts are
not in it. :func:`glb_bytes` draws loose parts, each at its pose (recordings' models).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from ..kit.math3d import Pose, to_matrix
from .assets import AssetLibrary, placed
from .geometry import solid_points, triangle_arrays
from .urdf_file import rgba

if TYPE_CHECKING:  # imported where used: the web process imports this module for its
    import trimesh  # routes, and trimesh with scipy is half a second of every server's start

SPHERE_SEGMENTS = 32  # around and from pole to pole: a multiple of 4 puts corners on the axes
ROUGHNESS = 0.8  # a matte surface, as the viewer's Phong material draws parts


@dataclass(frozen=True)
class DrawnPart:
    """A part to draw: its id, geometry (as compiled), world pose and recolours."""

    id: str
    geometry: dict[str, Any]
    pose: Pose
    recolors: Sequence[Sequence[Any]] = ()


def glb_bytes(parts: Sequence[DrawnPart], assets: AssetLibrary) -> bytes:
    """The binary glTF of ``parts``, each a mesh at its pose (none: a valid file that
    draws nothing)."""
    import trimesh
    from trimesh.exchange.gltf import export_glb

    scene = trimesh.Scene()
    for part in parts:
        scene.add_geometry(part_mesh(part, assets), node_name=part.id, geom_name=part.id,
                           transform=_matrix(part.pose))
    # the GLB writer itself: trimesh's generic export refuses a scene without meshes, and
    # a robot with no parts yet is a file with its root node and nothing drawn
    return export_glb(scene)


@dataclass(frozen=True)
class DrawnLink:
    """A node of a robot's file: its name, its parent's index among the links (-1: the
    robot's root node), its pose in its parent's frame, and the part it carries (the part's
    ``pose``: where it sits in the link's frame)."""

    name: str
    parent: int
    pose: Pose
    part: DrawnPart | None = None


def robot_glb_bytes(name: str, pose: Pose, links: Sequence[DrawnLink], assets: AssetLibrary) -> bytes:
    """The binary glTF of a robot: a root node ``name`` at ``pose`` and its links below it."""
    import trimesh
    from trimesh.exchange.gltf import export_glb

    scene = trimesh.Scene()
    scene.graph.update(frame_from=scene.graph.base_frame, frame_to=name, matrix=_matrix(pose))
    for link in links:
        parent = name if link.parent < 0 else links[link.parent].name
        if link.part is None:
            scene.graph.update(frame_from=parent, frame_to=link.name, matrix=_matrix(link.pose))
            continue
        mesh = part_mesh(link.part, assets)
        mesh.apply_transform(_matrix(link.part.pose))  # the part's place in the link, baked in
        scene.add_geometry(mesh, node_name=link.name, geom_name=link.part.id,
                           parent_node_name=parent, transform=_matrix(link.pose))
    return export_glb(scene)


def part_mesh(part: DrawnPart, assets: AssetLibrary) -> trimesh.Trimesh:
    """The coloured mesh of one part, in its own frame."""
    import trimesh
    from trimesh.visual.material import PBRMaterial

    geometry = part.geometry
    kind = geometry["kind"]
    if kind == "mesh":
        return _file_mesh(geometry, part.recolors, assets)
    if kind == "sphere":
        mesh = trimesh.creation.uv_sphere(geometry["radius"], count=(SPHERE_SEGMENTS, SPHERE_SEGMENTS))
    elif kind == "box":
        mesh = trimesh.creation.box(extents=geometry["size"])
    elif kind == "triangles":
        mesh = trimesh.Trimesh(*triangle_arrays(geometry), process=False)
    else:  # hulls, cylinders (three.js draws a cylinder as the hull of its corners)
        mesh = trimesh.convex.convex_hull(np.asarray(solid_points(geometry), float))
    colour = geometry.get("color")
    mesh.visual = trimesh.visual.TextureVisuals(material=PBRMaterial(
        name=str(colour if colour is not None else "default"), baseColorFactor=_rgba8(linear(colour)),
        metallicFactor=0.0, roughnessFactor=ROUGHNESS))
    return mesh


def _file_mesh(geometry: dict[str, Any], recolors: Sequence[Sequence[Any]],
               assets: AssetLibrary) -> trimesh.Trimesh:
    """A mesh file's triangles and vertex colours, placed as the part places them."""
    import trimesh

    assets.mesh(geometry["url"])  # the file checked (and refused) as a part's file is
    path, _ = assets.locate(geometry["url"])
    vertices, faces, colors = _coloured(str(path), path.stat().st_mtime_ns)
    mesh = trimesh.Trimesh(*placed(geometry, vertices, faces), process=False)
    if colors is not None:
        mesh.visual = trimesh.visual.ColorVisuals(mesh, vertex_colors=_rgba8(_recolored(colors, recolors)))
    return mesh


@lru_cache(maxsize=16)
def _coloured(path: str, version: int) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """A mesh file's vertices, triangles and vertex colours (0…1, None: it has none), read
    once per version of the file: a recording's scene update draws a hand's fifteen
    segments from three files."""
    import trimesh

    mesh = trimesh.load(path, force="mesh", process=False)
    colors = np.asarray(mesh.visual.vertex_colors, float)[:, :4] / 255 \
        if mesh.visual.kind == "vertex" else None
    return np.asarray(mesh.vertices), np.asarray(mesh.faces), colors


def _recolored(colors: np.ndarray, recolors: Sequence[Sequence[Any]]) -> np.ndarray:
    """The viewer's recolor: each vertex within eps of ``from`` (every component) takes
    ``to``, in the order they were called; [r, g, b] are the file's own components."""
    out = colors.copy()
    for source, target, eps in recolors:
        near = np.all(np.abs(out[:, :3] - linear(source)[:3]) <= eps, axis=1)
        out[near, :3] = linear(target)[:3]
    return out


def linear(color: Any) -> np.ndarray:
    """A part colour in glTF's (and three.js's) linear components: CSS colours are sRGB,
    [r, g, b] already linear (a mesh file's own, as recolor takes them)."""
    values = np.asarray(rgba(color))
    if isinstance(color, (list, tuple)):
        return values
    srgb = values[:3]
    values[:3] = np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)
    return values


def _rgba8(color: Sequence[float] | np.ndarray) -> np.ndarray:
    return np.clip(np.round(np.asarray(color) * 255), 0, 255).astype(np.uint8)


def _matrix(pose: Pose) -> np.ndarray:
    matrix = np.eye(4)
    matrix[:3, :3] = to_matrix(pose[1])
    matrix[:3, 3] = pose[0]
    return matrix
