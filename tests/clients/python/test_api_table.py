"""The client's classes offer exactly the methods of the API table, in snake_case."""

import inspect
import json
from pathlib import Path

import virtual_prosthetics as vp
from virtual_prosthetics.robots import CLASSES

API = json.loads((Path(__file__).resolve().parents[3] / "protocol" / "api.json").read_text())
CLIENT_ONLY = {"delete"}


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
        assert public_methods(cls) == table_methods(type_name) | CLIENT_ONLY, type_name


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
