"""Binding a request's wire arguments to a method's parameters, with errors that name them."""

import pytest

from server.core.model.parts import Ball
from server.core.protocol.api import TYPES, methods_of
from server.core.protocol.arguments import bind
from server.core.kit.errors import BadArguments, OutOfRange, UnknownObject, WrongType


def params(type_name: str, method: str):
    return methods_of(type_name)[method].params


def test_a_point_is_one_list_or_three_numbers():
    where = "setPosition of c1.1"
    assert bind(params("Part", "setPosition"), [[1, 2, 3]], None, where) == [(1.0, 2.0, 3.0)]
    assert bind(params("Part", "setPosition"), [1, 2, 3], None, where) == [(1.0, 2.0, 3.0)]
    with pytest.raises(BadArguments, match="a point needs 3 numbers, got 2"):
        bind(params("Part", "setPosition"), [[1, 2]], None, where)
    with pytest.raises(OutOfRange, match="coordinates lie within"):
        bind(params("Part", "setPosition"), [[1e9, 0, 0]], None, where)


def test_wrong_values_and_too_many_arguments_name_the_call_and_argument():
    where = "setAngle of c1.2"
    with pytest.raises(WrongType, match=r"setAngle of c1.2, argument 1 \(angle\): expected a number"):
        bind(params("Robot", "setAngle"), [0, "wide"], None, where)
    with pytest.raises(BadArguments, match="takes at most 2 arguments, got 3"):
        bind(params("Robot", "setAngle"), [0, 1, 2], None, where)


def test_angles_pass_as_they_came_and_references_are_resolved(scene):
    assert bind(params("Robot", "setAngles"), [0.5, -0.25], scene.get, "setAngles") == [0.5, -0.25]
    ball = Ball(scene, "c1.3")
    [parent, slot] = bind(params("Part", "attachToSlot"), [{"ref": "c1.3"}], scene.get, "attachToSlot")
    assert parent is ball and slot == 0
    with pytest.raises(UnknownObject):
        bind(params("Part", "attachToSlot"), [{"ref": "c1.9"}], scene.get, "attachToSlot")



def test_a_motor_axis_is_a_name_or_a_vector_made_unit():
    constructor = TYPES["Motor"].params
    assert bind(constructor, ["z"], None, "new Motor")[0] == "z"
    assert bind(constructor, [[0, 3, 4]], None, "new Motor")[0] == (0.0, 0.6, 0.8)
    with pytest.raises(OutOfRange, match=r"new Motor, argument 0 \(axis\): an axis needs a length"):
        bind(constructor, [[0, 0, 0]], None, "new Motor")
    with pytest.raises(WrongType, match=r"expected an axis 'x', 'y', 'z' or \[x, y, z\], got an array of 2 items"):
        bind(constructor, [[1, 0]], None, "new Motor")
    with pytest.raises(OutOfRange, match="expected an axis 'x', 'y', 'z' or"):
        bind(constructor, ["w"], None, "new Motor")


@pytest.mark.parametrize("kind", ["number", "limit", "angle", "bool", "integer", "size"])
def test_a_lone_argument_binds_as_its_kind_says_whatever_the_shortcut(kind):
    """Finite floats of the plain kinds and booleans of a bool skip the general coercion
    (an animation's every call has them): what binds, and what is refused, is the same."""
    from server.core.protocol import arguments
    from server.core.protocol.api import REQUIRED, Param
    param = Param(name="x", kind=kind, default=REQUIRED)
    for value in (0.25, -3.0, 1e300, 7, True, False, None, "NaN", "Infinity", float("inf"),
                  float("nan"), 2.0 ** 60, "x"):
        try:
            expected = arguments._coerce(param, value, None, "label")
        except Exception as error:  # noqa: BLE001 (the same kind of refusal is expected)
            expected = type(error)
        if value is None and kind != "angle":
            continue  # (a left-out argument: its default, or needed)
        try:
            found = bind([param], [value], None, "call")[0]
        except Exception as error:  # noqa: BLE001
            found = type(error)
        assert found == expected or (found != found and expected != expected), (kind, value)
        assert type(found) is type(expected)
