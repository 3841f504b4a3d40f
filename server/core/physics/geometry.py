"""SceneMesh geometry as data: what a page's mesh becomes on the server, and scaled shapes.

A :class:`~server.core.model.page_meshes.SceneMesh` is given its geometry in one of five forms (the
``geometry`` argument kind), as a three.js page has it:

``{"kind": "box", "size": [x, y, z]}`` · ``{"kind": "sphere", "radius": r}`` ·
``{"kind": "cylinder", "radiusTop": a, "radiusBottom": b, "height": h, "segments": n}``
(three.js ``CylinderGeometry``; a cone has one radius 0) ·
``{"kind": "hull", "vertices": [x0, y0, z0, x1, …]}`` (the convex hull of any geometry's
points) · ``{"kind": "triangles", "vertices": [x0, y0, z0, …], "indices": [i0, i1, i2, …]}``
(any geometry as its triangles, counter-clockwise seen from outside; without
``indices`` every three vertices make one).

A hull is kept as its corner points (kind ``convex``, as the edged parts), the others as
given. Rays meet each exactly; contacts measure a triangle mesh by its convex hull.
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

from ..kit.errors import BadArguments, OutOfRange, WrongType, show
from ..kit.limits import MAX_COORDINATE, MAX_SIZE, MIN_SIZE
from .hulls import convex_hull

MIN_SCALE = 1e-6  # a shape scaled to nothing keeps this much of its size (Bullet needs some)
MAX_SEGMENTS = 256
_ELLIPSOID_STEPS = 12  # rings and half-segments of the hull a stretched sphere becomes
_FIELDS = {"box": {"size"}, "sphere": {"radius"},
           "cylinder": {"radiusTop", "radiusBottom", "height", "segments"},
           "hull": {"vertices"}, "triangles": {"vertices", "indices"}}


def check(value: Any, label: str, max_vertices: int, max_triangles: int) -> dict[str, Any]:
    """A shape geometry from its wire form, checked; what the SceneMesh keeps and describes."""
    if not isinstance(value, dict) or value.get("kind") not in _FIELDS:
        raise WrongType(f"{label}: expected a geometry {{\"kind\": one of "
                        f"{', '.join(_FIELDS)}, …}}, got {show(value)}")
    kind = value["kind"]
    unknown = set(value) - _FIELDS[kind] - {"kind"}
    if unknown:
        raise BadArguments(f"{label}: a {kind} geometry has no field {', '.join(sorted(unknown))}")
    missing = _FIELDS[kind] - set(value) - {"indices"}
    if missing:
        raise BadArguments(f"{label}: a {kind} geometry needs {', '.join(sorted(missing))}")
    if kind == "box":
        return {"kind": "box", "size": _sizes(value["size"], f"{label} size")}
    if kind == "sphere":
        return {"kind": "sphere", "radius": _size(value["radius"], f"{label} radius")}
    if kind == "cylinder":
        return _cylinder(value, label)
    vertices = _vertices(value["vertices"], f"{label} vertices", max_vertices)
    if kind == "hull":
        corners = convex_hull(vertices)
        # the hull's own points: a flat set was thickened by a hair (hulls.solid)
        return {"kind": "convex", "points": corners.points[corners.vertices].tolist()}
    indices = _indices(value.get("indices"), len(vertices), f"{label} indices", max_triangles)
    return {"kind": "triangles", "vertices": vertices.ravel().tolist(), "indices": indices}


def _number(value: Any, label: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise WrongType(f"{label}: expected a finite number, got {show(value)}")
    return float(value)


def _size(value: Any, label: str, low: float = MIN_SIZE) -> float:
    number = _number(value, label)
    if not low <= number <= MAX_SIZE:
        raise OutOfRange(f"{label}: lies between {low:g} and {MAX_SIZE:g} m, got {number:g}")
    return number


def _sizes(value: Any, label: str) -> list[float]:
    if not isinstance(value, list) or len(value) != 3:
        raise WrongType(f"{label}: expected [x, y, z], got {show(value)}")
    return [_size(v, label) for v in value]


def _cylinder(value: dict[str, Any], label: str) -> dict[str, Any]:
    top = _size(value["radiusTop"], f"{label} radiusTop", 0.0)
    bottom = _size(value["radiusBottom"], f"{label} radiusBottom", 0.0)
    if max(top, bottom) < MIN_SIZE:
        raise OutOfRange(f"{label}: a cylinder needs a radius of at least {MIN_SIZE:g} m")
    segments = value["segments"]
    if isinstance(segments, bool) or not isinstance(segments, int) or \
            not 3 <= segments <= MAX_SEGMENTS:
        raise OutOfRange(f"{label} segments: a whole number from 3 to {MAX_SEGMENTS}, "
                         f"got {show(segments)}")
    return {"kind": "cylinder", "radiusTop": top, "radiusBottom": bottom,
            "height": _size(value["height"], f"{label} height"), "segments": segments}


def _flat_numbers(value: Any, label: str, limit: int) -> np.ndarray:
    expected = f"{label}: expected a flat list of at most {limit} numbers"
    if not isinstance(value, list):
        raise WrongType(f"{expected}, got {show(value)}")
    if len(value) > limit:
        raise OutOfRange(f"{expected}, got {len(value)} items")
    if not all(type(v) in (int, float) for v in value):  # no booleans, strings or lists
        bad = next(v for v in value if type(v) not in (int, float))
        raise WrongType(f"{label}: expected numbers, got {show(bad)}")
    array = np.asarray(value, dtype=float)
    if not np.isfinite(array).all():
        raise OutOfRange(f"{label}: every number must be finite")
    return array


def _vertices(value: Any, label: str, max_vertices: int) -> np.ndarray:
    flat = _flat_numbers(value, label, 3 * max_vertices)
    if len(flat) % 3 or len(flat) < 9:
        raise BadArguments(f"{label}: x, y, z of at least 3 vertices, got {len(flat)} numbers")
    if np.abs(flat).max() > MAX_COORDINATE:
        raise OutOfRange(f"{label}: coordinates lie within ±{MAX_COORDINATE:g} m")
    return flat.reshape(-1, 3)


def _indices(value: Any, vertices: int, label: str, max_triangles: int) -> list[int]:
    if value is None:
        if vertices % 3:
            raise BadArguments(f"{label}: without indices the vertices come in threes, "
                               f"got {vertices}")
        value = list(range(vertices))
    numbers = _flat_numbers(value, label, 3 * max_triangles)
    if not (numbers == np.floor(numbers)).all():
        raise WrongType(f"{label}: expected whole numbers")
    flat = numbers.astype(np.int64)
    if len(flat) % 3 or not len(flat):
        raise BadArguments(f"{label}: three per triangle, got {len(flat)}")
    if flat.min() < 0 or flat.max() >= vertices:
        raise OutOfRange(f"{label}: each index lies from 0 to {vertices - 1}")
    return flat.tolist()


# --- what rays and contacts use ---------------------------------------------------------

def cylinder_points(geometry: dict[str, Any]) -> list[list[float]]:
    """The corners of a cylinder drawn as three.js draws it (flat sides, +Y up, centred)."""
    n, half = geometry["segments"], geometry["height"] / 2
    points = []
    for radius, y in ((geometry["radiusTop"], half), (geometry["radiusBottom"], -half)):
        # three.js starts its segments at +Z and turns towards +X
        points += [[radius * math.sin(2 * math.pi * k / n), y, radius * math.cos(2 * math.pi * k / n)]
                   for k in range(n)] if radius else [[0.0, y, 0.0]]
    return points


def triangle_arrays(geometry: dict[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (n, 3) and triangles (m, 3) of a ``triangles`` geometry."""
    return (np.asarray(geometry["vertices"], float).reshape(-1, 3),
            np.asarray(geometry["indices"], np.int64).reshape(-1, 3))


