"""An imported robot in the viewer: every link drawn from its file's meshes in the file's
colours, where the robot's kinematics put it, and moving with its motors."""

from __future__ import annotations

import math
import os

import virtual_prosthetics as vp
from tests import hand_files
from tests.conftest import eventually

from .conftest import open_viewer, wait_until
from .picture import Picture, project

CAMERA = ((0.0, 0.12, 0.45), (0.0, 0.08, 0.0))
DRAWN = """(ids) => ids.every((id) => { let n = 0; VP.objects.get(id)?.traverse((c) => {
             if (c.isMesh && c.geometry.getAttribute('color')) n++; }); return n > 0; }) && VP.drawn()"""


def reddish(colour):
    r, g, b = colour
    return r > 120 and r > 2 * g and r > 2 * b


def test_an_imported_hand_is_drawn_in_its_files_colours_and_curls(browser, pages, server, scene,
                                                                  scene_name, tmp_path):
    archive = tmp_path / "hand.zip"
    archive.write_bytes(hand_files.hand_zip())
    vp.set_physics("kinematic", unit=1.0)  # a scene unit a metre: the file's figures
    hand = vp.load_robot(archive, rotation=[0, 0, 0])
    vp.set_camera_position(*CAMERA[0])
    vp.set_camera_target(*CAMERA[1])
    scene.sync()
    links = [p.id for p in hand.get_parts() if not isinstance(p, vp.Motor)]
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(viewer, DRAWN, links)
    picture = Picture(viewer.screenshot())
    if os.environ.get("VP_PICTURES"):
        (tmp_path / "straight.png").write_bytes(viewer.screenshot())
    # the middle finger's tip (red in the file) sits at its base + three segments along +y
    x, y, _ = hand_files.DIGITS["middle"]
    tip = (x, y + 2.5 * hand_files.SEGMENT, 0.0)
    assert reddish(picture.at(project(tip, *CAMERA, picture.size))), picture.at(project(tip, *CAMERA, picture.size))
    palm = picture.at(project((0.0, 0.0, 0.0), *CAMERA, picture.size))
    assert palm[0] > palm[2] and not reddish(palm)  # the palm's skin colour, not the tips' red
    # the middle finger's distal link: the highest at its x
    distal = max((p for p in server.get(f"/api/scenes/{scene_name}/robots/{hand.id}")["parts"]
                  if p["id"] in links and abs(p["world"]["position"][0] - x) < 1e-3),
                 key=lambda p: p["world"]["position"][1])["id"]
    hand.set_angles(*[None] * 6, 1.5)  # the middle finger curls: its tip leaves that spot
    scene.sync()
    # the middle finger's distal link has gone down, then the
    # picture is drawn with nothing moving (a loaded machine's screenshot once caught it
    # upright: the link waited for was another finger's, and the drawing came first)
    wait_until(viewer, """([id, y]) => { const o = VP.objects.get(id); o.updateWorldMatrix(true, false);
                           return o.matrixWorld.elements[13] < y; }""",
               [distal, y + 2 * hand_files.SEGMENT])
    wait_until(viewer, "() => VP.drawn()")
    # drawn, the page's screenshot may still be the frame before (Chromium's compositor
    # on a loaded machine): the spot is looked at until it changes, or the guard ends
    spot = project(tip, *CAMERA, picture.size)
    eventually(lambda: not reddish(Picture(viewer.screenshot()).at(spot)))
    if os.environ.get("VP_PICTURES"):
        (tmp_path / "curled.png").write_bytes(viewer.screenshot())
        print("pictures in", tmp_path)


def test_sliding_jaws_are_shown_where_the_server_puts_them(browser, pages, server, scene,
                                                           scene_name, tmp_path):
    archive = tmp_path / "jaws.zip"
    archive.write_bytes(hand_files.hand_zip(hand_files.JAWS))
    hand = vp.load_robot(archive)  # at the default unit: the robot scaled 18.4 times
    scene.sync()
    report = server.get(f"/api/scenes/{scene_name}/robots/{hand.id}")
    jaws = {p["id"]: p["world"]["position"] for p in report["parts"]
            if p["type"] == "RobotLink" and p["name"].startswith("jaw")}
    slides = [m for m in report["motors"] if m["type"] == "Slider"]
    assert len(jaws) == 2 and [m["name"] for m in slides] == ["jaw_a_slide", "jaw_b_slide"]
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(viewer, DRAWN, list(jaws))
    unit = vp.get_physics()["unit"]
    next(m for m in hand.get_motors() if m.id == slides[0]["id"]).set_angle(0.02 / unit)  # 2 cm
    scene.sync()
    for part in server.get(f"/api/scenes/{scene_name}/robots/{hand.id}")["parts"]:
        if part["id"] not in jaws:
            continue
        where = part["world"]["position"]  # 2 cm from where it was (the other jaw 2.1: it follows)
        assert 0.019 < math.dist(where, jaws[part["id"]]) * unit < 0.022
        wait_until(viewer, """([id, where]) => { const o = VP.objects.get(id); o.updateWorldMatrix(true, false);
                               const e = o.matrixWorld.elements;
                               return Math.hypot(e[12] - where[0], e[13] - where[1], e[14] - where[2]) < 1e-6; }""",
                   [part["id"], where])


DROP = """async ([data, name, x, y]) => {
    const bytes = Uint8Array.from(atob(data), (c) => c.charCodeAt(0));
    const files = new DataTransfer();
    files.items.add(new File([bytes], name));
    const canvas = VP.renderer.domElement;
    const box = canvas.getBoundingClientRect();
    canvas.dispatchEvent(new DragEvent('drop', { dataTransfer: files, bubbles: true, cancelable: true,
                                                 clientX: box.left + x * box.width, clientY: box.top + y * box.height }));
}"""


def test_a_robot_file_dropped_on_a_controllers_viewer_lands_where_it_was_dropped(
        browser, pages, server, scene, scene_name):
    import base64
    vp.set_camera_position(0, 2, 2)
    vp.set_camera_target(0, 0, 0)
    scene.sync()
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}&role=controller")
    wait_until(viewer, "() => VP.drawn()")
    viewer.evaluate(DROP, [base64.b64encode(hand_files.hand_zip()).decode(), "hand.zip", 0.5, 0.5])
    wait_until(viewer, "() => document.getElementById('robot-drop').textContent.includes('test_hand (api.')")
    assert viewer.evaluate("() => document.getElementById('robot-drop').textContent").endswith(', 9 motors')
    [robot] = [r for r in server.get(f"/api/scenes/{scene_name}/robots") if r["owner"] == "api"]
    assert robot["position"] == [0.0, 0.0, 0.0]  # the middle of the picture: the camera's target
    viewer.evaluate(DROP, [base64.b64encode(b"not a robot").decode(), "notes.urdf", 0.5, 0.5])
    wait_until(viewer, "() => /neither a zip nor a URDF/.test(document.getElementById('robot-drop').textContent)")
    viewer.evaluate(DROP, [base64.b64encode(b"x").decode(), "photo.png", 0.5, 0.5])
    wait_until(viewer, "() => /drop a .urdf/.test(document.getElementById('robot-drop').textContent)")
    assert len(server.get(f"/api/scenes/{scene_name}/robots")) == 1
