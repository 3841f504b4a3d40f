"""Mesh parts in the viewer: an uploaded GLB is drawn where the part is, in its own colours,
and a recolour shows in every viewer, including one that joins later."""

from __future__ import annotations

import numpy as np
import trimesh

import virtual_prosthetics as vp

from .conftest import open_viewer, wait_until
from .picture import Picture, project

CAMERA = ((0, 1.5, 4), (0, 1, 0))
LOADED = """(id) => { const o = VP.objects.get(id); let n = 0;
                      o?.traverse((c) => { if (c.isMesh && c.geometry.getAttribute('color')) n++; });
                      return n > 0 && VP.drawn(); }"""


def coloured_ball(rgb) -> bytes:
    ball = trimesh.creation.icosphere(3, 0.5)
    ball.visual.vertex_colors = np.tile([*[int(255 * c) for c in rgb], 255], (len(ball.vertices), 1))
    return ball.export(file_type="glb")


def near(colour, wanted, tolerance=60):
    return all(abs(c - w) < tolerance for c, w in zip(colour, wanted))


def greenish(colour):
    r, g, b = colour
    return g > 90 and g > 1.5 * r and g > 1.5 * b


def blueish(colour):
    r, g, b = colour
    return b > 90 and b > 1.5 * r and b > 1.2 * g


def green_ball_in_view(scene) -> vp.GLTFPart:
    """An uploaded green ball at (0, 1, 0), in the middle of the camera's picture."""
    part = vp.GLTFPart(vp.upload_asset(coloured_ball((0.1, 0.8, 0.1))), 0, callback=lambda p: None)
    part.set_position(0, 1, 0)
    vp.set_camera_position(*CAMERA[0])
    vp.set_camera_target(*CAMERA[1])
    scene.sync()
    return part


def test_an_uploaded_glb_is_drawn_and_recoloured_in_every_viewer(browser, pages, server, scene, scene_name):
    part = green_ball_in_view(scene)
    first = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(first, LOADED, part.id)
    picture = Picture(first.screenshot())
    centre = project((0, 1, 0), *CAMERA, picture.size)
    assert greenish(picture.at(centre)), picture.at(centre)
    assert not greenish(picture.at(project((1.2, 1, 0), *CAMERA, picture.size)))  # beside it

    part.recolor([0.1, 0.8, 0.1], "blue", 0.05)
    scene.sync()
    later = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(later, LOADED, part.id)
    for page in (first, later):
        wait_until(page, "(id) => VP.objects.get(id).userData.node.recolors?.length === 1 "
                         "&& VP.drawn()", part.id)
        assert blueish(Picture(page.screenshot()).at(centre))


TRIANGLES = """(id) => { let n = 0; VP.objects.get(id).traverse((c) => {
                 if (c.isMesh && c.geometry.getAttribute('color')) n += c.geometry.index.count / 3; });
               return n; }"""
# hold the viewer at one drawing level, as ?quality= holds one (quality.js LEVELS: 0 full,
# 4 lower); conftest.LEVEL is the query the tests' viewers open with
HOLD_LEVEL = "(index) => { const q = VP.quality; q.held = true; q.index = index; q.apply(q.level); }"
FULL, LOWER = 0, 4


def test_coarse_levels_draw_mesh_files_simplified_in_the_same_place_and_colours(
        browser, pages, server, scene, scene_name):
    """Software WebGL spends its time on triangles: coarse levels draw a mesh file with
    fewer, and the part still looks the same colour in the same place, recolours included."""
    part = green_ball_in_view(scene)
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(page, LOADED, part.id)
    page.evaluate(HOLD_LEVEL, FULL)
    full = page.evaluate(TRIANGLES, part.id)
    assert full == 1280                                    # the icosphere as uploaded
    page.evaluate(HOLD_LEVEL, LOWER)
    assert page.evaluate(TRIANGLES, part.id) < full / 2
    centre = project((0, 1, 0), *CAMERA, Picture(page.screenshot()).size)
    wait_until(page, "() => VP.drawn()")
    assert greenish(Picture(page.screenshot()).at(centre))
    part.recolor([0.1, 0.8, 0.1], "blue", 0.05)
    scene.sync()
    wait_until(page, "(id) => VP.objects.get(id).userData.node.recolors?.length === 1 && VP.drawn()", part.id)
    assert blueish(Picture(page.screenshot()).at(centre))
    page.evaluate(HOLD_LEVEL, FULL)                            # back in full, in the new colour
    assert page.evaluate(TRIANGLES, part.id) == full
    wait_until(page, "() => VP.drawn()")
    assert blueish(Picture(page.screenshot()).at(centre))
