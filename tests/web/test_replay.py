"""A recording played in the viewer (/view?recording=ID): seeking shows the robot where it
was at that time, playing moves the timeline on, and a tick at a time steps it."""

from __future__ import annotations

import math
import os
import signal
import time

import pytest

import virtual_prosthetics as vp

from .conftest import open_viewer, red_box_on_a_motor, wait_until
from .picture import DEFAULT_CAMERA, Picture, background_like, project, reddish

ANGLES = (0.0, -1.0, 1.0)


def _recorded(server, scene):
    """A red box on a motor held at each of ANGLES for 0.8 s, recorded; the recording's id
    and, for each angle, a time in the recording when the box stood at it."""
    robot, motor, _ = red_box_on_a_motor()
    rec = vp.start_recording()
    for angle in ANGLES:
        motor.set_angle(angle)
        scene.sync()
        time.sleep(0.8)
    rec.stop()
    ticks = server.get(f"/api/recordings/{rec.id}/ticks?after=0&until={rec.summary['seconds']}")["ticks"]
    turned, held = [], ANGLES[0]  # when the angle changed (the robot's first frame names it too)
    for t, messages in ticks:
        for m in messages:
            angle = m.get("angles", {}).get(robot.id, [held])[0] if m["op"] == "frame" else held
            if angle != held:
                turned.append(t)
                held = angle
    assert len(turned) == 2, turned  # to -1, then to 1
    ends = [0.0, *turned, rec.summary["seconds"]]
    return rec.id, motor, [(a + b) / 2 for a, b in zip(ends, ends[1:])]


def test_seeking_shows_the_robot_where_it_was_then(browser, pages, server, scene, scene_name, tmp_path):
    recording, motor, times = _recorded(server, scene)
    page = open_viewer(browser, pages, server, f"recording={recording}")
    wait_until(page, "(id) => VP.objects.has(id)", motor.id)
    for k in (2, 0, 1):  # out of order: each seek stands alone
        page.evaluate("(t) => VP.replay.seek(t)", times[k])
        wait_until(page, "([id, a]) => VP.angle(id) === a && VP.shownAngle(id) === a && VP.drawn()",
                   [motor.id, ANGLES[k]])
        png = page.screenshot()
        (tmp_path / f"seek{k}.png").write_bytes(png)
        picture = Picture(png)
        top = (0.5 * math.sin(-ANGLES[k]), 0.5 * math.cos(ANGLES[k]), 0)  # the box's middle
        assert reddish(picture.at(project(top, *DEFAULT_CAMERA, picture.size))), (k, picture.at(project(top, *DEFAULT_CAMERA, picture.size)))
        elsewhere = (0.5 * math.sin(ANGLES[k]), 0.5 * math.cos(ANGLES[k]), 0) if ANGLES[k] else (0.6, 0.4, 0)
        assert background_like(picture.at(project(elsewhere, *DEFAULT_CAMERA, picture.size)))
    label = page.evaluate("() => document.querySelector('#timeline span').textContent")
    assert label.startswith(f"{times[1]:.2f} / ")
    assert "recording" in page.evaluate("() => document.getElementById('status').textContent")


def test_playing_and_stepping_move_the_timeline(browser, pages, server, scene, scene_name):
    recording, motor, times = _recorded(server, scene)
    page = open_viewer(browser, pages, server, f"recording={recording}")
    wait_until(page, "(id) => VP.objects.has(id)", motor.id)
    page.select_option("#timeline select", "2")
    page.click("#timeline button[title='play / pause']")
    wait_until(page, "([id, a]) => VP.angle(id) === a", [motor.id, ANGLES[2]])
    wait_until(page, "() => !VP.replay.playing && VP.replay.time === VP.replay.duration")  # played to the end
    page.evaluate("(t) => VP.replay.seek(t)", times[0])
    wait_until(page, "(t) => VP.replay.time === t", times[0])
    before = page.evaluate("() => VP.seq")
    page.click("#timeline button[title='a tick forwards']")
    wait_until(page, "(seq) => VP.seq === seq + 1", before)
    assert page.evaluate("() => VP.replay.time") > times[0]
    page.click("#timeline button[title='a tick back']")
    wait_until(page, "(seq) => VP.seq <= seq", before)


def test_a_tick_forwards_and_back_cross_a_gap_where_the_scene_stalled(browser, pages, server, scene, scene_name):
    """A scene's process stopped for a second (a loaded machine) left a gap between two
    ticks longer than the player reads ahead: stepping still goes to the next tick."""
    _, motor, _ = red_box_on_a_motor()
    scene.sync()
    rec = vp.start_recording()
    motor.set_angle(-1.0)
    scene.sync()
    time.sleep(0.3)
    pid = server.get("/api/metrics")["scenes"][scene_name]["pid"]
    os.kill(pid, signal.SIGSTOP)
    time.sleep(1.2)
    os.kill(pid, signal.SIGCONT)
    motor.set_angle(1.0)
    scene.sync()
    time.sleep(0.3)
    rec.stop()
    times = [t for t, _ in server.get(f"/api/recordings/{rec.id}/ticks?after=0&until={rec.summary['seconds']}")["ticks"]]
    gap = max(range(1, len(times)), key=lambda k: times[k] - times[k - 1])
    assert times[gap] - times[gap - 1] > 1.0  # the stop, as the recording has it
    page = open_viewer(browser, pages, server, f"recording={rec.id}")
    wait_until(page, "(id) => VP.objects.has(id)", motor.id)
    page.evaluate("(t) => VP.replay.seek(t)", times[gap - 1])
    wait_until(page, "(t) => VP.replay.time === t", times[gap - 1])
    before = page.evaluate("() => VP.seq")
    page.click("#timeline button[title='a tick forwards']")
    wait_until(page, "([seq, t]) => VP.seq === seq + 1 && VP.replay.time === t", [before, times[gap]])
    page.click("#timeline button[title='a tick back']")
    wait_until(page, "([seq, t]) => VP.seq === seq && VP.replay.time === t", [before, times[gap - 1]])


def test_a_controllers_viewer_records_the_scene_and_offers_the_replay(browser, pages, server, scene, scene_name):
    hand = vp.EdgedHand(True)
    scene.sync()
    page = open_viewer(browser, pages, server, f"scene={scene_name}&role=controller")
    assert open_viewer(browser, pages, server, f"scene={scene_name}").query_selector("#recorder") is None
    page.click("#recorder button")
    wait_until(page, "() => document.querySelector('#recorder button').textContent.includes('Stop')")
    for k in range(10):
        hand.flex_fingers(k / 10)
        scene.sync()
    time.sleep(0.5)
    page.click("#recorder button")
    wait_until(page, "() => document.querySelector('#recorder a') !== null")
    replay_link = page.evaluate("() => document.querySelector('#recorder a').getAttribute('href')")
    recording = replay_link.split("recording=")[1]
    listed = {r["id"]: r for r in server.get("/api/recordings")}[recording]
    assert listed["state"] == "stopped" and listed["scene"] == scene_name
    assert listed["messages"]["/vp/ticks"] > 10
    player = open_viewer(browser, pages, server, replay_link.split("?")[1])
    wait_until(player, "(id) => VP.objects.has(id)", hand.id)
