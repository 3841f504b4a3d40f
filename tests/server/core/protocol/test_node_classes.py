"""The class of each type a client may make, by its manual name."""

from server.core.protocol import api
from server.core.protocol.node_classes import NODE_CLASSES


def test_every_creatable_type_has_a_class_and_every_class_a_type():
    creatable = {name for name, spec in api.TYPES.items() if spec.creatable}
    assert creatable == set(NODE_CLASSES)
    assert all(cls.type_name == name for name, cls in NODE_CLASSES.items())
