"""Fuzzing robot shapes up to every limit (issue 44, G15): attachChain of 128 boxes ended
a scene's process (PyBullet keeps 127 links of a multibody; link 128 was a segfault).

Each case builds one to three robots of random shape in a scene of its own, through the
protocol's session as a client would: chains (``attachChain``), branches (parts on the
slots of random parts), motors in a row with no part between them (a link each), bare
nodes, robots below other robots' parts; sizes drawn to straddle the engine's 127 links
(``treeLinks``), ``treeDepth``, ``clientObjects`` and ``sceneBodies`` (each lowered in
about half the cases, so that a case reaches it quickly); now and then a node is deleted, a robot moved or turned, the
scene made dynamic. Every answer must be ``ok`` or a structured refusal, never
``internal``; every tree the engine holds has all its links (none cut short) and every
physical part in the scene a body; the scene ticks after each case. A crash ends the
program: its exit code and the last case it began say which.

Run as a program it prints a JSON summary::

    python -m tests.features.fuzz.trees --cases 10000 [--seed 7]
"""

from __future__ import annotations

import argparse
import json
import random
import sys
from collections import Counter
from dataclasses import replace
from typing import Any

from server.core.kit.limits import DEFAULT
from server.core.protocol.session import Session
from server.core.scene.scene import Scene
from server.core.physics.articulation import MAX_LINKS
from tests.features.fuzz.gltf_files import peak_megabytes

# each case's limits: the defaults or lowered ones, so that a case of a few hundred
# objects reaches each of them now and then
LOWERED = {"client_objects": 400, "scene_bodies": 150, "tree_depth": 60}
PARTS = ["Box", "Ball", "EdgedFinger", "EdgedTip", "EdgedPalm", "Sensor"]
MOTORS = ["MotorX", "MotorY", "MotorZ"]
REFUSALS = {"limit_exceeded", "out_of_range", "cycle", "unknown_object", "bad_arguments",
            "wrong_type", "forbidden", "duplicate_id"}
SIZES = [(1, 20), (100, 140), (120, 135), (200, 320)]  # nodes of one robot


