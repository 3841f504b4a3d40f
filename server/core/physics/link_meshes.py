"""What an imported link looks like and what it collides as, from its file's elements.

A link's visual elements (boxes, spheres, cylinders, capsules, meshes in STL, OBJ, DAE,
GLB, PLY), each placed in the link's frame and painted its colour, become one GLB with
vertex colours: the file viewers draw, kept as an upload (one file a link, cached by every
browser like any mesh). Its collision elements become one convex envelope, as a mesh
part's (:func:`.envelopes.hull_envelope`): contacts here measure every shape by its hull.
Meshes are read with trimesh; what they refer to (an OBJ's materials, a DAE's textures)
resolves inside the upload only (:class:`ArchiveResolver`).
"""

from __future__ import annotations

import io
import posixpath
from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from ..kit.errors import BadAsset, LimitExceeded
from ..kit.limits import MAX_SIZE, Limits
from ..kit.math3d import Vec3
from .envelopes import hull_envelope
from .robot_archive import RobotArchive

MESH_TYPES = ("stl", "obj", "dae", "glb", "gltf", "ply")
DEFAULT_RGBA = (0.75, 0.75, 0.78, 1.0)  # a link the file gives no colour
ROUND_SECTIONS = 24                     # around a cylinder or capsule drawn or enveloped


@dataclass(frozen=True)
class Element:
    """One visual or collision element: a mesh in its own frame, where it sits in the
    link (4×4), and its colour (RGBA in 0…1; None: the mesh's own, else the default)."""

    mesh: Any                      # trimesh.Trimesh
    placement: np.ndarray
    rgba: Sequence[float] | None = None


class TriangleBudget:
    """The triangles of a robot's meshes so far, refused past ``robotTriangles``."""

    def __init__(self, limits: Limits) -> None:
        self.limits = limits
        self.triangles = 0

    def count(self, triangles: int, what: str) -> None:
        """Add ``triangles`` (of ``what``) to the robot's total."""
        self.triangles += triangles
        if self.triangles > self.limits.robot_triangles:
            raise LimitExceeded(f"the robot's meshes come to more than {self.limits.robot_triangles} "
                                f"triangles (at {what})", limit="robotTriangles",
                                value=self.limits.robot_triangles)


class MeshReader:
    """Reads an upload's mesh files (each once), within the robot's triangle limit."""

    def __init__(self, archive: RobotArchive, limits: Limits) -> None:
        self.archive = archive
        self.budget = TriangleBudget(limits)
        self._read: dict[str, Any] = {}

    def mesh(self, reference: str, scale: Sequence[float] | float | None = None) -> Any:
        """The mesh a description's reference names, scaled as the description says."""
        path, data = self.archive.resolve(reference)
        if path not in self._read:
            self._read[path] = self._load(path, data)
        mesh = self._read[path].copy()
        if scale is not None:
            mesh.apply_scale(np.broadcast_to(np.asarray(scale, dtype=float), 3))
        return mesh

    def _load(self, path: str, data: bytes) -> Any:
        import trimesh

        kind = posixpath.splitext(path)[1].lower().lstrip(".")
        if kind not in MESH_TYPES:
            raise BadAsset(f"mesh {path}: the formats read are {', '.join(MESH_TYPES)}")
        try:
            loaded = trimesh.load(io.BytesIO(data), file_type=kind, force="mesh", process=False,
                                  resolver=ArchiveResolver(self.archive, posixpath.dirname(path)))
        except (BadAsset, LimitExceeded):
            raise
        except Exception as error:  # trimesh and its loaders raise many kinds for bad files
            raise BadAsset(f"mesh {path} does not read as {kind.upper()}: {str(error)[:160]}") from None
        if not hasattr(loaded, "faces") or len(loaded.faces) == 0:
            raise BadAsset(f"mesh {path} holds no triangles")
        if not np.isfinite(loaded.vertices).all() or np.abs(loaded.vertices).max() > MAX_SIZE * 1000:
            raise BadAsset(f"mesh {path}: its coordinates must be finite and not huge")
        self.budget.count(len(loaded.faces), path)
        return loaded


