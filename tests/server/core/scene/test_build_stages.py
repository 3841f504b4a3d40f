"""A big batch of new parts gets its bodies over several ticks, each tick's share bounded."""

from server.core.model.parts import Ball, Box
from server.core.scene.build_stages import STAGE, BuildStages


def test_a_tower_made_in_one_batch_is_built_over_ticks_each_within_the_stage(scene):
    # 300 boxes stacked in one batch: the tick that built them all took one step of 440 ms
    # (Bullet's solver grew its arrays a contact row at a time)
    scene.set_physics("dynamic")
    with scene.journal.transaction():
        for i in range(300):
            Box(scene, f"b{i}", 0.5, 0.5, 0.5).set_position((0, 0.26 + 0.5 * i, 0))
    built, ticks = [0], 0
    while built[-1] < 300:
        scene.tick(1 / 60)
        built.append(len(scene.bodies))
        ticks += 1
        assert ticks < 100, built
    assert ticks > 2  # not in one tick
    for before, now in zip(built[1:], built[2:]):  # after the first: within the stage
        made = now - before  # each box: its one part × the world's parts with it
        assert made * before + made * (made + 1) // 2 <= STAGE or made == 1
    # in the order they were made: the lowest boxes first
    assert all(f"b{i}" in scene.bodies.physics for i in range(built[1]))
    assert scene.nodes["b299"].position[1] > scene.nodes["b0"].position[1]


def test_a_request_that_reads_the_physics_between_ticks_builds_what_waits(scene):
    scene.set_physics("dynamic")
    with scene.journal.transaction():
        balls = [Ball(scene, f"b{i}", 0.2) for i in range(400)]
        for ball in balls:
            ball.set_position((0, 2, 0))
    scene.tick(1 / 60)
    assert 0 < len(scene.bodies) < 400
    assert scene.bodies.touching(balls[-1]) == []  # exact: measured now, so built now
    assert len(scene.bodies) == 400


def test_the_same_batch_is_built_the_same_way_every_time():
    from server.core.scene.scene import Scene

    def run() -> list[tuple[float, ...]]:
        scene = Scene("again")
        try:
            scene.set_physics("dynamic")
            # paused and stepped: every step with every solver iteration (a running
            # scene trades iterations for time, which a loaded machine made differ)
            scene.clock.pause("test")
            with scene.journal.transaction():
                for i in range(250):
                    Ball(scene, f"b{i}", 0.2).set_position((0, 2, 0))
            for _ in range(40):
                scene.tick(1 / 60)
            return [scene.nodes[f"b{i}"].position for i in range(250)]
        finally:
            scene.close()
    assert run() == run()  # counted, not timed: the same on any machine and load


def test_outside_a_tick_everything_is_admitted_and_within_one_the_first_tree_always_is():
    stages = BuildStages()
    assert stages.admits(10_000, 10_000)
    with stages.tick():
        assert stages.admits(500, 0)  # bigger than the stage, but the first of the tick
        assert not stages.admits(1, 500)
        assert not stages.admits(1, 0)  # once one waits, every later one waits
    assert stages.admits(1, 0)
