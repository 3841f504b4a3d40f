"""1.0 pages (web/examples, only the import line changed) in headless Chromium: their
robots appear on the server and move, and a second browser watching the scene sees them."""

from __future__ import annotations

import contextlib
import json
import math
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import WAIT_SECONDS, free_port

from .conftest import CALM, open_page, open_viewer, wait_until

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first

EXAMPLES = Path(__file__).resolve().parents[2] / "web" / "examples"
ASSETS = EXAMPLES.parents[1] / "assets" / "gltf"


def _angles(server, scene: str) -> list[float]:
    return [n["angle"] for n in server.nodes(scene) if n["type"].startswith("Motor")]


def _moves(server, scene: str, expected: bool) -> bool:
    """Whether the scene's motor angles change. An animated page gets 20 s (its first
    picture in software WebGL can hold the page's loop for seconds); a static one 1 s."""
    first = _angles(server, scene)
    deadline = time.monotonic() + (20 if expected else 1)
    while _angles(server, scene) == first and time.monotonic() < deadline:
        time.sleep(0.2)
    return _angles(server, scene) != first


def _yaw(quaternion: list[float]) -> float:
    """The turn about y of a rotation about y alone."""
    x, y, z, w = quaternion
    assert abs(x) < 1e-9 and abs(z) < 1e-9, quaternion
    return 2 * math.atan2(y, w)


def _wait_for_robots(server, scene: str, count: int) -> None:
    deadline = time.monotonic() + WAIT_SECONDS
    while time.monotonic() < deadline:
        if len(server.robots(scene)) == count:
            return
        time.sleep(0.2)
    raise AssertionError(f"{count} robots never appeared in {scene}: "
                         f"{[n['type'] for n in server.nodes(scene)]}")



def _seen_by_a_viewer(browser, pages, server, scene: str) -> None:
    """A second browser watching the scene holds every node the server has, meshes drawn."""
    ids = [n["id"] for n in server.nodes(scene)]
    viewer = open_viewer(browser, pages, server, f"scene={scene}&{CALM}")
    wait_until(viewer, "(ids) => ids.every((id) => VP.objects.has(id))", ids)
    meshes = [i for i, n in _meshes(server, scene).items() if n["visible"]]
    wait_until(viewer, "(ids) => ids.every((id) => VP.objects.get(id).userData.shape)", meshes)


@pytest.mark.parametrize("example, robots, moving", [
    ("simple-robot-2", 1, False), ("simple-robot-3", 1, True), ("simple-robot-4", 1, True),
    ("two-hands", 2, True), ("two-hands?hand=RoundHand", 2, True),
    ("two-hands?hand=AnthroHand", 2, True)])
def test_an_example_page_builds_its_robot_on_the_server(browser, pages, server, scene_name,
                                                        example, robots, moving):
    page, _, query = example.partition("?")
    open_page(browser, pages, f"{server.http}/examples/{page}.html?scene={scene_name}&{query}&{CALM}")
    _wait_for_robots(server, scene_name, robots)
    assert _moves(server, scene_name, moving) == moving
    if page == "two-hands":
        hands = sorted(server.robots(scene_name), key=lambda n: n["position"][0])
        assert [n["position"][0] for n in hands] == [-2, 2]
        # chained as 1.0 pages chain them, the right one's z left out
        assert [round(_yaw(n["quaternion"]), 6) for n in hands] == [0.3, -0.3]
        assert {n["type"] for n in hands} == {query.partition("=")[2] or "EdgedHand"}
        _seen_by_a_viewer(browser, pages, server, scene_name)


