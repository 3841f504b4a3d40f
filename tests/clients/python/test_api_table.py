"""The client's classes offer exactly the methods of the API table, in snake_case."""

import inspect
import json
from pathlib import Path

import virtual_prosthetics as vp
from virtual_prosthetics.http_api import request
from virtual_prosthetics.objects import Node
from virtual_prosthetics.runtime import CLASSES

from tests.hand_files import hand_zip

API = json.loads((Path(__file__).resolve().parents[3] / "protocol" / "api.json").read_text())
CLIENT_ONLY = {"delete"}
ROBOT_FILES = {"export_urdf", "export_mjcf", "export_glb"}  # REST downloads, not protocol calls


def table_methods(type_name):
    names = set()
    while type_name:
        spec = API["types"][type_name]
        names |= {m["python"] for m in spec["methods"].values()}
        names |= set(spec["callbacks"].values())
        type_name = spec["extends"]
    return names


def public_methods(cls):
    return {n for n, v in inspect.getmembers(cls, inspect.isfunction) if not n.startswith("_")}


def test_every_creatable_type_has_a_client_class():
    creatable = {name for name, spec in API["types"].items() if spec["creatable"]}
    assert creatable == set(CLASSES)


def test_client_methods_match_the_table():
    for type_name, cls in CLASSES.items():
        files = ROBOT_FILES if issubclass(cls, vp.Robot) else set()
        assert public_methods(cls) == table_methods(type_name) | CLIENT_ONLY | files, type_name


def test_constructors_take_the_tables_parameters():
    for type_name, cls in CLASSES.items():
        params = API["types"][type_name]["params"]
        signature = inspect.signature(cls.__init__).parameters.values()
        positional = [p for p in signature if p.kind in (p.POSITIONAL_OR_KEYWORD, p.VAR_POSITIONAL)][1:]
        if any(p.kind is p.VAR_POSITIONAL for p in positional):
            continue
        assert len(positional) == len(params), type_name


def test_scene_functions_exist():
    scene_methods = {m["python"] for m in API["types"]["Scene"]["methods"].values()}
    for name in scene_methods:
        assert callable(getattr(vp, name)), name


ARGUMENTS = {
    "point": lambda: [0.1, 0.2, 0.3], "number": lambda: 0.1, "integer": lambda: 0,
    "angle": lambda: 0.1, "order": lambda: "XYZ", "quaternion": lambda: [0, 0, 0, 1],
    "scale": lambda: [1, 1, 1], "bool": lambda: True, "string": lambda: "named",
    "slot": lambda: 0, "color": lambda: 0x336699, "rgb": lambda: [1, 0, 0],
    "node": lambda: vp.MotorZ(), "part": lambda: vp.Box(), "motor": lambda: vp.MotorZ(), "axis": lambda: "z",
    "asset": lambda: "round-tip.glb", "geometry": lambda: {"kind": "box", "size": [1, 1, 1]},
    "mass": lambda: 2.0, "friction": lambda: 0.5, "torque": lambda: 100.0, "speed": lambda: 3.0,
    "robotFile": lambda: uploaded_hand(),
}


def uploaded_hand() -> str:
    """The test hand's robot file on the current session's server."""
    return json.loads(request(vp.current_session(), "/api/robots", "upload", hand_zip()))["file"]
RETURNS = {
    "none": lambda result, obj: result is None,
    "self": lambda result, obj: result is obj,
    "ref": lambda result, obj: isinstance(result, Node),
}


def table_method_specs(type_name):
    found = {}
    while type_name:
        for name, spec in API["types"][type_name]["methods"].items():
            found.setdefault(name, spec)
        type_name = API["types"][type_name]["extends"]
    return found


def test_every_changing_method_returns_what_the_table_says(scene):
    """Where 1.0 returned ``this`` the client returns the object, so calls chain."""
    checked = []
    for type_name, cls in CLASSES.items():
        for name, spec in table_method_specs(type_name).items():
            if not spec["mutates"] or name == "setTransforms":
                continue
            args = [ARGUMENTS[p["kind"]]() for p in API["types"][type_name]["params"]
                    if "default" not in p]
            obj = cls(*args)
            result = getattr(obj, spec["python"])(*[ARGUMENTS[p["kind"]]() for p in spec["params"]])
            assert RETURNS[spec["returns"]](result, obj), f"{type_name}.{name}: {result!r}"
            checked.append(f"{type_name}.{name}")
    scene.sync()  # the server took every call
    assert "EdgedHand.setRotation" in checked and "Motor.flip" in checked
