"""A scene as a document: what ``GET /api/scenes/{scene}/export`` gives, ``import`` takes
and ``--state-dir`` keeps (the form: ``sceneDocument`` in ``protocol/schema/protocol.json``).

A node is written as how it was made (type and, for a top-level object, the manual's
constructor arguments) and what changed since (its children, slots and :data:`STATE`).
Restoring makes each top-level object again with its constructor, so the parts it makes
inside come back with the same ids, then puts the tree and the state back through the
same checks as a client's calls. Nothing in a document depends on the clock (the scene's
time is left out): exporting an unchanged scene twice gives the same bytes.
"""

from __future__ import annotations

import base64
import hashlib
import json
from dataclasses import dataclass
from functools import cache
from typing import Any, Callable

from ..kit.errors import BadJSON, BadMessage, Forbidden, UnknownAsset, WrongType
from ..kit.ids import owner_of
from ..kit.numbers import encode_numbers
from ..model.gltf_parts import GLTFPart
from ..model.imported import ImportedRobot
from ..model.motor import Motor
from ..model.node import Node, Slot
from ..model.page_meshes import SceneMesh
from ..model.parts import Part
from ..model.robot import Robot
from ..physics.assets import UPLOADED_URL, AssetLibrary
from ..physics.robot_description import RobotDescription
from ..physics.settings import KINEMATIC, Physics
from ..scene.scene import Scene
from . import api
from .api import Param
from .arguments import bind
from .messages import check_document, encode
from .node_classes import NODE_CLASSES

FORMAT = "virtual-prosthetics-scene"
VERSION = 1


@dataclass(frozen=True)
class Saved:
    """One piece of a node's state: the attribute, its key in a document, how a value is
    checked (as a call's arguments are) and how it is set again."""

    attribute: str
    params: tuple[Param, ...]
    restore: Callable[..., Any]
    key: str = ""
    repeated: bool = False  # the attribute holds the arguments of several calls
    spread: bool = False    # the attribute holds the arguments of one call

    @property
    def name(self) -> str:
        return self.key or self.attribute


def _target(motor: Motor, target: float) -> None:
    """Where a motor drives in dynamic mode, when it is not where it is."""
    motor.target = target


def _follow(motor: Motor, leader: str, ratio: float, offset: float) -> None:
    """A follower's leader, once every node is in its place."""
    motor.follow(motor.scene.get(leader), ratio, offset)  # type: ignore[arg-type]


def _mount(robot: Robot, position: tuple[float, ...], quaternion: tuple[float, ...]) -> None:
    """Where a dynamic robot's mount holds it (its node: where the physics had it)."""
    robot._assign("mount", (tuple(position), tuple(quaternion)))


def _slot_count(part: Part, count: int) -> None:
    """Slots ``addSlot`` made so far: new ones continue the numbering, never reuse it."""
    part._slot_count = max(part._slot_count, count)


# Node's own setters, not Robot's: a robot's setPosition also puts it back in the scene.
STATE: dict[type[Node], tuple[Saved, ...]] = {
    Node: (Saved("position", (Param("position", "point"),), Node.set_position),
           Saved("quaternion", (Param("quaternion", "quaternion"),), Node.set_quaternion),
           Saved("scale", (Param("scale", "scale"),), Node.set_scale),
           Saved("visible", (Param("visible", "bool"),), Node.set_visible),
           Saved("kept", (Param("on", "bool"),), Node.keep)),
    Part: (Saved("_slot_count", (Param("count", "integer"),), _slot_count, key="slotCount"),
           Saved("mass", (Param("mass", "mass"),), Part.set_mass),
           Saved("friction", (Param("friction", "friction"),), Part.set_friction),
           Saved("saved_static", (Param("static", "bool"),), Part.set_static, key="static")),
    Motor: (Saved("name", (Param("name", "string"),), Motor.set_name),
            Saved("flipped", (Param("flipped", "bool"),), Motor.flip),
            Saved("angle", (Param("angle", "number"),), Motor.set_angle),
            Saved("max_torque", (Param("torque", "torque"),), Motor.set_max_torque, key="maxTorque"),
            Saved("max_speed", (Param("speed", "speed"),), Motor.set_max_speed, key="maxSpeed"),
            Saved("saved_target", (Param("target", "number"),), _target, key="target"),
            Saved("following", (Param("leader", "string"), Param("ratio", "number"),
                                Param("offset", "number")), _follow, key="follows", spread=True)),
    Robot: (Saved("gui", (Param("title", "string"),), Robot.add_gui),
            Saved("shared", (Param("on", "bool"),), Robot.share),
            Saved("mount", (Param("position", "point"), Param("quaternion", "quaternion")),
                  _mount, spread=True)),
    GLTFPart: (Saved("recolors", (Param("fromColor", "rgb"), Param("toColor", "rgb"),
                                  Param("eps", "number")), GLTFPart.recolor, repeated=True),),
    SceneMesh: (Saved("color", (Param("color", "color"),), SceneMesh.set_color),),
}