class ArchiveResolver:
    """trimesh's resolver for what a mesh file refers to: members of the upload only."""

    def __init__(self, archive: RobotArchive, folder: str) -> None:
        self.archive, self.folder = archive, folder

    def get(self, name: str) -> bytes:
        reference = posixpath.relpath(posixpath.join(self.folder, name), self.archive.folder or ".")
        return self.archive.resolve(reference)[1]

    def __getitem__(self, name: str) -> bytes:
        # how trimesh's OBJ reader asks for a material file (without it an OBJ's colours
        # were silently dropped: its Resolver base class maps this to get())
        return self.get(name)

    def namespaced(self, namespace: str) -> ArchiveResolver:
        return ArchiveResolver(self.archive, posixpath.join(self.folder, namespace))

    def keys(self) -> list[str]:
        return list(self.archive.files)


def box(size: Sequence[float]) -> Any:
    import trimesh
    return trimesh.creation.box(extents=[max(float(s), 1e-6) for s in size])


def sphere(radius: float) -> Any:
    import trimesh
    return trimesh.creation.icosphere(subdivisions=2, radius=max(float(radius), 1e-6))


def cylinder(radius: float, length: float) -> Any:
    """A cylinder along Z centred at its middle (URDF's and MJCF's)."""
    import trimesh
    return trimesh.creation.cylinder(radius=max(float(radius), 1e-6), height=max(float(length), 1e-6),
                                     sections=ROUND_SECTIONS)


def capsule(radius: float, length: float) -> Any:
    """A capsule along Z: ``length`` between its hemispheres' centres."""
    import trimesh
    return trimesh.creation.capsule(height=max(float(length), 0.0), radius=max(float(radius), 1e-6),
                                    count=[ROUND_SECTIONS, ROUND_SECTIONS // 2])


def drawn(elements: Sequence[Element], link: str, limits: Limits) -> bytes | None:
    """One GLB of the visual elements, placed and painted (None: the link shows nothing)."""
    import trimesh

    if not elements:
        return None
    pieces = []
    for element in elements:
        mesh = element.mesh.copy()
        mesh.apply_transform(element.placement)
        colours = _colours(mesh, element.rgba)
        mesh.visual = trimesh.visual.ColorVisuals(mesh, vertex_colors=colours)
        pieces.append(mesh)
    whole = trimesh.util.concatenate(pieces) if len(pieces) > 1 else pieces[0]
    if len(whole.faces) > limits.asset_triangles:
        raise LimitExceeded(f"link {link!r} would be drawn with {len(whole.faces)} triangles; a "
                            f"mesh holds at most {limits.asset_triangles}", limit="assetTriangles",
                            value=limits.asset_triangles)
    return whole.export(file_type="glb")


def _colours(mesh: Any, rgba: Sequence[float] | None) -> np.ndarray:
    """Vertex colours (0…255): the element's colour, else the mesh's own, else the default."""
    count = len(mesh.vertices)
    if rgba is None:
        try:
            own = _own_colours(mesh)
            if len(own) == count:
                return np.asarray(own, dtype=np.uint8)
        except Exception:  # a mesh without usable colours: the default below
            pass
        rgba = DEFAULT_RGBA
    return np.tile(np.round(np.clip(np.asarray(rgba, dtype=float), 0, 1) * 255).astype(np.uint8),
                   (count, 1))


def _own_colours(mesh: Any) -> np.ndarray:
    """A mesh's colours by vertex: a material's colour, a texture's mean, the file's own."""
    visual = mesh.visual
    material = getattr(visual, "material", None)
    if material is not None and getattr(visual, "uv", None) is None:
        # a material without texture coordinates (an OBJ's Kd alone): trimesh's to_color()
        # then paints it grey, not in the material's colour
        return np.tile(np.asarray(material.main_color, dtype=np.uint8), (len(mesh.vertices), 1))
    colours = visual.to_color()
    colours.mesh = mesh  # (made apart from the mesh, it counts no vertices)
    return colours.vertex_colors


def envelope(elements: Sequence[Element]) -> tuple[Vec3, ...] | None:
    """The collision envelope of the elements in the link's frame (None: none collides)."""
    if not elements:
        return None
    points = [np.asarray(e.mesh.vertices, dtype=float) @ e.placement[:3, :3].T + e.placement[:3, 3]
              for e in elements]
    return hull_envelope(np.vstack(points))
