"""An MJCF robot read into a :class:`~.robot_description.RobotDescription`, compiled by
MuJoCo's own library (includes, default classes, angle units, mesh centring).

The model is compiled from the upload's files alone: every file the XML names (includes,
meshes, textures, height fields, skins, and the ``meshdir``/``texturedir``/``assetdir``
they are found in) must be a plain relative path to a member of the upload, checked before
MuJoCo sees it (MuJoCo looks on the disk for a file it is not given). Then each body under
the world becomes a link in the frame of its first joint; hinge joints become motors and
slide joints sliders (a body with several gets a link for each), fixed bodies hold their
link; ``<equality><joint>`` and fixed tendons of two joints (held by an equality or driven
by an actuator) become couplings; ball and free joints are refused by name. Visual elements
are geoms of groups 0-2, collision elements geoms that collide (``contype``/``conaffinity``).
"""

from __future__ import annotations

import posixpath
from typing import Any, Iterable

import numpy as np

from ..kit.errors import BadAsset, Forbidden
from ..kit.limits import Limits
from ..kit.math3d import to_matrix
from . import link_meshes
from .link_meshes import Element, TriangleBudget
from .robot_archive import RobotArchive, inside_upload
from .robot_description import (Coupling, JointDescription, LinkDescription, RobotDescription,
                                checked, diagonal_in)
from .urdf_reading import Store, parse_xml

FILE_ELEMENTS = {"include": None, "mesh": "meshdir", "skin": "meshdir", "hfield": "meshdir",
                 "texture": "texturedir"}
TEXTURE_FILES = ("file", "fileright", "fileleft", "fileup", "filedown", "filefront", "fileback")
VISUAL_GROUPS = 3  # geoms of groups 0, 1, 2 are drawn (MuJoCo's viewer shows those by default)


def read_mjcf(archive: RobotArchive, limits: Limits, store: Store) -> RobotDescription:
    """The robot of the archive's MJCF model; each link's GLB kept by ``store``."""
    import mujoco

    files = _model_files(archive)
    main = archive.files[archive.description].decode(errors="replace")
    try:
        model = mujoco.MjModel.from_xml_string(main, files)
    except ValueError as error:
        raise BadAsset(f"MuJoCo does not compile the model: {str(error).strip()[:240]}") from None
    return checked(_Converter(model, limits, store).robot())


def _model_files(archive: RobotArchive) -> dict[str, bytes]:
    """The upload's files the model names (its includes, meshes, textures, height fields
    and skins), by their path in the upload, once each is known to be one of them.

    A path may climb out of the model's folder (``meshdir="../meshes"``) as long as it
    stays inside the upload. MuJoCo's file system looks a file up by its name alone (it
    drops the folders of the names it is given and asks for), so two different files of
    one name cannot both be given: they are refused, naming both."""
    dirs: dict[str, str] = {}
    named: list[tuple[str, str]] = []
    pending, seen = [archive.description], set()
    while pending:
        path = pending.pop()
        if path in seen:
            continue
        seen.add(path)
        root = parse_xml(archive.files[path], "MJCF")
        for compiler in root.iter("compiler"):
            for key in ("meshdir", "texturedir", "assetdir"):
                if compiler.get(key) is not None:
                    dirs[key] = _relative(compiler.get(key), key)
        for element in root.iter():
            if not isinstance(element.tag, str):
                continue
            names = [element.get(k) for k in TEXTURE_FILES] if element.tag == "texture" else [element.get("file")]
            for name in filter(None, names):
                if element.tag not in FILE_ELEMENTS:
                    raise BadAsset(f"<{element.tag} file={name!r}>: only includes, meshes, "
                                   f"textures, height fields and skins name files here")
                named.append((element.tag, _relative(name, "file")))
                if element.tag == "include":
                    pending.append(_named_path(archive, "include", name, dirs))
    return _by_name((_named_path(archive, tag, name, dirs) for tag, name in named), archive)


