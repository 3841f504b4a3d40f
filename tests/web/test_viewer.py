"""The viewer in real headless Chromium: many pages follow one scene, and show it right."""

from __future__ import annotations

import math

import pytest

import virtual_prosthetics as vp
from tests.conftest import start_server, stop_server

from .conftest import open_page, open_viewer, red_box_on_a_motor, wait_until
from .picture import DEFAULT_CAMERA, Picture, background_like, project, reddish

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first


def settled(page, motor_id, angle):
    """Wait until a page has drawn a motor at ``angle``."""
    wait_until(page, "([id, a]) => Math.abs(VP.shownAngle(id) - a) < 1e-9 && VP.drawn()",
               [motor_id, angle])


def test_three_viewers_follow_a_script_and_draw_the_robot_where_the_server_has_it(
        browser, pages, server, scene, scene_name):
    robot, motor, box = red_box_on_a_motor()
    scene.sync()
    viewers = [open_viewer(browser, pages, server, f"scene={scene_name}") for _ in range(3)]
    for page in viewers:
        wait_until(page, "(id) => VP.objects.has(id)", box.id)
        settled(page, motor.id, 0.0)
    upright = Picture(viewers[0].screenshot())
    standing = project((0, 0.5, 0), *DEFAULT_CAMERA, upright.size)
    assert reddish(upright.at(standing))

    motor.set_angle(-1.0)  # about Z: the box leans towards +X
    for page in viewers:
        wait_until(page, "(id) => VP.angle(id) === -1", motor.id)
    report = server.get(f"/api/scenes/{scene_name}/robots/{robot.id}")
    [box_now] = [part["world"]["position"] for part in report["parts"] if part["id"] == box.id]
    assert box_now == pytest.approx([0.5 * math.sin(1), 0.5 * math.cos(1), 0])
    angles = [page.evaluate("(id) => VP.angle(id)", motor.id) for page in viewers]
    assert angles == [-1.0, -1.0, -1.0]
    wait_until(viewers[0], "() => document.getElementById('status').textContent"
                           ".endsWith('3 viewers · 1 controller')")
    for page in viewers:
        settled(page, motor.id, -1.0)
        picture = Picture(page.screenshot())
        leaning = project(box_now, *DEFAULT_CAMERA, picture.size)  # where the server has the box
        assert reddish(picture.at(leaning)), picture.at(leaning)
        assert background_like(picture.at(standing)), picture.at(standing)


def test_an_empty_scene_shows_the_spinning_logo_until_something_comes(
        browser, pages, server, scene, scene_name):
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(page, "() => VP.scene.getObjectByName('logo').visible")
    picture = Picture(page.screenshot())
    assert picture.share(lambda c: not background_like(c)) > 0.01  # the logo, not a blank
    vp.Ball(0.5).set_position(0, 0.5, 0)
    wait_until(page, "() => !VP.scene.getObjectByName('logo').visible")


def test_the_camera_follows_the_script_and_still_orbits(browser, pages, server, scene,
                                                       scene_name):
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    vp.set_camera_position(1, 2, 10)
    vp.set_camera_target(0, 0.5, 0)
    wait_until(page, "() => Math.abs(VP.camera.position.z - 10) < 1e-6")
    assert page.evaluate("() => VP.camera.position.toArray()") == pytest.approx([1, 2, 10])
    page.mouse.move(400, 250)
    page.mouse.down()
    page.mouse.move(300, 250, steps=5)
    page.mouse.up()
    wait_until(page, "() => Math.abs(VP.camera.position.x - 1) > 0.1")  # a person orbited


def test_frame_all_brings_what_the_scene_holds_into_view(browser, pages, server, scene,
                                                         scene_name):
    """Found: a task's scene opened cropped (the hand half out of view, a wall in front).
    "Frame all" (the button, or F) fits everything in, centred, from where the camera looks."""
    far = vp.Box(1, 1, 1, "red")
    far.set_position(25, 0.5, -12)  # out of the default camera's view
    vp.Ball(0.3).set_position(-2, 0.3, 0)
    vp.set_camera_position(*DEFAULT_CAMERA[0])  # placed by the script: kept on opening
    scene.sync()
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(page, "(id) => VP.objects.has(id) && VP.drawn()", far.id)
    assert Picture(page.screenshot()).share(lambda c: reddish(c)) == 0
    page.keyboard.press("f")
    wait_until(page, "() => VP.drawn()")
    target = page.evaluate("() => VP.camera.position.toArray()")
    red = Picture(page.screenshot()).share(lambda c: reddish(c))
    assert red > 0.0005  # the far box is in the picture now
    vp.set_camera_position(4, 4, 7.5)  # the scene's camera moves every viewer again
    vp.set_camera_position(*DEFAULT_CAMERA[0])
    wait_until(page, "() => Math.abs(VP.camera.position.z - 7) < 1e-9")
    page.get_by_role("button", name="Frame all").click()
    wait_until(page, "() => VP.drawn()")
    assert page.evaluate("() => VP.camera.position.toArray()") == pytest.approx(target, abs=1e-6)


