"""Every part type drawn, and the URL overlays: slots, envelopes, contact glow, lasers."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import pytest

import virtual_prosthetics as vp

from .conftest import open_viewer, wait_until
from .picture import Picture, background_like

EXAMPLE = Path(__file__).resolve().parents[2] / "clients" / "python" / "examples" / "all_parts.py"
COUNT = "(name) => { let n = 0; VP.scene.traverse((o) => { if (o.name === name) n++; }); return n; }"


def crimson(colour) -> bool:
    r, g, b = colour
    return r > 150 and g < 90 and b < 110


@pytest.fixture
def all_parts(server, scene_name):
    spec = importlib.util.spec_from_file_location("all_parts", EXAMPLE)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    scene = vp.connect(server.ws, scene=scene_name)
    parts = example.build()
    scene.sync()
    yield parts
    scene.close()


def snapshot_counts(server, scene_name):
    nodes = server.nodes(scene_name)
    return (sum(n["type"] == "Slot" for n in nodes), sum(bool(n.get("physical")) for n in nodes),
            len(nodes))


def test_every_part_type_is_drawn_and_overlays_add_slots_and_envelopes(
        browser, pages, server, scene_name, all_parts):
    slots, physical, total = snapshot_counts(server, scene_name)
    shares = {}
    for overlay in ("", "show-slots", "debug-physics"):
        page = open_viewer(browser, pages, server, f"scene={scene_name}&{overlay}")
        wait_until(page, "(n) => VP.objects.size === n && VP.drawn()", total)
        kinds = page.evaluate("() => [...VP.objects.values()].filter((o) => o.userData.shape)"
                              ".map((o) => o.userData.node.geometry.kind)")
        assert set(kinds) == {"sphere", "box", "convex", "cylinder", "dome"}
        assert page.evaluate(COUNT, "slot-marker") == (slots if overlay == "show-slots" else 0)
        assert page.evaluate(COUNT, "envelope") == (physical if overlay == "debug-physics" else 0)
        picture = Picture(page.screenshot())
        assert picture.share(lambda c: not background_like(c)) > 0.05  # not a blank canvas
        shares[overlay] = picture.share(crimson)
        pages.release(page)
    assert shares["show-slots"] > shares[""] + 0.001
    assert shares["debug-physics"] > shares[""] + 0.001


def test_parts_in_contact_glow_in_the_touch_colour(browser, pages, server, scene_name):
    with vp.Session(server.ws, scene=scene_name) as client:
        box = vp.Box(0.5, 0.5, 0.5, "white", scene=client)
        box.set_position(0, 1, 0)
        client.sync()
        page = open_viewer(browser, pages, server, f"scene={scene_name}&touch-color=red")
        glow = ("(id) => VP.objects.get(id).userData.shape.children[0]"
                ".material.emissive.getHexString()")
        wait_until(page, "(id) => VP.objects.has(id)", box.id)
        assert page.evaluate(glow, box.id) == "000000"
        box.set_position(0, 0.2, 0)  # into the ground
        wait_until(page, f"(id) => ({glow})(id) === 'ff0000'", box.id)
        box.set_position(0, 1, 0)
        wait_until(page, f"(id) => ({glow})(id) === '000000'", box.id)


def test_a_laser_reaches_what_its_sensor_senses(browser, pages, server, scene_name):
    with vp.Session(server.ws, scene=scene_name) as client:
        sensor = vp.Sensor(True, "lime", scene=client)
        sensor.set_position(0, 2, 0)
        sensor.set_rotation(math.pi, 0, 0)
        client.sync()
        page = open_viewer(browser, pages, server, f"scene={scene_name}")
        beam_end = ("() => { let end = null; VP.scene.traverse((o) => { if (o.isLine && "
                    "!o.isLineSegments && o.material.color.getHexString() === '00ff00') "
                    "end = [...o.geometry.attributes.position.array.slice(3, 6)]; });"
                    " return end; }")
        wait_until(page, f"() => {{ const e = ({beam_end})(); return e && Math.abs(e[1]) < 1e-3; }}")
        assert page.evaluate(beam_end) == pytest.approx([0, 0, 0], abs=1e-3)  # on the ground
        sensor.set_position(0, 2, 0.5)
        vp.Box(1, 0.2, 1, scene=client).set_position(0, 0.6, 0.5)
        on_the_box = "(e) => Math.abs(e[1] - 0.7) < 1e-3 && Math.abs(e[2] - 0.5) < 1e-3"
        wait_until(page, f"() => ({on_the_box})(({beam_end})())")