def _named_path(archive: RobotArchive, tag: str, name: str, dirs: dict[str, str]) -> str:
    """Where in the upload a file named by a ``<tag>`` is (its kind's folder first)."""
    kind = FILE_ELEMENTS[tag]
    base = "" if kind is None else dirs.get(kind, dirs.get("assetdir", ""))
    path = inside_upload(posixpath.join(archive.folder, base, name), name)
    if path not in archive.files:
        raise BadAsset(f"<{tag} file={name!r}>: {path!r} is not in the upload")
    return path


def _by_name(paths: Iterable[str], archive: RobotArchive) -> dict[str, bytes]:
    """The files at ``paths``, refused if two different ones share a name."""
    files: dict[str, bytes] = {}
    first: dict[str, str] = {}
    for path in paths:
        other = first.setdefault(posixpath.basename(path), path)
        if other != path and archive.files[other] != archive.files[path]:
            raise BadAsset(f"{other!r} and {path!r} are different files of one name: MuJoCo "
                           f"finds a model's files by their names alone; rename one")
        files[other] = archive.files[other]
    return files


def _relative(name: str, what: str) -> str:
    """A path the model names, refused unless it is plain and relative (where it leads is
    checked once it is joined to its folder)."""
    if "://" in name or name.startswith(("/", "~")) or "\\" in name or "\0" in name:
        raise Forbidden(f"{what} {name!r}: only relative paths inside the upload are read",
                        filename=name)
    normal = posixpath.normpath(name) if name else "."
    return "" if normal == "." else normal