def scaled(geometry: dict[str, Any], scale: Sequence[float]) -> dict[str, Any]:
    """A physical geometry stretched by a (world) scale; the kinds stay those rays and
    physics know (a stretched sphere and a cylinder become hulls)."""
    s = np.maximum(np.asarray(scale, float), MIN_SCALE)
    kind = geometry["kind"]
    if kind == "sphere" and s.min() == s.max():
        return {**geometry, "radius": geometry["radius"] * float(s[0])}
    if kind == "box":
        return {**geometry, "size": (np.asarray(geometry["size"]) * s).tolist()}
    if kind == "triangles":
        vertices = np.asarray(geometry["vertices"], float).reshape(-1, 3) * s
        return {**geometry, "vertices": vertices.ravel().tolist()}
    if kind == "mesh":  # a file's triangles for rays, its envelope for contacts
        return {**geometry, "scale": (np.asarray(geometry.get("scale", (1.0, 1.0, 1.0))) * s).tolist(),
                "points": (np.asarray(geometry["points"]) * s).tolist()}
    look = {key: geometry[key] for key in ("color", "edges") if key in geometry}
    return {"kind": "convex", "points": (np.asarray(solid_points(geometry)) * s).tolist(), **look}


def solid_points(geometry: dict[str, Any]) -> list[list[float]]:
    """Points whose convex hull is a sphere (as a fine polyhedron), cylinder or hull."""
    kind = geometry["kind"]
    if kind == "cylinder":
        return cylinder_points(geometry)
    if kind == "sphere":
        r, n = geometry["radius"], _ELLIPSOID_STEPS
        return [[r * math.sin(math.pi * i / n) * math.cos(math.pi * j / n), r * math.cos(math.pi * i / n),
                 r * math.sin(math.pi * i / n) * math.sin(math.pi * j / n)]
                for i in range(n + 1) for j in range(2 * n)]
    if kind == "triangles":
        return triangle_arrays(geometry)[0].tolist()
    return geometry["points"]


def volume(geometry: dict[str, Any]) -> float:
    """The volume a physical geometry encloses (m³): exact for spheres and boxes, the
    convex hull's for the rest (what contacts and dynamics measure them by)."""
    kind = geometry["kind"]
    if kind == "sphere":
        return 4 / 3 * math.pi * geometry["radius"] ** 3
    if kind == "box":
        return float(np.prod(geometry["size"]))
    return float(convex_hull(solid_points(geometry)).volume)


def centroid(geometry: dict[str, Any]) -> tuple[float, float, float]:
    """The centre of the volume a physical geometry encloses, in its own frame (that of
    its convex hull for the kinds measured by their hulls)."""
    if geometry["kind"] in ("sphere", "box"):
        return (0.0, 0.0, 0.0)
    hull = convex_hull(solid_points(geometry))
    corners = hull.points[hull.simplices]  # (faces, 3, 3)
    inside = hull.points[hull.vertices].mean(axis=0)
    # the hull as tetrahedra from a point inside: their volumes weigh their centres
    a, b, c = corners[:, 0] - inside, corners[:, 1] - inside, corners[:, 2] - inside
    weights = np.abs(np.einsum("ij,ij->i", a, np.cross(b, c)))
    centres = inside + (corners.sum(axis=1) - 3 * inside) / 4
    return tuple(float(x) for x in (weights @ centres) / weights.sum())  # type: ignore[return-value]