@cache
def state_of(cls: type[Node]) -> tuple[Saved, ...]:
    """Every piece of state a node of this class has, its bases' first."""
    return tuple(saved for base in reversed(cls.__mro__) for saved in STATE.get(base, ()))


# --- export -------------------------------------------------------------------------------

def export_scene(scene: Scene, embed_assets: bool = True) -> dict[str, Any]:
    """The scene as a document; uploaded mesh files by content hash, with their bytes
    (base64) when ``embed_assets`` (a document another server can import)."""
    physics = {"physics": scene.physics.wire()} if scene.physics != Physics() else {}
    caption = {"caption": scene.caption.text} if scene.caption.text else {}
    return {"format": FORMAT, "version": VERSION, "scene": scene.name,
            "camera": scene.camera.wire(), **caption, **physics,
            "ids": scene.ids.wire(),
            "assets": [_asset_entry(scene.assets, name, embed_assets)
                       for name in uploaded_assets(scene)],
            "nodes": [_node_entry(node) for node in scene.in_order_made()]}


def encode_document(document: dict[str, Any]) -> bytes:
    """The document's bytes, as every message is encoded: the same document, the same bytes."""
    return encode(document).encode()


def _node_entry(node: Node) -> dict[str, Any]:
    entry: dict[str, Any] = {"id": node.id, "type": node.type_name}
    if "/" not in node.id:
        entry["owner"] = owner_of(node.id)
        entry["args"] = encode_numbers(node.constructor_args())
    if node.children:
        entry["children"] = [child.id for child in node.children]
    if node.slots:
        entry["slots"] = [slot.id for slot in node.slots]
    state = {}
    for attribute, key in _keys(type(node)):
        value = getattr(node, attribute)
        if value is not None and value != ():
            # state is finite (its setters refuse the rest; encoding would fail loudly)
            state[key] = _lists(value) if type(value) is tuple else value
    entry["state"] = state
    return entry


@cache
def _keys(cls: type[Node]) -> tuple[tuple[str, str], ...]:
    """(attribute, document key) of each piece of state of a class (export's hot loop)."""
    return tuple((saved.attribute, saved.name) for saved in state_of(cls))


def _lists(value: tuple[Any, ...]) -> list[Any]:
    """A tuple (and the tuples in it) as lists, which JSON documents hold."""
    return [_lists(item) if type(item) is tuple else item for item in value]


def document_owners(document: dict[str, Any]) -> list[str]:
    """Every owner a (checked) document names: of its objects and of the ids it used."""
    return sorted({owner_of(entry["id"]) for entry in document["nodes"]} | set(document["ids"]))


def scene_owners(scene: Scene) -> list[str]:
    """Every owner a scene knows: of its objects and of the ids used in it."""
    return sorted({owner_of(node_id) for node_id in scene.nodes} | set(scene.ids.wire()))


def parse_document(body: bytes) -> Any:
    """A document's JSON from the bytes of a request or file (:class:`BadJSON` if it is not
    JSON, nested too deep included); checked by :func:`import_scene`."""
    try:
        return json.loads(body)
    except (ValueError, UnicodeDecodeError, RecursionError) as error:
        raise BadJSON(f"the body is not JSON: {str(error)[:120]}") from None