class _Converter:
    """Walks a compiled model's bodies into links (see the module's docstring)."""

    def __init__(self, model: Any, limits: Limits, store: Store) -> None:
        import mujoco

        self.m, self.mj, self.limits, self.store = model, mujoco, limits, store
        self.links: list[LinkDescription] = []
        self.link_of: dict[int, int] = {}      # body id -> index of the link carrying it
        self.anchor: dict[int, np.ndarray] = {}  # body id -> its link frame's offset in the body
        self.budget = TriangleBudget(limits)

    def robot(self) -> RobotDescription:
        m = self.m
        roots = [b for b in range(1, m.nbody) if m.body_parentid[b] == 0]
        if len(roots) != 1:
            names = ", ".join(self._name(self.mj.mjtObj.mjOBJ_BODY, b) for b in roots[:5])
            raise BadAsset(f"an MJCF robot has one body under the world; this one has "
                           f"{len(roots)}: {names}")
        for body in range(1, m.nbody):  # MuJoCo numbers every parent before its children
            self._body(body)
        model_name = bytes(m.names[:m.names.index(b"\0")]).decode(errors="replace")
        return RobotDescription(model_name or self._name(self.mj.mjtObj.mjOBJ_BODY, roots[0]),
                                "mjcf", tuple(self.links), tuple(self._couplings()))

    def _name(self, kind: Any, index: int) -> str:
        return self.mj.mj_id2name(self.m, kind, index) or f"{kind.name[6:].lower()}{index}"

    def _body(self, body: int) -> None:
        """The links of a body: one in the frame of each of its joints (the last carries the
        body), or one fixed where the body is."""
        m, mj = self.m, self.mj
        parent = int(m.body_parentid[body])
        name = self._name(mj.mjtObj.mjOBJ_BODY, body)
        position = np.asarray(m.body_pos[body], dtype=float) - self.anchor.get(parent, np.zeros(3))
        w, x, y, z = m.body_quat[body]
        rotation = (float(x), float(y), float(z), float(w))
        joints = list(range(m.body_jntadr[body], m.body_jntadr[body] + m.body_jntnum[body]))
        holder = self.link_of.get(parent, -1)
        if parent == 0 and joints:  # a root that turns: on a base of its own, at the world's origin
            holder = self._link(body, "world", -1, None, np.zeros(3), carries=False)
        at = np.zeros(3)
        if not joints:
            fixed = None if parent == 0 else JointDescription(
                f"{name}_fixed", "fixed", (tuple(map(float, position)), rotation))  # type: ignore[arg-type]
            self._link(body, name, holder, fixed, at)
        for k, joint in enumerate(joints):
            anchor = np.asarray(m.jnt_pos[joint], dtype=float)
            origin = (position + _matrix(rotation) @ anchor, rotation) if k == 0 else \
                (anchor - at, (0.0, 0.0, 0.0, 1.0))  # joints of one body: one after another
            last = k == len(joints) - 1
            described = self._joint(joint, origin)
            holder = self._link(body, name if last else f"{name}_{described.name}", holder,
                                described, anchor, carries=last)
            at = anchor
        self.anchor[body] = at

    def _joint(self, joint: int, origin: tuple[np.ndarray, tuple[float, ...]]) -> JointDescription:
        m, mj = self.m, self.mj
        name = self._name(mj.mjtObj.mjOBJ_JOINT, joint)
        kind = int(m.jnt_type[joint])
        if kind not in (mj.mjtJoint.mjJNT_HINGE, mj.mjtJoint.mjJNT_SLIDE):
            raise BadAsset(f"joint {name!r} is {mj.mjtJoint(kind).name[6:].lower()}: only hinge "
                           f"and slide joints are taken (a hand's joints turn or slide)")
        lower, upper = m.jnt_range[joint] if m.jnt_limited[joint] else (-np.inf, np.inf)
        axis = np.asarray(m.jnt_axis[joint], dtype=float)
        sliding = kind == mj.mjtJoint.mjJNT_SLIDE
        return JointDescription(name, "prismatic" if sliding else "revolute", (tuple(float(c) for c in origin[0]), origin[1]),  # type: ignore[arg-type]
                                tuple(float(a) for a in axis / np.linalg.norm(axis)),  # type: ignore[arg-type]
                                float(lower), float(upper), None)

    def _link(self, body: int, name: str, parent: int, joint: JointDescription | None,
              anchor: np.ndarray, carries: bool = True) -> int:
        visuals, collisions, mass, centre, inertia, friction = ([], [], None, None, None, None)
        if carries:
            visuals, collisions, friction = self._geoms(body, anchor)
            mass, centre, inertia = self._inertia(body, anchor)
        glb = link_meshes.drawn(visuals, name, self.limits)
        self.links.append(LinkDescription(name, parent, joint, None if glb is None else self.store(glb),
                                          link_meshes.envelope(collisions), mass, centre, inertia,
                                          friction))
        if carries:
            self.link_of[body] = len(self.links) - 1
        return len(self.links) - 1

    def _geoms(self, body: int, anchor: np.ndarray) -> tuple[list[Element], list[Element], float | None]:
        m = self.m
        visuals, collisions, friction = [], [], None
        for geom in range(m.body_geomadr[body], m.body_geomadr[body] + m.body_geomnum[body]):
            shape = self._shape(geom)
            if shape is None:
                continue
            placement = np.eye(4)
            w, x, y, z = m.geom_quat[geom]
            placement[:3, :3] = _matrix((x, y, z, w))
            placement[:3, 3] = np.asarray(m.geom_pos[geom]) - anchor
            if m.geom_group[geom] < VISUAL_GROUPS and m.geom_rgba[geom][3] > 0:
                material = m.geom_matid[geom]
                rgba = m.mat_rgba[material] if material >= 0 else m.geom_rgba[geom]
                visuals.append(Element(shape, placement, tuple(float(c) for c in rgba)))
            if m.geom_contype[geom] or m.geom_conaffinity[geom]:
                collisions.append(Element(shape, placement))
                friction = float(m.geom_friction[geom][0]) if friction is None else friction
        return visuals, collisions, friction

    def _shape(self, geom: int) -> Any:
        m, types = self.m, self.mj.mjtGeom
        kind, size = int(m.geom_type[geom]), m.geom_size[geom]
        if kind == types.mjGEOM_BOX:
            return link_meshes.box(2 * size)
        if kind == types.mjGEOM_SPHERE:
            return link_meshes.sphere(size[0])
        if kind == types.mjGEOM_CAPSULE:
            return link_meshes.capsule(size[0], 2 * size[1])
        if kind == types.mjGEOM_CYLINDER:
            return link_meshes.cylinder(size[0], 2 * size[1])
        if kind == types.mjGEOM_ELLIPSOID:
            ball = link_meshes.sphere(1.0)
            ball.apply_scale(size)
            return ball
        if kind == types.mjGEOM_MESH:
            return self._mesh(int(m.geom_dataid[geom]))
        return None  # planes, height fields and SDFs belong to the world, not a hand

    def _mesh(self, mesh: int) -> Any:
        import trimesh

        m = self.m
        vertices = m.mesh_vert[m.mesh_vertadr[mesh]:m.mesh_vertadr[mesh] + m.mesh_vertnum[mesh]]
        faces = m.mesh_face[m.mesh_faceadr[mesh]:m.mesh_faceadr[mesh] + m.mesh_facenum[mesh]]
        self.budget.count(len(faces), f"mesh {self._name(self.mj.mjtObj.mjOBJ_MESH, mesh)}")
        return trimesh.Trimesh(np.array(vertices, dtype=float), np.array(faces), process=False)

    def _inertia(self, body: int, anchor: np.ndarray) -> tuple[Any, Any, Any]:
        m = self.m
        mass = float(m.body_mass[body])
        if mass <= 0:
            return None, None, None
        w, x, y, z = m.body_iquat[body]
        centre = tuple(float(c) for c in np.asarray(m.body_ipos[body]) - anchor)
        return mass, centre, diagonal_in(_matrix((x, y, z, w)), np.diag(m.body_inertia[body]))

    def _couplings(self) -> list[Coupling]:
        m, mj = self.m, self.mj
        joint_name = lambda j: self._name(mj.mjtObj.mjOBJ_JOINT, int(j))  # noqa: E731
        found = []
        for eq in range(m.neq):
            data = m.eq_data[eq]
            if m.eq_type[eq] == mj.mjtEq.mjEQ_JOINT and m.eq_obj2id[eq] >= 0:
                found.append(Coupling(joint_name(m.eq_obj1id[eq]), joint_name(m.eq_obj2id[eq]),
                                      float(data[1]), float(data[0])))
            elif m.eq_type[eq] == mj.mjtEq.mjEQ_TENDON and m.eq_obj2id[eq] < 0:
                pair = self._fixed_pair(int(m.eq_obj1id[eq]))
                if pair:  # c_l·q_l + c_f·q_f = c0 holds the tendon's length
                    (leader, c_l), (follower, c_f) = pair
                    found.append(Coupling(joint_name(follower), joint_name(leader), -c_l / c_f,
                                          float(data[0]) / c_f))
        driven = {int(m.actuator_trnid[a][0]) for a in range(m.nu)
                  if m.actuator_trntype[a] == mj.mjtTrn.mjTRN_TENDON}
        for tendon in sorted(driven):
            pair = self._fixed_pair(tendon)
            if pair:  # an actuator pulls both joints: they share its travel as their coefficients say
                (leader, c_l), (follower, c_f) = pair
                found.append(Coupling(joint_name(follower), joint_name(leader), c_l / c_f, 0.0))
        return found

    def _fixed_pair(self, tendon: int) -> list[tuple[int, float]] | None:
        """(joint, coefficient) of a fixed tendon over exactly two joints, else None."""
        m, mj = self.m, self.mj
        wraps = range(m.tendon_adr[tendon], m.tendon_adr[tendon] + m.tendon_num[tendon])
        if len(wraps) != 2 or any(m.wrap_type[w] != mj.mjtWrap.mjWRAP_JOINT for w in wraps):
            return None
        pair = [(int(m.wrap_objid[w]), float(m.wrap_prm[w])) for w in wraps]
        return pair if all(c != 0 for _, c in pair) else None


def _matrix(quaternion: tuple[float, float, float, float]) -> np.ndarray:
    return np.asarray(to_matrix(quaternion))


