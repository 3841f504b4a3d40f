"""A scene as a document: exported, imported into another scene and exported again, it is
the same document; a document that fails a check changes nothing."""

from __future__ import annotations

import base64
import copy
import json
import math
import random

import pytest
import trimesh

from server.core.protocol import api
from server.core.physics.assets import AssetLibrary
from server.core.protocol.messages import schema
from server.core.protocol.operations import Operations
from server.core.scene.scene import Scene
from server.core.protocol.scene_document import encode_document, export_scene, import_scene
from server.core.kit.errors import BadMessage, DuplicateId, Forbidden, UnknownAsset, VPError
from server.web.storage.upload_folder import UploadFolder
from tests.hand_files import stored_hand


def ref(node_id):
    return {"ref": node_id}


def cube_glb() -> bytes:
    return trimesh.creation.box(extents=(0.4, 0.8, 0.2)).export(file_type="glb")


@pytest.fixture
def library(tmp_path):
    (tmp_path / "uploads").mkdir()
    return AssetLibrary(uploads=tmp_path / "uploads")


def new_scene(name, library):
    """A scene as a server's process makes it: what documents bring is kept with its uploads."""
    return Scene(name, assets=library, uploads=UploadFolder(library))


@pytest.fixture
def busy(library):
    """A scene with every creatable type, changed after it was made in every saved way."""
    scene = new_scene("lab", library)
    upload = UploadFolder(library).store(cube_glb(), scene.limits)["name"]
    ops = Operations(scene, "c1")
    for object_id, type_name, args in [
            ("c1.1", "RoundHand", [False]), ("c1.2", "AnthroHand", []), ("c1.3", "EdgedHand", [False]),
            ("c1.4", "Robot", []), ("c1.5", "MotorZ", ["-Infinity", 1.2, 0.5, 0.3, 0.2]),
            ("c1.6", "Motor", ["y", -1, "Infinity"]), ("c1.7", "MotorX", []), ("c1.8", "MotorY", []),
            ("c1.9", "Ball", [0.3, "red"]), ("c1.10", "Box", [0.1, 0.2, 0.3, 0x00ff00]),
            ("c1.11", "EdgedFinger", [0.8, 0.2, 0.25]), ("c1.12", "EdgedTip", []),
            ("c1.13", "EdgedPalm", [True, 1.2]), ("c1.14", "Sensor", [False, "#ffaa00"]),
            ("c1.15", "Part", []), ("c1.16", "Slot", [[0, 1, 0]]),
            ("c1.17", "GLTFPart", [upload, 0.5]), ("c1.18", "RoundFinger", ["round-finger-8.glb"]),
            ("c1.19", "RoundPalm", [True, "../assets/gltf/round-palm.glb", 1.3]),
            ("c1.20", "AnthroPalm", [False, "anthro-palm.glb"]),
            ("c1.21", "AnthroThumb", [True, "anthro-thumb.glb"]),
            ("c1.arm", "SceneMesh", [{"kind": "sphere", "radius": 0.2}, "blue"]),
            ("c1.22", "MotorY", [-1, 1]), ("c1.23", "ImportedRobot", [stored_hand(library)]),
            ("c1.24", "Slider", [[0, 0, 1], 0, 0.5, 0.1])]:
        ops.create(object_id, type_name, args)
    ops.call("c1.1", "setAngles", [0.1, 0.4, 0.5])
    ops.call("c1.1", "setPosition", [1, 0, 2])
    ops.call("c1.1", "share", [])
    ops.call("c1.1", "addGUI", ["Right"])
    ops.call("c1.1/0", "recolor", ["white", [1, 0, 0], 0.2])
    ops.call("c1.17", "recolor", [0xffffff, "black"])
    ops.call("c1.2", "setPosition", [])  # out of the scene, kept
    ops.call("c1.3", "setRotation", [0.1, 0.2, 0.3, "ZYX"])
    ops.call("c1.3", "setScale", [[2, 1, 1]])
    ops.call("c1.4", "attachChain", [ref("c1.5"), ref("c1.11"), ref("c1.6"), ref("c1.17")])
    ops.call("c1.5", "setName", ["shoulder"])
    ops.call("c1.1/4", "follow", [ref("c1.1/2"), 0.5, -0.1])
    ops.call("c1.23", "setAngles", [0.3, 0, 0, 1.1])
    ops.call("c1.23/3", "setMass", [0.05])
    ops.call("c1.6", "flip", [])
    ops.call("c1.6", "setAngle", [2.5])
    ops.call("c1.24", "setMaxTorque", [12])
    ops.call("c1.24", "setAngle", [0.4])
    ops.call("c1.11", "addSlot", [[0, 0.3, 0.1]])
    ops.call("c1.14", "attachToSlot", [ref("c1.11"), 1])
    ops.call("c1.9", "attachToSlot", [ref("c1.3"), ref("c1.16")])  # a loose slot, moved
    ops.call("c1.4", "keep", [])
    ops.call("c1.arm", "setColor", ["#123456"])
    ops.call("scene", "setCameraPosition", [[1, 2, 3]])
    ops.call("c1.7", "setVisible", [False])
    # parts taken out of a hand, one of its motors deleted, a finger kept elsewhere
    ops.call("c1.12", "attachToSlot", [ref("c1.13"), 2])
    ops.call("c1.3/9", "attachToSlot", [ref("c1.4")])
    ops.apply({"op": "delete", "object": "c1.3/5"})
    ops.apply({"op": "delete", "object": "c1.8"})
    scene.tick(1 / 60)
    yield scene
    scene.close()