def check_document_bytes(body: bytes) -> None:
    """Refuse bytes that are not a scene document (:func:`parse_document`, the schema)."""
    check_document(parse_document(body))


def check_import(scene: Scene, document: Any, present: set[str], replace: bool) -> None:
    """Refuse an import that would take what belongs to clients ``present`` in the scene
    (connected, or within their grace period): objects or ids of theirs in the document
    would become theirs, and without ``replace`` their objects in the scene would go."""
    check_document(document)
    theirs = sorted(set(document_owners(document)) & present)
    if theirs:
        raise Forbidden(f"the document holds objects or ids of {', '.join(theirs[:5])}, a "
                        f"client of scene {scene.name} now: they would become that client's; "
                        f"import it when that client has left", clients=", ".join(theirs[:5]))
    holding = sorted({owner_of(node_id) for node_id in scene.nodes} & present)
    if holding and not replace:
        raise Forbidden(f"scene {scene.name} holds objects of {', '.join(holding[:5])}, "
                        f"connected now: importing deletes them; add ?replace=true to replace "
                        f"the scene anyway (they are told)", clients=", ".join(holding[:5]))


def uploaded_assets(scene: Scene) -> list[str]:
    """Names of the uploaded files the scene's parts and robots are made of, sorted."""
    names = set()
    for node in scene.nodes.values():
        if isinstance(node, ImportedRobot):
            names.update(node.uploaded_files())
        elif isinstance(node, GLTFPart) and node.mesh.url.startswith(UPLOADED_URL):
            names.add(node.mesh.url[len(UPLOADED_URL):])
    return sorted(names)


def _asset_entry(library: AssetLibrary, name: str, embed: bool) -> dict[str, Any]:
    data = library.locate(name)[0].read_bytes()
    entry = {"name": name, "sha256": hashlib.sha256(data).hexdigest(), "bytes": len(data)}
    if embed:
        entry["data"] = base64.b64encode(data).decode()
    return entry


# --- import -------------------------------------------------------------------------------

_LATER = ("target", "mount")  # restored once the scene's physics is

def import_scene(scene: Scene, document: Any) -> dict[str, Any]:
    """Replace everything in ``scene`` with what ``document`` holds; what was restored.

    Call it inside a journal transaction: a document that fails any check (the schema,
    an argument, a missing mesh file, a cycle, a limit) changes nothing, except that
    mesh files it carries are kept (by content hash: they can only add files)."""
    check_document(document)
    entries = document["nodes"]
    wanted = {entry["id"] for entry in entries}
    if len(wanted) != len(entries):
        raise BadMessage("scene document: an id is listed twice in nodes")
    _store_assets(scene, document["assets"])
    physics = dict(document.get("physics", {"mode": KINEMATIC}))  # a kept state restores again
    for root in scene.roots():
        scene.delete(root)
    scene.set_physics(KINEMATIC)  # angles restored as set, targets after
    scene.registry.fresh_ids()
    for entry in entries:
        _make(scene, entry)
    for node in list(scene.nodes.values()):
        if node.parent is not None:
            node._link(None)
    for node_id in [i for i in list(scene.nodes) if i not in wanted]:
        scene.delete(scene.nodes[node_id])  # made by a constructor, deleted since
    for entry in entries:
        _place_children(scene, entry)
    for entry in entries:
        _restore_state(scene, entry)
    mode = physics.pop("mode")
    scene.set_physics(mode, physics)
    for entry in entries:
        _restore_state(scene, entry, later=True)
    scene.bodies.hold_mounts()
    scene.bodies.check_trees()  # a tree the engine cannot hold: the document is refused
    scene.ids.absorb(document["ids"])
    camera = document["camera"]
    if camera.get("placed", True):
        scene.set_camera_position(tuple(camera["position"]))
        scene.set_camera_target(tuple(camera["target"]))
    else:  # one no script placed stays so: viewers frame the scene
        scene.camera.reset()
    scene.set_caption(document.get("caption", ""))
    return {"scene": scene.name, "objects": len(scene.nodes),
            "owners": sorted({owner_of(i) for i in wanted})}