def test_a_viewer_frames_what_a_scene_holds_when_no_script_placed_the_camera(
        browser, pages, server, scene, scene_name):
    """Found: a task's scene opened cropped. A camera nobody placed frames everything
    when something is out of view, on opening, as things are added and once they have
    moved, until a person orbits; a scene that fits stays in the manual's view."""
    vp.Ball(0.3).set_position(-2, 0.3, 0)
    scene.sync()
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(page, "() => VP.objects.size === 1 && VP.drawn()")
    assert page.evaluate("() => VP.camera.position.toArray()") == pytest.approx(DEFAULT_CAMERA[0])
    far = vp.Box(1, 1, 1, "red")
    scene.sync()
    wait_until(page, "(id) => VP.objects.has(id) && VP.drawn()", far.id)  # made in view
    far.set_position(25, 0.5, -12)  # then moved out of it (found: not framed then)
    scene.sync()
    wait_until(page, "(id) => VP.objects.get(id).position.x === 25 && VP.drawn()", far.id)
    assert Picture(page.screenshot()).share(lambda c: reddish(c)) > 0.0005
    other = open_viewer(browser, pages, server, f"scene={scene_name}")  # framed on opening
    wait_until(other, "() => VP.objects.size === 2 && VP.drawn()")
    assert Picture(other.screenshot()).share(lambda c: reddish(c)) > 0.0005


def test_a_scripts_caption_shows_in_a_corner_of_every_viewer(browser, pages, server, scene,
                                                             scene_name):
    vp.set_caption("grasp edged · 1.5 of 96 scene-s\nspherical · trials 1-10 of 20")
    scene.sync()
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    caption = page.locator("#caption")
    wait_until(page, "() => !document.getElementById('caption').hidden")
    assert caption.inner_text() == ("grasp edged · 1.5 of 96 scene-s\n"
                                    "spherical · trials 1-10 of 20")
    box, size = caption.bounding_box(), page.viewport_size  # the bottom-right corner
    assert box["x"] + box["width"] > size["width"] - 20
    assert box["y"] + box["height"] > size["height"] - 20
    vp.set_caption("")
    wait_until(page, "() => document.getElementById('caption').hidden")


def test_viewers_come_back_after_a_server_restart(browser, pages):
    own = start_server("--no-demo")
    try:
        page = open_viewer(browser, pages, own, "scene=default")
        client = vp.Session(own.ws)
        robot = vp.Robot(scene=client)
        robot.attach_chain(vp.MotorZ(scene=client), vp.Box(scene=client))
        robot.add_gui("Before")
        client.sync()
        wait_until(page, "() => document.querySelectorAll('.lil-gui').length === 1")
        stop_server(own)
        wait_until(page, "() => document.getElementById('status').textContent"
                         ".startsWith('reconnecting')")
        own = start_server("--no-demo", port=own.port)
        wait_until(page, "() => VP.snapshots >= 2")
        wait_until(page, "() => document.getElementById('status').textContent"
                         ".startsWith('connected')")
        assert page.evaluate("() => VP.objects.size") == 0  # the fresh server's scene
        assert page.evaluate("() => document.querySelectorAll('.lil-gui').length") == 0
        client.close()
    finally:
        stop_server(own)


def test_deleted_objects_free_their_gpu_memory(browser, pages, server, scene, scene_name):
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(page, "() => VP.rendered > 0 && VP.drawn()")
    before = page.evaluate("() => VP.renderer.info.memory.geometries")
    boxes = [vp.Box(0.2, 0.2, 0.2) for _ in range(20)]
    for k, box in enumerate(boxes):
        box.set_position(k * 0.3 - 3, 0.1, 0)
    scene.sync()
    wait_until(page, "(n) => VP.objects.size === 20 && VP.renderer.info.memory.geometries > n",
               before)
    for box in boxes:
        box.delete()
    wait_until(page, "(n) => VP.objects.size === 0 && VP.renderer.info.memory.geometries === n",
               before)


def test_an_unavailable_engine_is_named_in_the_status_line(browser, pages, server):
    page = open_page(browser, pages, f"{server.http}/view?scene=default&engine=cannon")
    wait_until(page, "() => document.getElementById('status').textContent.startsWith('refused')")
    assert "this server runs pybullet" in page.inner_text("#status")


def test_the_status_line_says_when_a_script_holds_the_scenes_clock(browser, pages, server,
                                                                   scene, scene_name):
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    vp.Ball(0.5)
    scene.pause()
    wait_until(page, "() => document.getElementById('status').textContent.includes('paused')")
    scene.resume()
    wait_until(page, "() => !document.getElementById('status').textContent.includes('paused')")