def same(a: Scene, b: Scene) -> None:
    """The two scenes' documents match, but for the scene's name."""
    first, second = export_scene(a), export_scene(b)
    first["scene"] = second["scene"]
    for one, other in zip(first["nodes"], second["nodes"]):
        assert one == other
    assert encode_document(first) == encode_document(second)


def test_every_creatable_type_is_in_the_busy_scene(busy):
    made = {entry["type"] for entry in export_scene(busy)["nodes"] if "/" not in entry["id"]}
    assert made == {name for name, spec in api.TYPES.items() if spec.creatable}


def test_a_scene_made_again_from_its_document_is_the_same_scene(busy, library):
    copy_ = new_scene("copy", library)
    with copy_.journal.transaction():
        summary = import_scene(copy_, json.loads(encode_document(export_scene(busy))))
    assert summary == {"scene": "copy", "objects": len(busy.nodes), "owners": ["c1"]}
    same(busy, copy_)
    assert copy_.snapshot()["nodes"] == busy.snapshot()["nodes"]
    for node_id, node in busy.nodes.items():  # where everything is, and how it turns
        assert copy_.get(node_id).world_pose() == node.world_pose()
    assert copy_.get("c1.1").get_angles() == busy.get("c1.1").get_angles()
    assert copy_.get("c1.4").get_motors()[1].angle == 2.5  # flipped, clamped into [-1, inf)
    copy_.get("c1.1/2").set_angle(-1.0)  # still coupled
    assert copy_.get("c1.1/4").angle == -0.6
    copy_.close()


def test_exporting_an_unchanged_scene_gives_the_same_bytes(busy):
    first = encode_document(export_scene(busy))
    busy.tick(1 / 60)
    busy.tick(1 / 60)
    assert encode_document(export_scene(busy)) == first
    assert b"time" not in first.split(b'"nodes"')[0]  # no clock before the nodes


def test_the_document_has_the_schema_form_and_carries_uploads_by_hash(busy, library):
    document = export_scene(busy)
    assert document["format"] == "virtual-prosthetics-scene" and document["version"] == 1
    [asset] = [a for a in document["assets"] if base64.b64decode(a["data"]) == cube_glb()]
    assert asset["bytes"] == len(cube_glb())
    assert "data" not in export_scene(busy, embed_assets=False)["assets"][0]
    robot = busy.get("c1.23")  # an imported robot: its file and every link's mesh
    assert {a["name"] for a in document["assets"]} == {asset["name"], *robot.uploaded_files()}
    hand = next(e for e in document["nodes"] if e["id"] == "c1.1")
    assert hand["owner"] == "c1" and hand["args"] == [False] and hand["state"]["shared"] is True
    motor = next(e for e in document["nodes"] if e["id"] == "c1.5")
    assert motor["args"][0] == "-Infinity"  # non-finite numbers as the protocol sends them


