"""An uploaded robot (URDF or MJCF) read and kept: its links' meshes and its description as uploads.

Run where uploads are checked (the server's checking process): a description and its
meshes are parsed there, never in a scene's process or the event loop. The description
is kept as ``<hash>.robot`` by the server's :class:`Uploads` (its upload folder:
:mod:`server.web.storage.upload_folder`), which ``ImportedRobot`` takes; the answer says
what the file holds.
"""

from __future__ import annotations

from typing import Any

from ..kit.limits import Limits
from ..kit.numbers import encode_numbers
from .assets import Uploads
from .mjcf_reading import read_mjcf
from .robot_archive import open_archive
from .urdf_reading import read_urdf


def store_robot_upload(uploads: Uploads, data: bytes, file: str | None,
                       limits: Limits) -> dict[str, Any]:
    """Read an upload (a zip, or a bare URDF or MJCF file) and keep what it makes."""
    archive = open_archive(data, file, limits)
    reader = read_urdf if archive.format == "urdf" else read_mjcf
    robot = reader(archive, limits, lambda glb: uploads.store(glb, limits)["name"])
    kept = uploads.store_robot(robot, limits)
    followers = {c.follower: c for c in robot.couplings}
    return encode_numbers({
        "file": kept["name"], "name": robot.name, "source": robot.source,
        "description": archive.description, "links": len(robot.links),
        "motors": [{"name": joint.name, "min": joint.lower, "max": joint.upper,
                    "follows": None if joint.name not in followers else
                    [followers[joint.name].leader, followers[joint.name].ratio,
                     followers[joint.name].offset]}
                   for joint in robot.motors()]})