@pytest.fixture
def own_folder(tmp_path):
    """A user's own folder of pages, served by ``python3 -m http.server`` on another
    loopback port (its pages import the client from the server by its full address)."""
    port = free_port()
    process = subprocess.Popen([sys.executable, "-m", "http.server", str(port), "--bind",
                                "127.0.0.1"], cwd=tmp_path, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + WAIT_SECONDS
        while time.monotonic() < deadline:
            with contextlib.suppress(OSError), socket.create_connection(("127.0.0.1", port)):
                break
            time.sleep(0.05)
        yield tmp_path, f"http://127.0.0.1:{port}"
    finally:
        process.kill()
        process.wait()


# what robot-reads.html prints: 1.0's answers, read in the same task as the building
READS = ["crane: 4 motors, 8 parts", "crane angle 0 after setAngles(5, 5, 5, 5): 1",
         "crane at -0.3, 0, 0", "hand: 20 motors, 36 parts"]


def check_reads_page_robots(server, scene: str) -> None:
    """The crane and the hand of robot-reads.html are where its calls put them, and move."""
    _wait_for_robots(server, scene, 2)
    crane, hand = sorted(server.robots(scene), key=lambda n: n["type"] != "Robot")
    assert crane["position"] == [-0.3, 0, 0]        # y and z left out: kept
    assert round(abs(_yaw(crane["quaternion"])), 9) == round(math.pi, 9)   # z left out
    names = {n["id"]: n.get("name") for n in server.nodes(scene)}
    assert [names[m] for m in crane["motors"]] == [f"joint {i}" for i in range(4)]
    assert hand["position"] == [2, 0.5, 0] and hand["type"] == "EdgedHand"
    assert _moves(server, scene, True)


def test_a_page_from_the_users_own_folder_runs_as_the_servers_own_do(browser, pages, server,
                                                                      scene_name, own_folder):
    folder, address = own_folder
    page_text = (EXAMPLES / "robot-reads.html").read_text().replace(
        '"/client/virtual-prosthetics.js"', f'"{server.http}/client/virtual-prosthetics.js"')
    assert server.http in page_text  # only the import line changed
    (folder / "reads.html").write_text(page_text)
    page = open_page(browser, pages, f"{address}/reads.html?scene={scene_name}")
    wait_until(page, "(n) => document.getElementById('reads').textContent.trim().split('\\n')"
               ".length === n", len(READS))
    assert page.inner_text("#reads").strip().split("\n") == READS
    check_reads_page_robots(server, scene_name)
    # its REST reads work too: the server answers its origin with CORS headers
    scenes = page.evaluate(f"async () => (await (await fetch('{server.http}/api/scenes')).json())")
    assert scene_name in [s["name"] for s in scenes]
    _seen_by_a_viewer(browser, pages, server, scene_name)


# a 1.0 page of a user's own, with a mesh file of its own beside it
OWN_MESH_PAGE = """<!DOCTYPE html><body><script type="module">
import * as Prosthetic from "SERVER/client/virtual-prosthetics.js";
var robot = new Prosthetic.Robot;
robot.attachChain( new Prosthetic.MotorZ( -1, 1 ),
	new Prosthetic.RoundFinger( "meshes/gripper.glb", 0.8, function( part ) { window.loaded = part; } ) );
Prosthetic.setAnimation( function( t ) { robot.setAngles( Math.sin( 3*t ) ); } );
</script></body>"""


MESH_DRAWN = """(id) => { let drawn = false;
    window.VP?.objects.get(id)?.userData.shape?.traverse((o) => { drawn ||= o.isMesh; });
    return drawn; }"""


def test_a_pages_own_mesh_file_is_uploaded_and_drawn(browser, pages, server, scene_name,
                                                     own_folder):
    folder, address = own_folder
    (folder / "meshes").mkdir()
    (folder / "meshes" / "gripper.glb").write_bytes((ASSETS / "round-finger-8.glb").read_bytes())
    (folder / "mesh.html").write_text(OWN_MESH_PAGE.replace("SERVER", server.http))
    page = open_page(browser, pages, f"{address}/mesh.html?scene={scene_name}")
    deadline = time.monotonic() + WAIT_SECONDS
    while not (fingers := [n for n in server.nodes(scene_name) if n["type"] == "RoundFinger"]):
        assert time.monotonic() < deadline, "the page's finger was never made"
        time.sleep(0.2)
    finger = fingers[0]
    assert finger["geometry"]["url"].startswith("/api/assets/")   # the page's file, uploaded
    wait_until(page, "() => window.loaded !== undefined")         # its callback ran
    assert _moves(server, scene_name, True)
    # drawn from the server's copy in the page itself (not the page's site) and in a viewer
    for drawing in (page, open_viewer(browser, pages, server, f"scene={scene_name}&{CALM}")):
        wait_until(drawing, MESH_DRAWN, finger["id"])


def test_the_digger_page_is_seen_by_another_browser(browser, pages, server, scene_name):
    page = open_page(browser, pages, f"{server.http}/examples/digger.html?scene={scene_name}&{CALM}")
    _wait_for_robots(server, scene_name, 3)
    nodes = {n["id"]: n for n in server.nodes(scene_name)}
    positions = sorted(n["position"][2] for n in server.robots(scene_name))
    assert positions == [-1, 0, 1]          # robotA at z=1, robotC at z=-1, as the manual says
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}&{CALM}")
    wait_until(viewer, "(ids) => ids.every((id) => window.VP.objects.has(id))", list(nodes))
    # the page draws the same scene: the viewer inside it holds the same nodes
    wait_until(page, "(ids) => window.VP && ids.every((id) => window.VP.objects.has(id))", list(nodes))
    assert "connected" in page.inner_text("#status")