def test_an_upload_travels_inside_the_document(busy, tmp_path):
    elsewhere = AssetLibrary(uploads=tmp_path)  # another server: the file is not there yet
    copy_ = new_scene("copy", elsewhere)
    with copy_.journal.transaction():
        import_scene(copy_, export_scene(busy))
    assert elsewhere.uploaded_names() == busy.assets.uploaded_names()
    same(busy, copy_)
    without = new_scene("bare", AssetLibrary(uploads=tmp_path / "none"))
    (tmp_path / "none").mkdir()
    with pytest.raises(UnknownAsset), without.journal.transaction():
        import_scene(without, export_scene(busy, embed_assets=False))
    assert not without.nodes
    keeps_nothing = Scene("keeps-nothing", assets=AssetLibrary(uploads=tmp_path / "none"))
    with pytest.raises(Forbidden), keeps_nothing.journal.transaction():
        import_scene(keeps_nothing, export_scene(busy))
    assert not keeps_nothing.nodes and not list((tmp_path / "none").iterdir())


def test_slot_numbers_and_ids_go_on_where_they_were(busy, library):
    copy_ = new_scene("copy", library)
    with copy_.journal.transaction():
        import_scene(copy_, export_scene(busy))
    ops = Operations(copy_, "c1")
    assert ops.call("c1.11", "addSlot", [])["ref"] == "c1.11/s2"  # s0, s1 were used
    assert "c1.3/5" not in copy_.nodes and "c1.3/9" in copy_.nodes
    with pytest.raises(DuplicateId):
        ops.create("c1.8", "Ball", [])  # deleted before the export: never used again
    ops.create("c1.25", "Ball", [])
    copy_.close()


def test_an_import_replaces_what_the_scene_held(busy, library):
    other = new_scene("other", library)
    Operations(other, "c9").create("c9.1", "EdgedHand", [])
    with other.journal.transaction():
        import_scene(other, export_scene(busy))
    assert "c9.1" not in other.nodes
    same(busy, other)


def broken(document, change):
    document = copy.deepcopy(document)
    change(document)
    return document


def entry(document, node_id):
    return next(e for e in document["nodes"] if e["id"] == node_id)


def upload(document, suffix):
    return next(a for a in document["assets"] if a["name"].endswith(suffix))


def cycle(document):
    entry(document, "c1.11").setdefault("children", []).append("c1.4")  # a robot below its part


@pytest.mark.parametrize("change, error", [
    (lambda d: d.update(format="other"), "not a scene document"),
    (lambda d: d.update(version=2), "version"),
    (lambda d: d["nodes"][0].update(type="Teapot"), "nodes/0/type"),
    (lambda d: entry(d, "c1.9")["args"].append(1), "at most 2 arguments"),
    (lambda d: entry(d, "c1.9")["args"].__setitem__(0, -1), "a size lies between"),
    (lambda d: d["nodes"][0]["state"].update(position=[1, 2, "x"]), "nodes/0/state/position"),
    (lambda d: d["nodes"][0]["state"].update(scale=[1, 2, -1]), "scale"),
    (lambda d: d["nodes"][0].update(owner="c2"), "belongs to c1"),
    (cycle, "below itself"),
    (lambda d: d["nodes"].append({"id": "c1.1/99", "type": "Ball", "state": {}}), "only slots"),
    (lambda d: d["nodes"].append({"id": "c1.1", "type": "Ball", "args": [], "state": {}}), "twice"),
    (lambda d: d["nodes"].append({"id": "c1.1/77", "type": "Slot", "state": {}}) or
     entry(d, "c1.1/0").setdefault("slots", []).append("c1.1/77"), "not a slot below"),
    (lambda d: entry(d, "c1.1/0/s0").update(type="Ball"), "is a Slot when made again, not a Ball"),
    (lambda d: d["assets"][0].update(data="not base64!"), "not base64"),
    (lambda d: upload(d, ".glb").update(data=base64.b64encode(b"glTF" * 9).decode()), "glTF|GLB"),
    (lambda d: upload(d, ".robot").update(data=base64.b64encode(b'{"links": 3}').decode()),
     "does not read as a robot description"),
    (lambda d: d["ids"].update(c1={"numbers": [], "names": [str(k) + "x" for k in range(1001)]}),
     "at most 1000"),
])
def test_a_document_that_fails_a_check_changes_nothing(busy, library, change, error):
    target = new_scene("target", library)
    Operations(target, "c5").create("c5.1", "RoundHand", [])
    before = encode_document(export_scene(target))
    with pytest.raises(VPError, match=error), target.journal.transaction():
        import_scene(target, broken(export_scene(busy), change))
    assert encode_document(export_scene(target)) == before
    target.close()


