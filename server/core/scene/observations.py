"""What a tick observes besides the changes made to it: contacts that began and ended,
the readings of watched sensors, and the limits that held that work back."""

from __future__ import annotations

from typing import Any, Mapping

from ..model.node import Node
from ..model.readings import Reading
from ..model.watches import Watches
from . import frames
from .bodies import SceneBodies


def observe(bodies: SceneBodies, watches: Watches, nodes: Mapping[str, Node]) -> dict[str, Any]:
    """This tick's frame fields ``contacts``, ``sensors`` and ``limited`` (those that apply)."""
    out: dict[str, Any] = {}
    began, ended = bodies.contacts.update(bodies.overlaps())
    if began or ended:
        out["contacts"] = {"begin": [list(p) for p in began], "end": [list(p) for p in ended]}
    forces = bodies.forces.changed()
    if forces:
        out["forces"] = forces
    readings = watched_wire(bodies, watches, nodes)
    if readings:
        out["sensors"] = readings
    tracker, dynamics = bodies.tracker, bodies.physics.dynamics
    steps, iterations = (0, 0) if dynamics is None else \
        (dynamics.held_back, dynamics.physics.solverIterations - dynamics.iterations)
    out.update(frames.held_back(contactTests=tracker.deferred, contactPairs=tracker.unrecorded,
                                physicsSteps=steps, solverIterations=iterations))
    return out


def watched_wire(bodies: SceneBodies, watches: Watches,
                 nodes: Mapping[str, Node]) -> dict[str, dict[str, Any]]:
    """The readings of every watched sensor as frames and snapshots carry them."""
    return {i: reading.wire() for i, reading in watched_readings(bodies, watches, nodes).items()}


def watched_readings(bodies: SceneBodies, watches: Watches,
                     nodes: Mapping[str, Node]) -> dict[str, Reading]:
    """Readings of every watched sensor (frames carry them); forgets deleted ones."""
    ids = watches.ids()
    watches.forget(i for i in ids if i not in nodes)
    return bodies.read([nodes[i] for i in ids if i in nodes], exact=False)
