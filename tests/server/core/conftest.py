"""A fresh scene (with its own PyBullet world) for each core test."""

import pytest

from server.core.scene.scene import Scene


@pytest.fixture
def scene():
    s = Scene("test")
    yield s
    s.close()
