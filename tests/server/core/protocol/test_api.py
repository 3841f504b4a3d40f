"""The API table: one source for names, backed by real methods."""

import inspect

from server.core.physics.assets import AssetLibrary
from server.core.protocol import api
from server.core.protocol.arguments import KINDS
from server.core.protocol.messages import schema
from server.core.protocol.node_classes import NODE_CLASSES
from server.core.protocol.operations import Operations
from server.core.protocol.saved_states import SCENE_CALLS
from server.core.scene.scene import Scene
from server.core.kit.errors import ERROR_CODES
from tests.hand_files import stored_hand


def test_every_method_in_the_table_exists_with_room_for_its_arguments():
    for type_name, cls in {**NODE_CLASSES, "Scene": Scene}.items():
        for method in api.methods_of(type_name).values():
            answered = SCENE_CALLS.get(method.name) if cls is Scene else None  # by saved_states
            function = answered or getattr(cls, method.python, None)
            assert callable(function), f"{type_name}.{method.python} is missing"
            parameters = list(inspect.signature(function).parameters.values())[1:]
            if any(p.kind is p.VAR_POSITIONAL for p in parameters):
                continue
            assert len(parameters) >= len(method.params), f"{type_name}.{method.name}"


def test_every_parameter_kind_is_known():
    for spec in api.TYPES.values():
        params = [*spec.params, *(p for m in spec.methods for p in m.params)]
        assert {p.kind for p in params} <= KINDS, spec.name


def test_snake_names():
    assert api.snake("attachToSlot") == "attach_to_slot"
    assert api.snake("addGUI") == "add_gui"
    assert api.snake("setCameraPosition") == "set_camera_position"


def test_error_codes_match_the_schema():
    codes = schema()["$defs"]["error"]["properties"]["code"]["enum"]
    assert sorted(codes) == sorted(ERROR_CODES)


REQUIRED_ARGS = {"GLTFPart": ["round-finger-8.glb"], "RoundFinger": ["round-finger-8.glb"],
             "RoundPalm": [True, "round-palm.glb"], "AnthroPalm": [True, "anthro-palm.glb"],
             "AnthroThumb": [True, "anthro-thumb.glb"], "Motor": ["x"], "Slider": ["y"],
             "SceneMesh": [{"kind": "box", "size": [1, 1, 1]}]}


def test_each_type_starts_with_the_slots_the_table_says(tmp_path):
    # clients name the slot addSlot makes next from these counts, without a round trip
    library = AssetLibrary(uploads=tmp_path)
    scene = Scene("slots", assets=library)
    operations = Operations(scene, "c1")
    required = {**REQUIRED_ARGS, "ImportedRobot": [stored_hand(library)]}
    for number, (name, count) in enumerate(api.slot_counts().items()):
        operations.create(f"c1.{number}", name, required.get(name, []))
        slots = scene.nodes[f"c1.{number}"].slots
        assert [slot.id for slot in slots] == [f"c1.{number}/s{k}" for k in range(count)], name
