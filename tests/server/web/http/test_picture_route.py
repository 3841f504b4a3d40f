"""``GET /api/scenes/{scene}/picture`` against a real server: the scene from its camera,
as PNG or raw RGB; a size out of range is a structured 400 naming it."""

from __future__ import annotations

import io
import json
import urllib.error
import urllib.request

import numpy as np
import pytest
from PIL import Image

import virtual_prosthetics as vp
from tests.conftest import WAIT_SECONDS


def fetch(server, path: str) -> tuple[bytes, dict[str, str]]:
    with urllib.request.urlopen(server.http + path, timeout=WAIT_SECONDS) as answer:
        return answer.read(), dict(answer.headers)


def test_the_scene_is_drawn_from_its_camera_as_png_and_as_raw_rows(server, scene_name):
    with vp.connect(server.ws, scene=scene_name):
        ball = vp.Ball(1.0, "red")
        ball.set_position(0, 1, 0)
        vp.set_camera_position(0, 1, 6)
        vp.set_camera_target(0, 1, 0)
        vp.current_session().sync()
        png, headers = fetch(server, f"/api/scenes/{scene_name}/picture?width=200&height=100")
        picture = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))
        assert headers["content-type"] == "image/png" and picture.shape == (100, 200, 3)
        centre = picture[50, 100].astype(int)
        assert centre[0] > 100 and centre[1] < 40 and centre[2] < 40  # the red ball, in the middle
        assert tuple(picture[5, 5]) == (255, 255, 255)  # nothing behind it
        raw, _ = fetch(server, f"/api/scenes/{scene_name}/picture?width=200&height=100&format=rgb")
        rows = np.frombuffer(raw, np.uint8).reshape(100, 200, 3)
        assert np.array_equal(rows, picture)


def test_a_picture_it_cannot_draw_is_refused_naming_why(server, scene_name):
    with vp.connect(server.ws, scene=scene_name):
        with pytest.raises(urllib.error.HTTPError) as large:
            fetch(server, f"/api/scenes/{scene_name}/picture?width=4000")
        with pytest.raises(urllib.error.HTTPError) as gif:
            fetch(server, f"/api/scenes/{scene_name}/picture?format=gif")
    body = json.loads(large.value.read())
    assert large.value.code == 400 and body["code"] == "out_of_range" and "width" in body["message"]
    assert gif.value.code == 422 and "format" in json.loads(gif.value.read())["detail"][0]["loc"]