def test_a_page_without_a_scene_gets_its_own_with_a_watch_link(browser, pages, server):
    page = open_page(browser, pages, f"{server.http}/examples/simple-robot-2.html?{CALM}")
    wait_until(page, "() => document.querySelector('#status a')")
    link = page.get_attribute("#status a", "href")
    scene = link.split("scene=")[1]
    assert scene.startswith("page-")
    _wait_for_robots(server, scene, 1)


def _meshes(server, scene: str) -> dict[str, dict]:
    return {n["id"]: n for n in server.nodes(scene) if n["type"] == "SceneMesh"}


def test_the_custom_meshes_page_shares_its_meshes_and_senses_them(browser, pages, server,
                                                                   scene_name):
    page = open_page(browser, pages, f"{server.http}/examples/custom-meshes.html?scene={scene_name}&{CALM}")
    _wait_for_robots(server, scene_name, 1)
    deadline = time.monotonic() + WAIT_SECONDS
    while len(_meshes(server, scene_name)) < 123 and time.monotonic() < deadline:
        time.sleep(0.2)
    meshes = _meshes(server, scene_name)
    kinds = sorted(n["geometry"]["kind"] for n in meshes.values())
    assert kinds.count("sphere") == 120 and {"box", "cylinder", "triangles"} <= set(kinds)
    wall = next(n for n in meshes.values() if n["geometry"]["kind"] == "box")
    assert wall["position"] == [2, 0.6, 0] and wall["geometry"]["size"] == [0.4, 1.2, 2.4]
    # the markers move with the page's loop
    markers = sorted(i for i, n in meshes.items() if n["geometry"]["kind"] == "sphere")
    before = _meshes(server, scene_name)[markers[0]]["position"]
    deadline = time.monotonic() + WAIT_SECONDS
    while _meshes(server, scene_name)[markers[0]]["position"] == before and time.monotonic() < deadline:
        time.sleep(0.2)
    assert _meshes(server, scene_name)[markers[0]]["position"] != before
    # the sweeping sensor measures the wall at some point of its sweep (1.64 m straight on)
    wait_until(page, "() => /distance: 1\\.[6-9]/.test(document.getElementById('reading').textContent)")
    # a second browser draws the page's meshes; the page does not draw them twice
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}&{CALM}")
    wait_until(viewer, "(ids) => ids.every((id) => VP.objects.get(id)?.userData.shape)", markers)
    assert page.evaluate("(ids) => ids.every((id) => !VP.objects.get(id)?.userData.shape)", markers)


def _reading(page) -> str:
    return page.inner_text("#reading")


def _sensor_page(browser, pages, server, scene: str, example: str):
    page = open_page(browser, pages, f"{server.http}/examples/{example}.html?scene={scene}&{CALM}")
    _wait_for_robots(server, scene, 1)
    return page


def test_the_distance_page_measures_the_ground_and_the_step_it_added(browser, pages, server,
                                                                     scene_name):
    page = _sensor_page(browser, pages, server, scene_name, "sensor-distance")
    # 1.5 above the ground, 0.9 above the 0.6-high step (a page mesh)
    wait_until(page, "() => /least 0\\.(89|90|91)\\d*, most 1\\.(49|50)/.test("
                     "document.getElementById('reading').textContent)")
    _seen_by_a_viewer(browser, pages, server, scene_name)


