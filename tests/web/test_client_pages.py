"""1.0 pages (web/examples, only the import line changed) in headless Chromium: their
robots appear on the server and move, and a second browser watching the scene sees them."""

from __future__ import annotations

import time

import pytest

from .conftest import open_page, open_viewer, wait_until


def _nodes(server, scene: str) -> list[dict]:
    try:
        return server.get(f"/api/scenes/{scene}/snapshot")["nodes"]
    except Exception:  # the page has not joined yet
        return []


def _angles(server, scene: str) -> list[float]:
    return [n["angle"] for n in _nodes(server, scene) if n["type"] == "MotorZ"]


def _moves(server, scene: str, expected: bool) -> bool:
    """Whether the scene's motor angles change. An animated page gets 20 s (its first
    picture in software WebGL can hold the page's loop for seconds); a static one 1 s."""
    first = _angles(server, scene)
    deadline = time.monotonic() + (20 if expected else 1)
    while _angles(server, scene) == first and time.monotonic() < deadline:
        time.sleep(0.2)
    return _angles(server, scene) != first


def _wait_for_robots(server, scene: str, count: int) -> None:
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        if sum(n["type"] == "Robot" for n in _nodes(server, scene)) == count:
            return
        time.sleep(0.2)
    raise AssertionError(f"{count} robots never appeared in {scene}: {_nodes(server, scene)}")


@pytest.mark.parametrize("example, robots, moving", [
    ("simple-robot-2", 1, False), ("simple-robot-3", 1, True), ("simple-robot-4", 1, True)])
def test_an_example_page_builds_its_robot_on_the_server(browser, pages, server, scene_name,
                                                        example, robots, moving):
    open_page(browser, pages, f"{server.http}/examples/{example}.html?scene={scene_name}")
    _wait_for_robots(server, scene_name, robots)
    assert _moves(server, scene_name, moving) == moving


def test_the_digger_page_is_seen_by_another_browser(browser, pages, server, scene_name):
    page = open_page(browser, pages, f"{server.http}/examples/digger.html?scene={scene_name}")
    _wait_for_robots(server, scene_name, 3)
    nodes = {n["id"]: n for n in _nodes(server, scene_name)}
    positions = sorted(n["position"][2] for n in nodes.values() if n["type"] == "Robot")
    assert positions == [-1, 0, 1]          # robotA at z=1, robotC at z=-1, as the manual says
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(viewer, "(ids) => ids.every((id) => window.VP.objects.has(id))", list(nodes))
    # the page draws the same scene: the viewer inside it holds the same nodes
    wait_until(page, "(ids) => window.VP && ids.every((id) => window.VP.objects.has(id))", list(nodes))
    assert "connected" in page.inner_text("#status")


def test_a_page_without_a_scene_gets_its_own_with_a_watch_link(browser, pages, server):
    page = open_page(browser, pages, f"{server.http}/examples/simple-robot-2.html")
    wait_until(page, "() => document.querySelector('#status a')", timeout=20_000)
    link = page.get_attribute("#status a", "href")
    scene = link.split("scene=")[1]
    assert scene.startswith("page-")
    _wait_for_robots(server, scene, 1)


def _meshes(server, scene: str) -> dict[str, dict]:
    return {n["id"]: n for n in _nodes(server, scene) if n["type"] == "SceneMesh"}


def test_the_custom_meshes_page_shares_its_meshes_and_senses_them(browser, pages, server,
                                                                   scene_name):
    page = open_page(browser, pages, f"{server.http}/examples/custom-meshes.html?scene={scene_name}")
    _wait_for_robots(server, scene_name, 1)
    deadline = time.monotonic() + 30
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
    deadline = time.monotonic() + 20
    while _meshes(server, scene_name)[markers[0]]["position"] == before and time.monotonic() < deadline:
        time.sleep(0.2)
    assert _meshes(server, scene_name)[markers[0]]["position"] != before
    # the sweeping sensor measures the wall at some point of its sweep (1.64 m straight on)
    wait_until(page, "() => /distance: 1\\.[6-9]/.test(document.getElementById('reading').textContent)",
               timeout=30_000)
    # a second browser draws the page's meshes; the page does not draw them twice
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(viewer, "(ids) => ids.every((id) => VP.objects.get(id)?.userData.shape)", markers)
    assert page.evaluate("(ids) => ids.every((id) => !VP.objects.get(id)?.userData.shape)", markers)
