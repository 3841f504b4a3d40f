"""A slow viewer gets frames folded together (server.web.connections.outbox): robots send their angles
as one array in motor order, and the folded frame must still leave every motor at its
angle, however motors moved between robots in between."""

import json

from server.core.protocol.session import Session
from server.core.scene.frames import merge_frames
from virtual_prosthetics.mirror import Mirror

PERIOD = 1 / 60


def _frames(scene, session, steps):
    """The frame of one tick after each step's requests."""
    frames = []
    for step in steps:
        answers = session.receive(json.dumps([{**op, "id": k + 1} for k, op in enumerate(step)]))
        assert all(answer["op"] == "ok" for answer in answers), answers
        [frame] = [m for m in scene.tick(PERIOD) if m["op"] == "frame"]
        frames.append(json.loads(json.dumps(frame)))
    return frames


def _angles_in(mirror):
    return {i: n["angle"] for i, n in mirror.nodes.items() if "angle" in n}


def test_folded_frames_keep_every_angle_while_motors_change_robots(scene):
    session = Session(scene, "c1")
    call = lambda obj, method, *args: {"op": "call", "object": obj, "method": method,  # noqa: E731
                                       "args": list(args)}
    made = [{"op": "create", "object": f"c1.{name}", "type": kind} for name, kind in (
        ("r", "Robot"), ("q", "Robot"), ("m1", "MotorZ"), ("m2", "MotorX"), ("m3", "MotorY"),
        ("b", "Box"))]
    _frames(scene, session, [made + [call("c1.r", "attachChain", {"ref": "c1.m1"}, {"ref": "c1.m2"}),
                                     call("c1.q", "attachChain", {"ref": "c1.m3"})]])
    mirror = Mirror()
    mirror.apply(json.loads(json.dumps(scene.snapshot())))
    frames = _frames(scene, session, [
        [call("c1.m2", "setAngle", 0.4), call("c1.m3", "setAngle", -0.3)],
        [call("c1.m2", "attachToSlot", {"ref": "c1.m3"})],  # m2 leaves r for q, unturned
        [call("c1.m1", "setAngle", 0.2)],
        [call("c1.m3", "attachToSlot", {"ref": "c1.b"}), call("c1.m3", "setAngle", 0.6)],
        [call("c1.r", "setAngles", 0.1)],
    ])
    assert frames[0]["angles"] == {"c1.r": [0, 0.4], "c1.q": [-0.3]}
    assert frames[1]["angles"] == {"c1.r": [0], "c1.q": [-0.3, 0.4]}
    assert frames[3]["angles"] == {"c1.q": [], "c1.m3": 0.6, "c1.m2": 0.4}
    folded = frames[0]
    for frame in frames[1:]:
        folded = merge_frames(folded, frame)
    mirror.apply(folded)
    assert _angles_in(mirror) == {"c1.m1": 0.1, "c1.m2": 0.4, "c1.m3": 0.6}
    assert _angles_in(mirror) == {i: scene.nodes[i].angle for i in ("c1.m1", "c1.m2", "c1.m3")}