class TreeCase:
    """One case: its scene, a client's session, and what the client made."""

    def __init__(self, rng: random.Random) -> None:
        self.rng = rng
        limits = {name: value for name, value in LOWERED.items() if rng.random() < 0.5}
        self.scene = Scene("fuzz", limits=replace(DEFAULT, **limits))
        self.session = Session(self.scene, "c1")
        self.serial = 0
        self.robots: list[str] = []
        self.parts: list[str] = []
        self.answers: Counter[str] = Counter()  # by code
        self.limits: Counter[str] = Counter()  # limit_exceeded, by limit
        self.faults: list[dict[str, Any]] = []

    def send(self, *ops: dict[str, Any]) -> list[dict[str, Any]]:
        answers = self.session.receive(json.dumps([{**op, "id": k} for k, op in enumerate(ops)]))
        for op, answer in zip(ops, answers):
            code = "ok" if answer["op"] == "ok" else answer.get("code", "?")
            self.answers[code] += 1
            if code == "limit_exceeded":
                self.limits[answer["details"]["limit"]] += 1
            if code != "ok" and code not in REFUSALS:
                self.faults.append({"op": op, "answer": answer})
        return answers

    def new(self, kind: str, *args: Any) -> str | None:
        self.serial += 1
        ref = f"c1.{self.serial}"
        [answer] = self.send({"op": "create", "object": ref, "type": kind, "args": list(args)})
        return ref if answer["op"] == "ok" else None

    def call(self, ref: str, method: str, *args: Any) -> bool:
        [answer] = self.send({"op": "call", "object": ref, "method": method, "args": list(args)})
        return answer["op"] == "ok"

    def nodes(self, count: int) -> list[str]:
        """Parts and motors (motors in a row make links with no part between them), made
        in one text as a client's batch of creates would be; those made."""
        ops = []
        for _ in range(count):
            kind = self.rng.choice(PARTS + MOTORS * 2)
            self.serial += 1
            ops.append({"op": "create", "object": f"c1.{self.serial}", "type": kind,
                        "args": [-1.5, 1.5] if kind in MOTORS else []})
        made = [op["object"] for op, answer in zip(ops, self.send(*ops)) if answer["op"] == "ok"]
        self.parts += made
        return made

    def robot(self) -> None:
        robot = self.new("Robot")
        if robot is None:
            return
        self.robots.append(robot)
        low, high = self.rng.choice(SIZES)
        made = self.nodes(self.rng.randint(low, high))
        chained = self.rng.randint(0, len(made))
        if chained:
            self.call(robot, "attachChain", *({"ref": ref} for ref in made[:chained]))
        bushy = self.rng.random() < 0.5
        self.send(*({"op": "call", "object": ref, "method": "attachToSlot", "args": [
            {"ref": self.rng.choice(made[:k] or [robot]) if bushy else (made[k - 1] if k else robot)},
            self.rng.choice([0, 0, 0, 1, 2, 7])]} for k, ref in enumerate(made[chained:], chained)))

    def shake(self) -> None:
        """Changes after the trees are made: delete, nest, move, turn, go dynamic."""
        rng = self.rng
        for _ in range(rng.randint(0, 6)):
            choice = rng.random()
            if choice < 0.25 and self.parts:
                self.send({"op": "delete", "object": rng.choice(self.parts)})
            elif choice < 0.45 and len(self.robots) > 1 and self.parts:
                self.call(rng.choice(self.robots), "setPosition", 0, 0, 0)
                self.call(rng.choice(self.parts), "addSlot", [0, 0.1, 0])
            elif choice < 0.6 and self.robots and self.parts:  # a robot below a part
                self.send({"op": "call", "object": rng.choice(self.robots),
                           "method": "attachChain", "args": [{"ref": rng.choice(self.parts)}]})
            elif choice < 0.8 and self.robots:
                self.call(rng.choice(self.robots), "setAngles",
                          *(rng.uniform(-2, 2) for _ in range(rng.randint(0, 40))))
            elif choice < 0.9:
                self.call("scene", "setPhysics", rng.choice(["dynamic", "kinematic"]))
            elif self.robots:
                self.call(rng.choice(self.robots), "setScale", rng.uniform(0.1, 3))

    def check(self) -> list[str]:
        """What is wrong with the scene's bodies now (nothing, when all is well)."""
        for _ in range(3):
            self.scene.tick(1 / 60)
        wrong = []
        bodies = self.scene.bodies
        bodies.sync()  # (as a request reading the physics does: what a big batch left waiting)
        if bodies.failures:
            wrong.append(f"{bodies.failures} trees could not be built")
        world = bodies.physics
        for root in world.roots():
            tree = world.tree(root)
            if tree is None:
                continue
            held = world.links_held(root)
            if held != len(tree.links) or held > MAX_LINKS:
                wrong.append(f"{root}: the engine holds {held} links of {len(tree.links)}")
        for node in self.scene.nodes.values():
            if node.physical and node.in_scene() and node.visible and node.id not in world:
                wrong.append(f"{node.id} ({type(node).__name__}) has no body")
        return wrong


def run_case(rng: random.Random) -> tuple[TreeCase, list[str]]:
    case = TreeCase(rng)
    try:
        for _ in range(rng.randint(1, 3)):
            case.robot()
        case.shake()
        return case, case.check()
    finally:
        case.scene.close()


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--cases", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=44)
    arguments = parser.parse_args()
    answers: Counter[str] = Counter()
    broken: list[dict[str, Any]] = []
    limits: Counter[str] = Counter()
    for number in range(arguments.cases):
        print(f"case {number}", file=sys.stderr, flush=True)  # (a crash: the last line says which)
        case, wrong = run_case(random.Random(arguments.seed * 1_000_003 + number))
        answers.update(case.answers)
        limits.update(case.limits)
        if wrong or case.faults:
            broken.append({"case": number, "wrong": wrong[:5], "faults": case.faults[:3]})
    print(json.dumps({"cases": arguments.cases, "answers": dict(answers),
                      "limits": dict(limits), "broken": broken[:20],
                      "peakMegabytes": peak_megabytes()}))


if __name__ == "__main__":
    main()
