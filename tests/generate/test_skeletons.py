"""The hands' skeletons the JS client predicts new hands from (their drift: test_generated)."""

from generate import skeletons
from server.core.model.hands import Hand
from server.core.scene.scene import Scene


def test_every_hand_type_has_a_skeleton_of_each_side_with_all_its_nodes():
    assert {cls.type_name for cls in skeletons.HANDS} == {cls.type_name for cls in _hand_classes()}
    scene = Scene("count")
    try:
        for cls in skeletons.HANDS:
            for is_left in (True, False):
                hand = cls(scene, f"{cls.type_name}-{is_left}", is_left)
                nodes = skeletons.skeleton(cls, is_left)
                assert len(nodes) == sum(1 for _ in hand.walk()) - 1
                motors = [suffix for suffix, kind, _, _ in nodes if kind.startswith("Motor")]
                assert [f"{hand.id}{suffix}" for suffix in motors] == hand.motors, "depth first"
    finally:
        scene.close()


def test_a_left_hand_is_not_a_right_hand():
    for cls in skeletons.HANDS:
        left, right = skeletons.skeleton(cls, True), skeletons.skeleton(cls, False)
        assert [n[:3] for n in left] == [n[:3] for n in right]
        assert left != right, f"{cls.type_name}: sides differ in flips and poses"


def _hand_classes() -> list[type[Hand]]:
    found, todo = [], [Hand]
    while todo:
        for sub in todo.pop().__subclasses__():
            found.append(sub)
            todo.append(sub)
    return found
