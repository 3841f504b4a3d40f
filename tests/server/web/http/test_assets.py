"""Mesh files over HTTP against a real server: uploads checked and kept by hash, served back,
and every path that points elsewhere refused."""

from __future__ import annotations

import hashlib
import http.client
import json
import os
import time

import pytest
import trimesh

import virtual_prosthetics as vp
from tests.conftest import WAIT_SECONDS, eventually, start_server, stop_server
from tests.features.fuzz.gltf_files import glb_parts, pack_glb, peak_megabytes

SMALL = ["--limit", "assetBytes=200000", "--limit", "assetTriangles=5000", "--limit", "assets=3"]


@pytest.fixture(scope="module")
def small_server():
    """A server whose upload limits are small enough to reach."""
    running = start_server("--no-demo", *SMALL)
    yield running
    stop_server(running)


def request(server, method: str, path: str, body: bytes | None = None) -> tuple[int, dict, bytes]:
    """The raw status, headers and body (the path is sent exactly as given)."""
    connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=WAIT_SECONDS)
    try:
        connection.request(method, path, body=body,
                           headers={"Content-Type": "application/octet-stream"})
        answer = connection.getresponse()
        return answer.status, dict(answer.getheaders()), answer.read()
    finally:
        connection.close()


def glb(subdivisions: int = 1, radius: float = 0.3) -> bytes:
    return trimesh.creation.icosphere(subdivisions, radius).export(file_type="glb")


def test_an_upload_is_kept_under_its_hash_and_served_back(small_server):
    data = glb()
    status, _, body = request(small_server, "POST", "/api/assets", data)
    stored = json.loads(body)
    name = hashlib.sha256(data).hexdigest()[:32] + ".glb"
    assert status == 201 and stored == {"name": name, "url": f"/api/assets/{name}",
                                        "bytes": len(data), "triangles": 80}
    assert request(small_server, "POST", "/api/assets", data)[2] == body  # the same file once
    assert name in small_server.get("/api/assets")["uploaded"]
    assert "round-palm.glb" in small_server.get("/api/assets")["bundled"]
    status, headers, served = request(small_server, "GET", f"/api/assets/{name}")
    assert status == 200 and served == data and headers["content-type"] == "model/gltf-binary"


def test_a_gltf_with_embedded_buffers_is_taken(small_server):
    files = trimesh.creation.box().export(file_type="gltf", embed_buffers=True)
    document = files["model.gltf"]
    assert b"data:" in document
    status, _, body = request(small_server, "POST", "/api/assets", document)
    assert status == 201 and json.loads(body)["name"].endswith(".gltf")


def refused(server, body: bytes, status: int, code: str, words: str) -> None:
    before = server.get("/api/assets")["uploaded"]
    got, _, answer = request(server, "POST", "/api/assets", body)
    error = json.loads(answer)
    assert (got, error["code"]) == (status, code) and words in error["message"], error
    assert server.get("/api/assets")["uploaded"] == before  # nothing kept


def test_oversize_files_are_refused_unread(small_server):
    refused(small_server, b"glTF" + bytes(300_000), 413, "too_large", "more than 200000 bytes")


@pytest.mark.parametrize("body, words", [
    (b"hello, not a mesh", "neither GLB nor glTF"),
    (b"glTF" + bytes(40), "a GLB of version 0"),
    (json.dumps({"hello": 1}).encode(), "no 'asset'"),
    (json.dumps({"asset": {"version": "2.0"}, "buffers": [{"uri": "../../etc/passwd",
                                                           "byteLength": 10}]}).encode(),
     "refers to '../../etc/passwd'"),
    (json.dumps({"asset": {"version": "2.0"}, "images": [{"uri": "http://example.com/a.png"}]}).encode(),
     "refers to 'http://example.com/a.png'"),
    (json.dumps({"asset": {"version": "2.0"}}).encode(), "no triangles"),
])
def test_files_that_are_not_usable_gltf_meshes_are_refused(small_server, body, words):
    refused(small_server, body, 400, "bad_asset", words)


def test_a_glb_whose_data_is_broken_is_refused(small_server):
    data = bytearray(glb())
    data[-200:] = bytes(200)  # binary chunk wiped: indices point nowhere
    status, _, answer = request(small_server, "POST", "/api/assets", bytes(data))
    assert status in (201, 400)  # zeros may still be a (degenerate) mesh; never a crash
    assert small_server.get("/api/health")["status"] == "ok"


def test_too_many_triangles_are_refused(small_server):
    refused(small_server, glb(subdivisions=4), 429, "limit_exceeded", "at most 5000")


def test_the_number_of_files_kept_is_limited(small_server):
    kept = len(small_server.get("/api/assets")["uploaded"])
    for k in range(3 - kept):
        assert request(small_server, "POST", "/api/assets", glb(1, 0.1 + 0.01 * k))[0] == 201
    refused(small_server, glb(1, 0.5), 429, "limit_exceeded", "at most 3 uploaded files")