def _store_assets(scene: Scene, assets: list[dict[str, Any]]) -> None:
    for asset in assets:
        name, data = asset["name"], asset.get("data")
        if data is not None:
            try:
                decoded = base64.b64decode(data, validate=True)
            except ValueError:
                raise BadMessage(f"asset {name}: its data is not base64") from None
            if _here(scene, name) == decoded:
                continue  # (the same file: nothing to keep)
            stored = _store(scene, name, decoded)
            if stored["name"] != name:
                raise BadMessage(f"asset {name}: its data has another content hash "
                                 f"({stored['name']})")
        else:
            path = scene.assets.locate(name)[0]
            if hashlib.sha256(path.read_bytes()).hexdigest() != asset["sha256"]:
                raise UnknownAsset(f"asset {name} here is not the document's file "
                                   f"(another content hash)", filename=name)


def _here(scene: Scene, name: str) -> bytes | None:
    """The bytes of the file ``name`` on this server, if it has one by that name."""
    try:
        return scene.assets.locate(name)[0].read_bytes()
    except (UnknownAsset, Forbidden):  # (a name no file may have: refused when kept)
        return None


def _store(scene: Scene, name: str, data: bytes) -> dict[str, Any]:
    """Keep a document's file: a mesh as an upload is kept, a robot file once it reads."""
    if scene.uploads is None:
        raise Forbidden(f"asset {name} is not on this server, and scene {scene.name} keeps "
                        f"no uploaded files")
    if name.endswith(".robot"):
        return scene.uploads.store_robot(RobotDescription.from_json(data), scene.limits)
    return scene.uploads.store(data, scene.limits)


def _make(scene: Scene, entry: dict[str, Any]) -> None:
    node_id, type_name = entry["id"], entry["type"]
    existing = scene.nodes.get(node_id)
    if existing is not None:  # made by its top-level object's constructor
        if existing.type_name != type_name:
            raise WrongType(f"{node_id} is a {existing.type_name} when made again, not a "
                            f"{type_name}", object=node_id)
        return
    if entry.get("owner", owner_of(node_id)) != owner_of(node_id):
        raise BadMessage(f"{node_id} belongs to {owner_of(node_id)}, not {entry['owner']}",
                         object=node_id)
    if "/" in node_id:
        if type_name != "Slot":
            raise BadMessage(f"{node_id} is a {type_name} that its top-level object does not "
                             f"make; only slots are added later", object=node_id)
        Slot(scene, node_id)
        return
    spec = api.TYPES[type_name]  # the schema allows creatable types only
    args = bind(spec.params, entry.get("args", []), scene.get, f"new {type_name} {node_id}")
    NODE_CLASSES[type_name](scene, node_id, *args)


def _place_children(scene: Scene, entry: dict[str, Any]) -> None:
    node = scene.get(entry["id"])
    for child_id in entry.get("children", []):
        child = scene.get(child_id)
        if child.parent is not None:
            raise BadMessage(f"{child_id} is a child of both {child.parent.id} and {node.id}",
                             object=child_id)
        child._link(node)  # refuses cycles and trees too deep
    slots = [scene.get(slot_id) for slot_id in entry.get("slots", [])]
    for slot in slots:
        if not isinstance(slot, Slot) or slot.parent is not node:
            raise BadMessage(f"{slot.id} is not a slot below {node.id}", object=slot.id)
    node.restore_slots(slots)


def _restore_state(scene: Scene, entry: dict[str, Any], later: bool = False) -> None:
    """A node's state as the document has it: all of it but what waits for the scene's
    physics (:data:`_LATER`), or (``later``) just that."""
    node = scene.get(entry["id"])
    state = entry["state"]
    for saved in state_of(type(node)):
        value = state.get(saved.name)
        if value is None or (saved.name in _LATER) != later:
            continue
        where = f"state {saved.name} of {node.id}"
        calls = value if saved.repeated else [value] if saved.spread else [[value]]
        if not isinstance(calls, list) or not all(isinstance(c, list) for c in calls):
            raise WrongType(f"{where}: expected a list of argument lists", object=node.id)
        if saved.repeated:
            node._assign(saved.attribute, ())  # its constructor's calls are in the list too
        for raw in calls:
            saved.restore(node, *bind(saved.params, raw, scene.get, where))

