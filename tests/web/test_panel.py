"""Motor panels: addGUI in a script shows sliders in every viewer; a controller's move them."""

from __future__ import annotations

import time

import pytest

import virtual_prosthetics as vp

from tests.conftest import WAIT_SECONDS
from .conftest import open_viewer, wait_until

SLIDER_INPUTS = "() => [...document.querySelectorAll('.lil-gui .lil-controller.lil-number input')]"


@pytest.fixture
def arm(server, scene_name):
    scene = vp.connect(server.ws, scene=scene_name)
    robot = vp.Robot()
    robot.attach_chain(vp.MotorZ(-1, 1).set_name("shoulder"), vp.EdgedFinger(),
                       vp.MotorX(-2, 2), vp.EdgedTip())
    robot.add_gui("Arm")
    robot.share()  # a controller page may move it
    scene.sync()
    yield robot
    scene.close()


def test_a_controller_moves_motors_and_every_viewer_follows(browser, pages, server,
                                                            scene_name, arm):
    controller = open_viewer(browser, pages, server, f"scene={scene_name}&role=controller")
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}")
    for page in (controller, viewer):
        wait_until(page, "() => document.querySelector('.lil-gui .lil-title')?.textContent === 'Arm'")
        labels = page.evaluate("() => [...document.querySelectorAll('.lil-gui .lil-controller.lil-number "
                               ".lil-name')].map((e) => e.textContent)")
        assert labels == ["shoulder", "1"]  # a name when set, else the motor's index
    assert viewer.evaluate(f"() => ({SLIDER_INPUTS})().every((input) => input.disabled)")
    assert not controller.evaluate(f"() => ({SLIDER_INPUTS})()[1].disabled")

    field = controller.locator(".lil-gui .lil-controller.lil-number input").nth(1)
    field.fill("0.5")
    field.press("Enter")
    motor_id = arm.get_motors()[1].id
    wait_until(viewer, "(id) => VP.angle(id) === 0.5", motor_id)
    deadline = time.monotonic() + WAIT_SECONDS    # the script hears it with its own next frame
    while arm.get_angles() != [0, 0.5] and time.monotonic() < deadline:
        time.sleep(0.05)
    assert arm.get_angles() == [0, 0.5]  # the server has it
    wait_until(viewer, f"() => ({SLIDER_INPUTS})()[1].value === '0.5'")

    viewer.get_by_text("Get gesture").click()
    wait_until(viewer, "() => !document.getElementById('gesture').hidden")
    assert viewer.inner_text("#gesture") == "setAngles( 0, 0.5 );"


TITLES = "() => [...document.querySelectorAll('.lil-gui.lil-root > .lil-title')].map((e) => e.textContent)"


def test_a_controller_view_has_a_panel_for_every_robot_a_viewer_for_addguis(browser, pages, server,
                                                                           scene_name):
    """Found: `/view?scene=default&role=controller` showed no motor panels (no demo robot
    called addGUI). A controller's view has one for every robot with motors, in one column,
    closed when there are more than two; a viewer's only for robots that called addGUI."""
    with vp.Session(server.ws, scene=scene_name) as client:
        robots = []
        for k in range(3):
            robot = vp.Robot(scene=client)
            robot.attach_chain(vp.MotorZ(scene=client).set_name(f"m{k}"))
            robots.append(robot)
        vp.Robot(scene=client)  # no motors: no panel
        client.sync()
        viewer = open_viewer(browser, pages, server, f"scene={scene_name}")
        wait_until(viewer, "(id) => VP.objects.has(id) && VP.drawn()", robots[-1].id)
        assert viewer.evaluate("() => document.querySelectorAll('.lil-gui').length") == 0
        page = open_viewer(browser, pages, server, f"scene={scene_name}&role=controller")
        wait_until(page, f"() => ({TITLES})().length === 3")
        assert sorted(page.evaluate(TITLES)) == sorted(r.id for r in robots)
        assert page.evaluate("() => [...document.querySelectorAll('#motor-panels > .lil-gui')]"
                             ".every((gui) => gui.classList.contains('lil-closed'))")
        tops = page.evaluate("() => [...document.querySelectorAll('#motor-panels > .lil-gui')]"
                             ".map((gui) => gui.getBoundingClientRect().top)")
        assert len(set(tops)) == 3  # stacked, not over each other
        robots[0].add_gui("Late")
        wait_until(viewer, "() => document.querySelector('.lil-gui .lil-title')?.textContent === 'Late'")
        wait_until(page, f"() => ({TITLES})().includes('Late')")


def test_a_controller_page_cannot_steer_a_robot_not_shared(browser, pages, server, scene_name):
    """Its panel is read-only, as a viewer's is, until the owner shares the robot."""
    with vp.Session(server.ws, scene=scene_name) as client:
        robot = vp.Robot(scene=client)
        robot.attach_chain(vp.MotorZ(-1, 1, scene=client))
        robot.add_gui("Mine")
        client.sync()
        page = open_viewer(browser, pages, server, f"scene={scene_name}&role=controller")
        wait_until(page, "() => document.querySelector('.lil-gui .lil-title')?.textContent === 'Mine'")
        assert page.evaluate(f"() => ({SLIDER_INPUTS})().every((input) => input.disabled)")
        robot.share()
        client.sync()
        wait_until(page, f"() => !({SLIDER_INPUTS})()[0].disabled")