FORBIDDEN = ["/api/assets/../../etc/passwd", "/api/assets/%2e%2e/%2e%2e/etc/passwd",
             "/api/assets/..%2f..%2fserver%2fcli.py", "/api/assets/%2fetc%2fpasswd",
             "/api/assets//etc/passwd", "/api/assets/http:%2f%2fexample.com%2fx.glb",
             "/api/assets/x.glb%00.txt", "/api/assets/..%5c..%5cserver%5ccli.py",
             "/api/assets/%252e%252e%252fetc%252fpasswd"]


@pytest.mark.parametrize("path", FORBIDDEN)
def test_paths_that_point_elsewhere_are_refused(server, path):
    status, _, body = request(server, "GET", path)
    error = json.loads(body)
    assert (status, error["code"]) == (403, "forbidden") and "is not allowed" in error["message"]


@pytest.mark.parametrize("path", ["/assets/gltf/../../server/cli.py", "/assets/gltf/..%2f..%2fserver%2fcli.py",
                                  "/assets/gltf/%2e%2e/%2e%2e/etc/passwd", "/assets/gltf//etc/passwd"])
def test_the_bundled_folder_serves_nothing_outside_it(server, path):
    status, _, body = request(server, "GET", path)
    assert status == 404 and b"argparse" not in body and b"root:" not in body


def test_an_unknown_upload_name_is_not_found(server):
    status, _, body = request(server, "GET", "/api/assets/" + "0" * 32 + ".glb")
    assert status == 404 and json.loads(body)["code"] == "unknown_asset"


def test_a_full_upload_folder_makes_room_from_what_no_scene_uses(tmp_path):
    """With as many files as the limit allows, an upload removes the old ones that no
    running or saved scene is made of; used and recent ones stay."""
    state = tmp_path / "state"
    server = start_server("--no-demo", "--state-dir", str(state), *SMALL,
                          "--limit", "sceneIdleSeconds=1", "--limit", "leaveGraceSeconds=1")

    def upload(data: bytes) -> tuple[int, dict]:
        status, _, body = request(server, "POST", "/api/assets", data)
        return status, json.loads(body)

    def age_every_upload() -> None:
        hours_ago = time.time() - 7200
        for path in (state / "assets").iterdir():
            os.utime(path, (hours_ago, hours_ago))

    try:
        live, saved, spare, new, newer = (glb(1, 0.1 + 0.02 * k) for k in range(5))
        live, saved, spare = (upload(data)[1]["name"] for data in (live, saved, spare))
        with vp.connect(server.ws, scene="stored") as script:
            vp.GLTFPart(saved).keep()
            script.sync()
        # stopped when idle: its part is in its file only
        eventually(lambda: "stored" not in [s["name"] for s in server.get("/api/scenes")], 20)
        with vp.connect(server.ws, scene="running") as script:
            vp.GLTFPart(live)
            script.sync()
            age_every_upload()
            status, stored = upload(new)
            assert status == 201
            assert sorted(server.get("/api/assets")["uploaded"]) == sorted([live, saved, stored["name"]])
            age_every_upload()
            assert upload(new)[0] == 201  # uploaded again: recent again
            status, refusal = upload(newer)
            assert status == 429 and "used by a scene or uploaded in the last 60 minutes" \
                in refusal["message"]
        document = json.loads(request(server, "GET", "/api/scenes/stored/export")[2])
        assert [asset["name"] for asset in document["assets"]] == [saved]
    finally:
        stop_server(server)


def test_a_small_file_that_expands_to_millions_of_triangles_costs_the_server_nothing():
    document, rest = glb_parts(glb(subdivisions=5, radius=1.0))  # 20 480 triangles
    document["nodes"] = [{"mesh": 0} for _ in range(1000)]
    document["scenes"] = [{"nodes": list(range(1000))}]
    bomb = pack_glb(document, rest)
    assert len(bomb) < 400_000
    server = start_server("--no-demo")  # the default limits
    try:
        for _ in range(3):
            refused(server, bomb, 429, "limit_exceeded", "make 20480000 triangles")
        assert peak_megabytes(server.process.pid) < 500  # loaded, it took 2.6 GB
    finally:
        stop_server(server)


def test_a_mesh_whose_indices_point_past_its_vertices_is_refused(small_server):
    document, rest = glb_parts(glb())
    indices = document["accessors"][document["meshes"][0]["primitives"][0]["indices"]]
    start = 8 + document["bufferViews"][indices["bufferView"]].get("byteOffset", 0)
    data = bytearray(rest)
    data[start:start + 4] = (5000).to_bytes(4, "little")
    refused(small_server, pack_glb(document, bytes(data)), 400, "bad_asset",
            "index 5000 points past its 42 vertices")
