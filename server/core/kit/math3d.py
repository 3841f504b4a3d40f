"""Rigid transforms: vectors, unit quaternions and three.js-style Euler angles.

Quaternions are ``(x, y, z, w)`` tuples, the order three.js and PyBullet share, so
values cross to the viewer and to the physics backend without reshuffling.
"""

from __future__ import annotations

import math
from typing import Sequence

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]
Pose = tuple[Vec3, Quat]

IDENTITY: Quat = (0.0, 0.0, 0.0, 1.0)
ORIGIN: Vec3 = (0.0, 0.0, 0.0)
EULER_ORDERS: tuple[str, ...] = ("XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX")
AXES: dict[str, Vec3] = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


Axis = str | Vec3  # a principal axis by name ('x', 'y', 'z') or a unit vector


def unit_axis(axis: Axis) -> Vec3:
    """The unit vector of an axis given by name or as a unit vector."""
    return AXES[axis.lower()] if isinstance(axis, str) else axis


def axis_angle(axis: Axis, angle: float) -> Quat:
    """Rotation by ``angle`` radians about the named principal axis 'x', 'y' or 'z', or
    about a unit vector."""
    ax, ay, az = unit_axis(axis)
    s = math.sin(angle / 2)
    return (ax * s, ay * s, az * s, math.cos(angle / 2))


def multiply(a: Quat, b: Quat) -> Quat:
    """Hamilton product ``a·b``: rotate by ``b`` first, then by ``a``."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def euler_to_quat(x: float, y: float, z: float, order: str = "XYZ") -> Quat:
    """Quaternion of three.js ``Euler(x, y, z, order)``.

    The order names intrinsic rotations: matrix = R1·R2·R3 for order "123".
    """
    if order not in EULER_ORDERS:
        raise ValueError(f"unknown Euler order {order!r}")
    angles = {"X": x, "Y": y, "Z": z}
    q = IDENTITY
    for axis in order:
        q = multiply(q, axis_angle(axis, angles[axis]))
    return q


def rotate(q: Quat, v: Sequence[float]) -> Vec3:
    """The vector ``v`` rotated by the unit quaternion ``q``."""
    qx, qy, qz, qw = q
    vx, vy, vz = v
    # t = 2·(q_vec × v); v' = v + w·t + q_vec × t
    tx = 2 * (qy * vz - qz * vy)
    ty = 2 * (qz * vx - qx * vz)
    tz = 2 * (qx * vy - qy * vx)
    return (
        vx + qw * tx + (qy * tz - qz * ty),
        vy + qw * ty + (qz * tx - qx * tz),
        vz + qw * tz + (qx * ty - qy * tx),
    )


def between(a: Pose, b: Pose, f: float) -> Pose:
    """The pose a fraction ``f`` of the way from ``a`` to ``b`` (positions straight, rotations
    along the shorter arc, normalised: near enough a slerp for the small turns of one tick);
    at ``f`` 1, ``b`` itself (normalised, its last bit could differ, and a pose put again
    where it was would look moved)."""
    if f >= 1.0:
        return b
    (ap, aq), (bp, bq) = a, b
    if sum(x * y for x, y in zip(aq, bq)) < 0:
        bq = tuple(-x for x in bq)  # type: ignore[assignment]
    q = tuple(x + (y - x) * f for x, y in zip(aq, bq))
    norm = math.sqrt(sum(x * x for x in q)) or 1.0
    return (tuple(x + (y - x) * f for x, y in zip(ap, bp)),  # type: ignore[return-value]
            tuple(x / norm for x in q))


def compose(parent: Pose, local: Pose) -> Pose:
    """World pose of a child whose pose relative to ``parent`` is ``local``."""
    (pp, pq), (lp, lq) = parent, local
    rx, ry, rz = rotate(pq, lp)
    return (pp[0] + rx, pp[1] + ry, pp[2] + rz), multiply(pq, lq)


def to_matrix(q: Quat) -> tuple[Vec3, Vec3, Vec3]:
    """Row-major 3×3 rotation matrix of a unit quaternion."""
    x, y, z, w = q
    return (
        (1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
        (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
        (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)),
    )


def matrix_to_euler_xyz(m: Sequence[Sequence[float]]) -> Vec3:
    """Euler angles in order 'XYZ' of a rotation matrix (three.js ``setFromRotationMatrix``)."""
    m13 = max(-1.0, min(1.0, m[0][2]))
    y = math.asin(m13)
    if abs(m13) < 0.9999999:
        return (math.atan2(-m[1][2], m[2][2]), y, math.atan2(-m[0][1], m[0][0]))
    return (math.atan2(m[2][1], m[1][1]), y, 0.0)