def test_the_schema_names_every_type_a_document_may_hold():
    enum = schema()["$defs"]["documentNode"]["properties"]["type"]["enum"]
    assert sorted(enum) == sorted(name for name in api.TYPES if name != "Scene")


def test_a_motor_angle_out_of_its_limits_is_clamped_as_setangle_does(busy, library):
    document = export_scene(busy)
    motor = next(e for e in document["nodes"] if e["id"] == "c1.5")
    motor["state"]["angle"] = 9.0
    copy_ = new_scene("copy", library)
    with copy_.journal.transaction():
        import_scene(copy_, document)
    assert copy_.get("c1.5").angle == 1.2
    assert math.isinf(copy_.get("c1.5").min)


def test_a_non_document_is_refused_with_what_is_wrong():
    scene = Scene("x")
    with pytest.raises(BadMessage, match="not a scene document"):
        import_scene(scene, [1, 2])
    scene.close()


ODD_VALUES = [float("nan"), float("inf"), -1e308, 1e9, -1, 0, 2 ** 63, "", "x", None, True,
              [], {}, [1e9] * 3, "c1.1", "c1.9999", {"ref": "c1.1"}, "demo.1"]


def _places(value, path=()):
    """Every path into a JSON value (dict keys and list indexes)."""
    yield path
    items = value.items() if isinstance(value, dict) else \
        enumerate(value) if isinstance(value, list) else ()
    for key, inner in items:
        yield from _places(inner, path + (key,))


def test_documents_changed_at_random_are_taken_or_refused_and_nothing_else(busy, library):
    """A saved file or an upload can hold anything: 300 documents with one to three values
    replaced by odd ones or left out are each made or refused with a VPError that changes
    nothing (an exception of another kind would be a bug; PyBullet must never see them)."""
    base = json.loads(encode_document(export_scene(busy)))
    places = [p for p in _places(base) if p]
    draw = random.Random(12)
    target = new_scene("target", library)
    empty = encode_document(export_scene(target))
    taken = 0
    for _ in range(300):
        document = copy.deepcopy(base)
        for path in draw.sample(places, draw.randint(1, 3)):
            holder = document
            try:
                for key in path[:-1]:
                    holder = holder[key]
                if draw.random() < 0.15:
                    del holder[path[-1]]
                else:
                    holder[path[-1]] = draw.choice(ODD_VALUES)
            except (KeyError, IndexError, TypeError):
                pass  # an earlier change took this place away
        try:
            with target.journal.transaction():
                import_scene(target, document)
        except VPError:
            assert encode_document(export_scene(target)) == empty
            continue
        taken += 1
        target.tick(1 / 60)
        with target.journal.transaction():
            import_scene(target, json.loads(empty))
    assert 0 < taken < 300  # both kinds were met
    target.close()


def test_a_dynamic_robot_comes_back_held_where_its_script_put_it(library):
    # its node is where the physics has it (a loaded hand turns a hair at its mount); a
    # document keeps the mount too, and an import holds the robot there from its first step
    scene = Scene("lab", assets=library)
    ops = Operations(scene, "c1")
    ops.call("scene", "setPhysics", ["dynamic"])
    ops.create("c1.h", "EdgedHand", [True])
    ops.call("c1.h", "setPosition", [0, 3, 0])
    ops.call("c1.h", "setRotation", [0.3, 0, 0])
    for _ in range(30):
        scene.tick(1 / 60)
    hand = scene.nodes["c1.h"]
    put = hand.mount
    assert put is not None and (hand.position, hand.quaternion) != put  # it sagged a hair
    document = json.loads(encode_document(export_scene(scene)))
    [entry] = [e for e in document["nodes"] if e["id"] == "c1.h"]
    assert entry["state"]["mount"] == [list(put[0]), list(put[1])]
    copy_of = Scene("copy", assets=library)
    with copy_of.journal.transaction():
        import_scene(copy_of, document)
    copy_of.tick(1 / 60)
    dynamics = copy_of.bodies.physics.dynamics
    built = copy_of.bodies.physics._trees["c1.h"]
    assert copy_of.nodes["c1.h"].mount == put and dynamics._mounts[built.mount] == put
