"""Pictures of a physics world, drawn by PyBullet's own software renderer (TinyRenderer: no
GPU, no display), as a learning environment's ``rgb_array`` shows them: from a second
PyBullet world in the same process holding a visual shape for each part, in its colour,
put where the physics world has the part each time a picture is taken. Y is up, as in the
scene.

Why a second world: PyBullet's software renderer draws a body's collision shapes when it
has no visual ones, but not those made from points (every mesh, hull and cylinder here),
so a hand would be missing from its own picture; and visual shapes in the physics world
would cost every scene memory for pictures few take. Built on the first picture, a
part's shape is kept while its geometry stays the same.
"""

from __future__ import annotations

from typing import Any, Iterator

import numpy as np

from ..kit.errors import OutOfRange
from ..kit.math3d import Pose, Vec3
from .bullet import shape_arguments
from .engine import PhysicsWorld
from .urdf_file import hull_mesh, rgba

SIZES = (16, 1024)  # pixels: the smallest and largest side of a picture
FIELD_OF_VIEW = 50.0  # degrees, vertical: the viewer's camera's


class PictureWorld:
    """The visual twin of a :class:`PhysicsWorld` (see the module)."""

    def __init__(self, pybullet: Any) -> None:
        self.p = pybullet
        self.client = pybullet.connect(pybullet.DIRECT)
        self._bodies: dict[str, tuple[int, int]] = {}  # part -> (its geometry's id(), body)

    def draw(self, world: PhysicsWorld, eye: Vec3, target: Vec3, width: int, height: int) -> np.ndarray:
        """``world`` seen from ``eye`` looking at ``target``: rows of RGB pixels."""
        check_size(width, height)
        seen = set()
        for key, geometry, pose in parts(world):
            body = self._body(key, geometry)
            self.p.resetBasePositionAndOrientation(body, pose[0], pose[1], physicsClientId=self.client)
            seen.add(key)
        for key in set(self._bodies) - seen:
            self.p.removeBody(self._bodies.pop(key)[1], physicsClientId=self.client)
        return render(self.p, self.client, eye, target, width, height)

    def _body(self, key: str, geometry: dict[str, Any]) -> int:
        kept = self._bodies.get(key)
        if kept is not None and kept[0] == id(geometry):
            return kept[1]
        if kept is not None:
            self.p.removeBody(kept[1], physicsClientId=self.client)
        shape = self.p.createVisualShape(physicsClientId=self.client, rgbaColor=rgba(geometry.get("color")),
                                         **visual_arguments(self.p, geometry))
        body = self.p.createMultiBody(0, -1, shape, physicsClientId=self.client)
        self._bodies[key] = (id(geometry), body)
        return body  # type: ignore[no-any-return]

    def close(self) -> None:
        self.p.disconnect(physicsClientId=self.client)


def parts(world: PhysicsWorld) -> Iterator[tuple[str, dict[str, Any], Pose]]:
    """Every part of ``world`` with a shape: its id, geometry and world pose."""
    for root in world.roots():
        tree = world.tree(root)
        if tree is None:
            continue
        geometries = {link.part: link.geometry for link in tree.links}
        geometries[tree.base_part] = tree.base_geometry
        for key, pose in zip(*world.part_poses(root)):
            if geometries.get(key) is not None:
                yield key, geometries[key], pose


def visual_arguments(pybullet: Any, geometry: dict[str, Any]) -> dict[str, Any]:
    """``createVisualShape`` arguments: a sphere or box as Bullet collides with it, anything
    else as the triangles of the convex hull it collides with."""
    if geometry["kind"] in ("sphere", "box"):
        return shape_arguments(geometry)
    hull = hull_mesh(geometry)  # trimesh's: its faces turned outwards (the renderer culls backs)
    return {"shapeType": pybullet.GEOM_MESH, "vertices": hull.vertices.tolist(),
            "indices": hull.faces.ravel().tolist()}


def check_size(width: int, height: int) -> None:
    """Refuse a picture's size outside :data:`SIZES`."""
    for name, value in (("width", width), ("height", height)):
        if not SIZES[0] <= value <= SIZES[1]:
            raise OutOfRange(f"a picture's {name} is {SIZES[0]}-{SIZES[1]} pixels, not {value}",
                             argument=name)


def render(pybullet: Any, client: int, eye: Vec3, target: Vec3, width: int,
           height: int) -> np.ndarray:
    """PyBullet's world ``client`` seen from ``eye`` looking at ``target`` (scene units):
    ``height`` rows of ``width`` RGB pixels (uint8)."""
    distance = float(np.linalg.norm(np.subtract(eye, target))) or 1.0
    view = pybullet.computeViewMatrix(list(eye), list(target), [0, 1, 0])
    projection = pybullet.computeProjectionMatrixFOV(FIELD_OF_VIEW, width / height,
                                                     distance / 100, distance * 100)
    _, _, pixels, _, _ = pybullet.getCameraImage(width, height, view, projection,
                                                 renderer=pybullet.ER_TINY_RENDERER,
                                                 physicsClientId=client)
    return np.asarray(pixels, dtype=np.uint8).reshape(height, width, 4)[:, :, :3]
