"""PyBullet's multibody conventions, measured: where joint frames, shapes and inertial
frames sit, so that a compiled tree's parts are read where they are."""

import math

import pytest

from server.core.kit import math3d
from server.core.physics.articulation import Articulation, Joint, Link

BOX = {"kind": "box", "size": [0.2, 0.4, 0.6]}
IDENTITY_POSE = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def turned(axis, angle):
    return ((0.0, 0.0, 0.0), math3d.axis_angle(axis, angle))


def test_origins_are_in_the_parent_links_frame_and_parts_at_their_shape_frame(world):
    base = ((1.0, 2.0, 3.0), math3d.euler_to_quat(0.1, 0.2, 0.3))
    origin1, shape1 = ((0.5, 0.0, 0.2), math3d.euler_to_quat(0.3, 0, 0.1)), ((0, 0.4, 0.1), math3d.euler_to_quat(0, 0.5, 0))
    origin2, shape2 = ((0.1, 0.7, 0.0), math3d.euler_to_quat(0.2, 0.1, 0)), ((0.2, 0, 0), math3d.euler_to_quat(0, 0, 0.4))
    tree = Articulation("r", links=(
        Link(-1, origin1, Joint("m1", (0.0, 0.0, 1.0), -3, 3), "a", shape1, BOX),
        Link(0, origin2, Joint("m2", (1.0, 0.0, 0.0), -3, 3), "b", shape2, BOX)))
    world.add_tree(tree, base, {"m1": 0.7, "m2": -0.4})
    compose = math3d.compose
    link1 = compose(compose(base, origin1), turned("z", 0.7))
    link2 = compose(compose(link1, origin2), turned("x", -0.4))
    expected = [compose(link1, shape1), compose(link2, shape2)]
    keys, poses = world.part_poses("r")
    assert list(keys) == ["a", "b"]
    for (position, orientation), (want_p, want_q) in zip(poses, expected):
        assert position == pytest.approx(want_p, abs=1e-12)
        assert abs(sum(x * y for x, y in zip(orientation, want_q))) == pytest.approx(1, abs=1e-12)
    low, high = world.parts.aabb("b")  # the shape sits at the part's frame too
    centre = [(lo + hi) / 2 for lo, hi in zip(low, high)]
    assert centre == pytest.approx(list(expected[1][0]), abs=1e-9)


def test_a_trees_pose_rows_are_its_part_poses_number_for_number(world):
    tree = Articulation("r", base_part="p", base_geometry=BOX, links=(
        Link(-1, ((0.5, 0.0, 0.2), math3d.euler_to_quat(0.3, 0, 0.1)),
             Joint("m1", (0.0, 0.0, 1.0), -3, 3), "a", ((0, 0.4, 0.1), math3d.euler_to_quat(0, 0.5, 0)), BOX),
        Link(0, ((0.1, 0.7, 0.0), IDENTITY_POSE[1]), Joint("m2", (1.0, 0.0, 0.0), -3, 3), "b",
             IDENTITY_POSE, BOX)))
    world.add_tree(tree, ((1.0, 2.0, 3.0), math3d.euler_to_quat(0.1, 0.2, 0.3)), {"m1": 0.7, "m2": -0.4})
    world.turn("r", [0.2, 1.1])
    keys, rows = world.part_pose_rows("r")
    want_keys, poses = world.part_poses("r")
    assert keys == tuple(want_keys) == ("p", "a", "b")
    assert rows.tolist() == [[*position, *orientation] for position, orientation in poses]


def test_turning_sets_the_joints_and_a_rebuild_keeps_angles_and_bases(world):
    tree = Articulation("r", links=(Link(-1, ((0, 0, 0), (0, 0, 0, 1)),
                                         Joint("m", (0.0, 0.0, 1.0), -3, 3), "a",
                                         ((1, 0, 0), (0, 0, 0, 1)), BOX),))
    world.add_tree(tree, ((0, 1, 0), (0, 0, 0, 1)), {"m": 0.0})
    world.turn("r", [math.pi / 2])
    world.move_base("r", ((0, 2, 0), (0, 0, 0, 1)))
    world.rebuild()
    [(position, _)] = world.part_poses("r")[1]
    assert position == pytest.approx((0, 3, 0), abs=1e-12)  # turned a quarter about z
    assert world.rebuilds == 1 and "a" in world and len(world) == 1


def test_parts_are_read_where_the_last_change_put_them(world):
    """Bullet's link frames as each change leaves them: a base placed alone, joints set
    alone, a rebuild; each read at once."""
    origin, shape = ((0.5, 0.0, 0.2), math3d.euler_to_quat(0.3, 0, 0.1)), ((0, 0.4, 0.1), IDENTITY_POSE[1])
    tree = Articulation("r", base_part="p", base_geometry=BOX, links=(
        Link(-1, origin, Joint("m", (0.0, 0.0, 1.0), -3, 3), "a", shape, BOX),))
    base, angle = ((1.0, 2.0, 3.0), math3d.euler_to_quat(0.1, 0.2, 0.3)), 0.7
    world.add_tree(tree, base, {"m": angle})

    def read_where_expected() -> None:
        link = math3d.compose(math3d.compose(base, origin), turned("z", angle))
        want_p, want_q = math3d.compose(link, shape)
        keys, rows = world.part_pose_rows("r")
        assert keys == ("p", "a")
        assert rows[1, :3].tolist() == pytest.approx(list(want_p), abs=1e-12)
        assert abs(rows[1, 3:] @ want_q) == pytest.approx(1, abs=1e-12)
        assert world.parts.pose("a")[0] == pytest.approx(want_p, abs=1e-12)

    read_where_expected()
    base = ((-2.0, 0.5, 1.0), math3d.euler_to_quat(-0.4, 0.0, 1.2))
    world.move_base("r", base)
    read_where_expected()
    angle = -1.1
    world.turn("r", [angle])
    read_where_expected()
    world.rebuild()
    read_where_expected()


def test_parts_of_one_tree_are_measured_against_each_other(world):
    tree = Articulation("r", "base", BOX, links=(
        Link(-1, ((0.1, 0, 0), (0, 0, 0, 1)), None, "near", ((0, 0, 0), (0, 0, 0, 1)), BOX),
        Link(-1, ((5.0, 0, 0), (0, 0, 0, 1)), None, "far", ((0, 0, 0), (0, 0, 0, 1)), BOX)))
    world.add_tree(tree, ((0, 5, 0), (0, 0, 0, 1)), {})
    assert world.parts.touching_many("base", ["near", "far"]) == [True, False]
    world.remove_tree("r")
    assert len(world) == 0 and "near" not in world
