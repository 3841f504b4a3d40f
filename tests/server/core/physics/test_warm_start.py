"""Bullet's articulated warm starting, switched on through PyBullet's C API: a stack of
multibodies holds up with fewer solver iterations, and clients it cannot reach are left
alone rather than crashing the process."""

from __future__ import annotations

import pytest

from server.core.physics import warm_start
from server.core.physics.bullet import pybullet


def _tower_sinks(warm: float | None, boxes: int = 8, iterations: int = 10) -> float:
    """How far the top of a tower of 10 cm, 1 kg multibody boxes sinks in 2 s at few
    solver iterations (metres)."""
    client = pybullet.connect(pybullet.DIRECT)
    try:
        pybullet.setGravity(0, 0, -9.81, physicsClientId=client)
        pybullet.setPhysicsEngineParameter(fixedTimeStep=1 / 240, numSolverIterations=iterations,
                                           physicsClientId=client)
        if warm is not None:
            assert warm_start.enable(pybullet, client, warm)
        plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, physicsClientId=client)
        pybullet.createMultiBody(0, plane, physicsClientId=client)
        box = pybullet.createCollisionShape(pybullet.GEOM_BOX, halfExtents=[0.05] * 3, physicsClientId=client)
        tower = [pybullet.createMultiBody(1.0, box, basePosition=[0, 0, 0.05 + 0.1 * level],
                                          physicsClientId=client) for level in range(boxes)]
        for _ in range(480):
            pybullet.stepSimulation(physicsClientId=client)
        top = pybullet.getBasePositionAndOrientation(tower[-1], physicsClientId=client)[0][2]
        return 0.05 + 0.1 * (boxes - 1) - top
    finally:
        pybullet.disconnect(client)


def test_a_warm_started_tower_sinks_less_at_the_same_iterations_the_more_the_warmer():
    cold, warm, full = _tower_sinks(None), _tower_sinks(warm_start.FACTOR), _tower_sinks(1.0)
    assert 0 < full < warm < 0.7 * cold, (full, warm, cold)  # measured: 2.7, 4.1, 7.5 mm


def test_a_factor_of_zero_switches_it_off_again():
    assert _tower_sinks(0.0) == _tower_sinks(None)


def test_clients_it_cannot_reach_are_refused_and_nothing_is_sent():
    client = pybullet.connect(pybullet.DIRECT)
    pybullet.disconnect(client)
    assert not warm_start.enable(pybullet, client)  # disconnected: its handle is gone
    assert not warm_start.enable(pybullet, -1)
    table = warm_start.client_table(pybullet.__file__)
    assert table is not None and table.clients >= 16  # PyBullet's room for clients
    assert not warm_start.enable(pybullet, table.clients)


@pytest.mark.parametrize("content", [b"", b"not a library", b"\x7fELF" + b"\0" * 60])
def test_a_file_that_is_no_library_of_the_kind_has_no_symbols(tmp_path, content):
    path = tmp_path / "library.so"
    path.write_bytes(content)
    assert warm_start.symbols(str(path), (warm_start.TABLE,)) == {}
    assert warm_start.symbols(str(tmp_path / "missing.so"), (warm_start.TABLE,)) == {}


def test_the_symbols_are_found_in_pybullets_own_library():
    found = warm_start.symbols(pybullet.__file__, (warm_start.TABLE, warm_start.ANCHOR, b"noSuchSymbol"))
    assert set(found) == {warm_start.TABLE, warm_start.ANCHOR}
    assert found[warm_start.TABLE][1] % 8 == 0 and found[warm_start.TABLE][1] > 0  # a table of handles
