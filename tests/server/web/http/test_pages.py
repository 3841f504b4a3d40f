"""The pages' routes: the viewer's files and its npm dependencies, and nothing else."""

from __future__ import annotations

import http.client

import pytest

from tests.conftest import WAIT_SECONDS



def raw_get(server, path):
    """GET a path exactly as written (no client-side normalisation of '..')."""
    connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=WAIT_SECONDS)
    connection.request("GET", path)
    response = connection.getresponse()
    return response.status, response.getheader("content-type"), response.read()


@pytest.mark.parametrize("path, kind", [
    ("/view", "text/html"), ("/web/viewer/main.js", "javascript"),
    ("/vendor/three/build/three.module.js", "javascript"),
    ("/vendor/three/examples/jsm/controls/OrbitControls.js", "javascript"),
    ("/vendor/lil-gui/dist/lil-gui.esm.js", "javascript"),
])
def test_the_viewer_and_its_dependencies_are_served(server, path, kind):
    status, content_type, _ = raw_get(server, path)
    assert status == 200 and kind in content_type


@pytest.mark.parametrize("path", ["/web/../../pyproject.toml", "/vendor/three/../../../Makefile",
                                  "/web/%2e%2e/%2e%2e/server/cli.py", "/web/nothing.js"])
def test_nothing_outside_the_served_folders_is_reachable(server, path):
    status, _, body = raw_get(server, path)
    assert status == 404 and b"vp-server" not in body
