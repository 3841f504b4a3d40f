"""A fresh collision world (its own PyBullet client) for each physics test that asks."""

import pytest

from server.core.physics.engine import PhysicsWorld


@pytest.fixture
def world():
    w = PhysicsWorld()
    yield w
    w.close()
