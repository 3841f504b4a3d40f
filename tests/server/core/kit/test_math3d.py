"""Euler orders and pose composition against rotation matrices built independently."""

import math
import random

import pytest

from server.core.kit import math3d


def rx(a):
    c, s = math.cos(a), math.sin(a)
    return [[1, 0, 0], [0, c, -s], [0, s, c]]


def ry(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def matvec(m, v):
    return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]


@pytest.mark.parametrize("order", math3d.EULER_ORDERS)
def test_euler_order_is_intrinsic_product_of_axis_matrices(order):
    rng = random.Random(order)
    for _ in range(20):
        x, y, z = (rng.uniform(-math.pi, math.pi) for _ in range(3))
        single = {"X": rx(x), "Y": ry(y), "Z": rz(z)}
        expected = matmul(matmul(single[order[0]], single[order[1]]), single[order[2]])
        got = math3d.to_matrix(math3d.euler_to_quat(x, y, z, order))
        for row_got, row_expected in zip(got, expected):
            assert row_got == pytest.approx(row_expected, abs=1e-12)


def test_orders_differ_for_the_same_angles():
    quats = {math3d.euler_to_quat(0.3, 0.5, 0.7, order) for order in math3d.EULER_ORDERS}
    assert len(quats) == 6


def test_rotate_matches_the_matrix():
    q = math3d.euler_to_quat(0.4, -1.1, 2.0, "ZYX")
    v = (0.3, -2.0, 5.0)
    assert math3d.rotate(q, v) == pytest.approx(matvec(math3d.to_matrix(q), v))


def test_compose_places_child_in_parent_frame():
    parent = ((1.0, 2.0, 3.0), math3d.axis_angle("z", math.pi / 2))
    position, quat = math3d.compose(parent, ((1.0, 0.0, 0.0), math3d.IDENTITY))
    assert position == pytest.approx((1.0, 3.0, 3.0))  # +X turned to +Y
    assert quat == pytest.approx(parent[1])


def test_matrix_to_euler_xyz_round_trips():
    angles = (0.2, -0.7, 1.3)
    back = math3d.matrix_to_euler_xyz(math3d.to_matrix(math3d.euler_to_quat(*angles)))
    assert back == pytest.approx(angles)


def test_unknown_order_is_refused():
    with pytest.raises(ValueError):
        math3d.euler_to_quat(0, 0, 0, "XXY")


def test_between_goes_straight_and_turns_along_the_shorter_arc():
    a = ((0.0, 0.0, 0.0), math3d.axis_angle("z", 0.0))
    b = ((2.0, 4.0, -6.0), math3d.axis_angle("z", 1.0))
    assert math3d.between(a, b, 0.0) == a
    assert math3d.between(a, b, 1.0) == b  # bit for bit: a pose put again is where it was
    position, quaternion = math3d.between(a, b, 0.5)
    assert position == pytest.approx((1.0, 2.0, -3.0))
    assert quaternion == pytest.approx(math3d.axis_angle("z", 0.5), abs=1e-9)
    flipped = (b[0], tuple(-x for x in b[1]))  # the same rotation, the other sign
    assert math3d.between(a, flipped, 0.5)[1] == pytest.approx(math3d.axis_angle("z", 0.5), abs=1e-9)
    odd = ((0.1, 0.2, 0.3), (0.1, 0.7, 0.1, 0.7))  # not quite unit: normalising moves its bits
    assert math3d.between(a, odd, 1.0) == odd