def test_the_touch_page_feels_the_box_and_lets_go(browser, pages, server, scene_name):
    page = _sensor_page(browser, pages, server, scene_name, "sensor-touch")
    wait_until(page, "() => /most 1\\.00/.test(document.getElementById('reading').textContent)")
    wait_until(page, "() => /touch: 0\\.00/.test(document.getElementById('reading').textContent)")
    # the page recolours its box while touched: the server has both colours in turn
    box = next(iter(_meshes(server, scene_name).values()))
    colours = {box["color"]}
    deadline = time.monotonic() + WAIT_SECONDS
    while len(colours) < 2 and time.monotonic() < deadline:
        colours.add(_meshes(server, scene_name)[box["id"]]["color"])
        time.sleep(0.05)
    assert len(colours) == 2, colours
    _seen_by_a_viewer(browser, pages, server, scene_name)


def test_the_position_page_reads_a_circle_and_leaves_a_trail(browser, pages, server, scene_name):
    page = _sensor_page(browser, pages, server, scene_name, "sensor-position")
    wait_until(page, "() => /position: \\[/.test(document.getElementById('reading').textContent)")
    points = set()
    deadline = time.monotonic() + WAIT_SECONDS
    while len(points) < 5 and time.monotonic() < deadline:
        points.add(tuple(json.loads(_reading(page).removeprefix("position: "))))
        time.sleep(0.2)
    assert len(points) >= 5
    # the arm turns about the vertical axis through the origin: one radius, one height
    radii = [math.hypot(x, z) for x, _, z in points]
    assert max(radii) - min(radii) < 0.01 and radii[0] > 0.5, points
    assert len({round(y, 2) for _, y, _ in points}) == 1, points
    height = next(iter(points))[1]
    # the trail: page meshes the server places where the sensor was (the page's first
    # frames, before the server has answered for the arm, read where the page's own tree
    # puts the sensor without its slots' offsets: the origin, or the robot's position
    # once that is set; those dots are moved on once the trail has gone round)
    def on_circle(x: float, y: float, z: float) -> bool:
        return abs(math.hypot(x, z) - radii[0]) < 0.01 and abs(y - height) < 0.01

    deadline = time.monotonic() + WAIT_SECONDS
    while time.monotonic() < deadline:
        trail = [n["position"] for n in _meshes(server, scene_name).values() if n["visible"]]
        if len(trail) == 40 and all(on_circle(*point) for point in trail):
            break
        time.sleep(0.2)
    assert len(trail) == 40 and all(on_circle(*point) for point in trail), trail
    assert len({tuple(round(c, 2) for c in point) for point in trail}) > 20, trail  # a trail, not a dot
    _seen_by_a_viewer(browser, pages, server, scene_name)


def test_the_collision_page_feels_the_ball_and_counts_contacts(browser, pages, server, scene_name):
    page = _sensor_page(browser, pages, server, scene_name, "sensor-collision")
    wait_until(page, "() => /collision: true, objects: [1-9]\\d*, ball: true/.test("
                     "document.getElementById('reading').textContent)")
    wait_until(page, "() => /hits: [1-9].*begun: [1-9]\\d*, ended: [1-9]/.test("
                     "document.getElementById('reading').textContent)")
    _seen_by_a_viewer(browser, pages, server, scene_name)


def test_the_motor_panel_page_moves_its_arm_and_a_viewer_follows(browser, pages, server,
                                                                 scene_name):
    page = _sensor_page(browser, pages, server, scene_name, "motor-panel")
    wait_until(page, "() => document.querySelector('.lil-gui .lil-title')?.textContent === 'Arm'")
    # the panel is the page's at once; its sliders come once the server has made the arm
    labels = "() => [...document.querySelectorAll('.lil-gui .lil-controller.lil-number .lil-name')]" \
             ".map((e) => e.textContent)"
    wait_until(page, f"() => ({labels})().length === 4")
    assert page.evaluate(labels) == ["turn", "shoulder", "2", "3"]
    field = page.locator(".lil-gui .lil-controller.lil-number input").nth(1)
    field.fill("1.2")
    field.press("Enter")
    shoulder = [n for n in server.nodes(scene_name) if n["type"] == "MotorZ"][0]
    deadline = time.monotonic() + WAIT_SECONDS
    while server.nodes(scene_name) and time.monotonic() < deadline:
        if {n["id"]: n for n in server.nodes(scene_name)}[shoulder["id"]]["angle"] == 1.2:
            break
        time.sleep(0.1)
    assert {n["id"]: n for n in server.nodes(scene_name)}[shoulder["id"]]["angle"] == 1.2
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}&{CALM}")
    wait_until(viewer, "(id) => VP.angle(id) === 1.2", shoulder["id"])
