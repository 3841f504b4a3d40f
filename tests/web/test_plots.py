"""Plots in the viewer: a watched sensor's distance and a motor's angle on one uPlot
chart, with the values the frames carried; the CSV holds them; over a recording the
chart follows the player's time."""

from __future__ import annotations

import time

import pytest

import virtual_prosthetics as vp
from tests.conftest import eventually

from .conftest import open_viewer, wait_until


def _lies_still(part: vp.Part) -> bool:
    """On the ground, not moving over a tenth of a second of the scene's time."""
    def position() -> list[float]:
        return vp.current_session().read(lambda mirror: list(mirror.nodes[part.id]["position"]))
    before, at = position(), vp.get_time()
    eventually(lambda: vp.get_time() > at + 0.1)
    return before[1] < 0.51 and position() == pytest.approx(before, abs=1e-4)


def _sensor_over_a_moving_box(scene):
    sensor = vp.Sensor()
    sensor.set_position(0, 4, 0)
    sensor.set_rotation(3.14159, 0, 0)  # looking down
    sensor.watch()
    box = vp.Box(1, 1, 1, "red")
    robot = vp.Robot()
    motor = vp.MotorZ(-2, 2)
    robot.attach_chain(motor)
    scene.sync()
    return sensor, box, motor


def _move(scene, box, motor, steps=30):
    for k in range(steps):
        box.set_position(0, k / 10, 0)  # the box rises under the sensor: distance shrinks
        motor.set_angle(k / 30)
        scene.sync()
        time.sleep(1 / 30)


def test_a_sensors_distance_and_a_motors_angle_are_plotted_live_and_given_as_csv(
        browser, pages, server, scene, scene_name, tmp_path):
    sensor, box, motor = _sensor_over_a_moving_box(scene)
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    page.click("#plot-button")
    _move(scene, box, motor)
    wait_until(page, "(name) => VP.plots.series.has(name)", f"{sensor.id} distance")
    # a robot's motors are plotted until someone chooses
    wait_until(page, "(name) => VP.plots.chosen.join() === name", f"{motor.id} angle")
    page.evaluate("(name) => VP.plots.choose(name)", f"{sensor.id} distance")
    page.wait_for_timeout(300)
    chosen = page.evaluate("() => VP.plots.chosen")
    assert chosen == [f"{motor.id} angle", f"{sensor.id} distance"]
    distances = page.evaluate("(name) => [...VP.plots.series.get(name).values()]", f"{sensor.id} distance")
    assert len(set(distances)) > 5 and distances == sorted(distances, reverse=True)  # it came closer
    assert distances[-1] == pytest.approx(sensor.sense_distance(), abs=1e-9)
    drawn = page.evaluate("() => VP.plots.plot.data")
    assert len(drawn) == 3 and len(drawn[0]) > 5  # times and the two series, drawn
    csv = page.evaluate("() => VP.plots.csv()").splitlines()
    assert csv[0] == f"time,{motor.id} angle,{sensor.id} distance" and len(csv) > 5
    angles = [float(row.split(",")[1]) for row in csv[1:] if row.split(",")[1]]
    assert angles[-1] == pytest.approx(29 / 30)
    (tmp_path / "plots.png").write_bytes(page.screenshot())


def test_series_are_listed_by_name_and_a_filter_box_narrows_them(browser, pages, server, scene,
                                                                 scene_name):
    """Found: 124 unlabelled checkboxes named by id (`demo.EdgedHand-left/11 angle`), no search."""
    sensor, box, motor = _sensor_over_a_moving_box(scene)
    robot = vp.Robot()
    robot.attach_chain(vp.MotorZ(-1, 1).set_name("shoulder"), vp.EdgedFinger(), vp.MotorX(-1, 1))
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    page.click("#plot-button")
    for k in range(10):
        robot.set_angles(k / 20, -k / 20)
        motor.set_angle(k / 20)
        scene.sync()
        time.sleep(1 / 30)
    labels = "() => [...document.querySelectorAll('#plots .series label')].map((l) => l.textContent.trim())"
    named = [f"{robot.id} · shoulder angle", f"{robot.id} · 1 angle"]
    wait_until(page, f"(named) => named.every((n) => ({labels})().includes(n))", named)
    other = page.evaluate("(id) => VP.objects.get(id).parent.name", motor.id)  # its robot
    assert f"{other} · 0 angle" in page.evaluate(labels)  # no name: its index
    page.fill("#plots .series-filter", "shoulder")
    wait_until(page, f"() => ({labels})().length === 1")
    page.locator("#plots .series input").first.check()
    wait_until(page, "() => document.querySelector('#plots .u-legend')?.textContent.includes('shoulder')")


