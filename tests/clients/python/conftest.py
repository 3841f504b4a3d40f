"""The Python client connected to a fresh scene of the test server (the current scene)."""

import pytest

import virtual_prosthetics as vp


@pytest.fixture
def scene(server, scene_name):
    connected = vp.connect(server.ws, scene=scene_name)
    yield connected
    connected.close()