def test_over_a_recording_the_chart_follows_the_player(browser, pages, server, scene, scene_name):
    sensor, box, motor = _sensor_over_a_moving_box(scene)
    rec = vp.start_recording()
    _move(scene, box, motor)
    rec.stop()
    page = open_viewer(browser, pages, server, f"recording={rec.id}")
    page.click("#plot-button")
    # found: nothing listed until played; then only what was played. The whole recording
    # is plotted at once, the robot's motor chosen
    angle, distance = f"{motor.id} angle", f"{sensor.id} distance"
    wait_until(page, "(name) => VP.plots.series.get(name)?.size >= 25", angle)
    assert page.evaluate("() => VP.replay.time") == 0
    assert page.evaluate("() => VP.plots.chosen") == [angle]
    wait_until(page, "() => VP.plots.plot.data[0].length >= 25")
    recorded = page.evaluate("(name) => [...VP.plots.series.get(name).values()]", angle)
    assert recorded[-1] == pytest.approx(29 / 30)  # the last angle, never played
    # frames carry changes only: the angle holds to the recording's end, drawn so
    times, drawn = page.evaluate("() => VP.plots.plot.data")
    assert times[-1] == pytest.approx(page.evaluate("() => VP.plots.span()[1]"))
    assert drawn[-1] == pytest.approx(29 / 30) and None not in drawn[drawn.index(recorded[0]):]
    page.select_option("#timeline select", "5")
    page.click("#timeline button[title='play / pause']")
    wait_until(page, "() => !VP.replay.playing && VP.replay.time === VP.replay.duration")
    name = f"{sensor.id} distance"
    wait_until(page, "(name) => VP.plots.series.get(name)?.size > 10", name)
    cursor, (start, end) = page.evaluate("() => [VP.plots.cursor(), VP.plots.span()]")
    assert cursor == pytest.approx(end) and end - start == pytest.approx(page.evaluate("() => VP.replay.duration"))
    scale = page.evaluate("() => [VP.plots.plot.scales.x.min, VP.plots.plot.scales.x.max]")
    assert scale == pytest.approx([start, end])  # the chart spans the recording, the line at its end
    times = page.evaluate("() => VP.plots.plot.data[0]")
    assert start <= times[0] and times[-1] <= cursor + 1e-9  # (the cursor is a sum: rounding)
    page.evaluate("(t) => VP.replay.seek(t)", 0.2)
    wait_until(page, "(t) => Math.abs(VP.plots.cursor() - VP.plots.span()[0] - t) < 1e-9", 0.2)
    # found: the axis showed scene time (474-485 s) while the timeline showed 0.00-11.72 s
    shown = page.evaluate("([a, b]) => VP.plots.plot.axes[0].values(VP.plots.plot, [a, b])", [start, end])
    assert shown == pytest.approx([0, round(end - start, 3)])  # what the axis writes at its ends
    assert page.evaluate("() => VP.plots.plot.axes[0].label") == "time in the recording (s)"


def test_the_heat_map_makes_a_pressed_part_glow_and_only_it(browser, pages, server, scene, scene_name):
    box = vp.Box(1, 1, 1, "steelblue")
    box.set_position(0, 1, 0)  # it falls and lies on the ground: pressed by its weight
    robot = vp.Robot()
    held = vp.Ball(0.3, "orange")
    held.attach_to_slot(robot)
    robot.set_position(3, 2, 0)  # held at its mount, touching nothing
    vp.set_physics("dynamic")
    scene.sync()
    # the viewer comes once the box lies still: full red is the largest force the viewer
    # saw, and on a loaded machine it could otherwise see the landing's
    eventually(lambda: _lies_still(box))
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    page.click("#plot-button")
    page.check("#heat")
    wait_until(page, "(id) => VP.heat.shown(id) > 0.5", box.id)
    assert page.evaluate("(id) => VP.heat.shown(id)", held.id) == 0
    page.uncheck("#heat")
    wait_until(page, "(id) => VP.heat.shown(id) === 0", box.id)
