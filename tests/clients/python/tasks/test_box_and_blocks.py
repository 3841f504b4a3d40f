"""``box-and-blocks`` against the real server: the box, its 150 blocks, the count."""

import random

import pytest

from virtual_prosthetics.tasks import box_and_blocks as bb
from virtual_prosthetics.tasks.hands import hand_source
from virtual_prosthetics.tasks.trial import TaskHand


def test_the_box_holds_150_blocks_on_one_side_and_counts_those_put_across(scene):
    scene.set_physics("dynamic")
    scene.sync()
    stage = bb.build(scene, TaskHand(hand_source("edged", scene)), random.Random(0))
    scene.sync()
    positions = stage.block_positions()
    assert len(positions) == bb.BLOCKS == 150
    assert all(p[0] < stage.partition_x for p in positions)
    assert stage.moved() == 0
    block = stage.scale.length(bb.BLOCK)
    for cube in stage.blocks[:3]:  # three put over the partition by hand
        cube.set_position(block * 3, stage.floor + block, 0)
    bb.drive(scene, 0.5, lambda t: None)
    assert stage.moved() == 3
    stage.remove()
    scene.sync()
    assert scene.read(lambda mirror: len(mirror.nodes)) == 0


def test_box_and_blocks_counts_as_the_examiner_does(scene):
    # the finding: a block past the partition counted even when the fingertips never
    # crossed, and two carried together counted two (Mathiowetz: one at a time, tips across)
    def carries(stage):
        hand_at = list(scene.read(lambda mirror: mirror.nodes[stage.hand.id]["position"]))
        over = stage.scale.length(0.15)

        def control(t):
            block = stage.scale.length(bb.BLOCK)
            if 0.2 < t < 0.25:  # two go over together, the hand still on the start side
                for i, cube in enumerate(stage.blocks[:2]):
                    cube.set_position(over, stage.floor + block * (1 + 2 * i), 0)
            if 0.5 < t < 1.0:  # then the hand follows them: one carry, one block
                stage.hand.set_position(over + stage.scale.length(0.1), *hand_at[1:])
            if t > 1.0:
                stage.hand.set_position(*hand_at)
            if 1.5 < t < 1.55:  # one thrown over with the hand back home: not counted
                stage.blocks[2].set_position(over, stage.floor + block, 0)
        return control

    result = bb.box_and_blocks(scene, TaskHand(hand_source("edged", scene)), 0, controller=carries,
                               seconds=2.0, blocks=20)
    assert result["task"] == "box-and-blocks" and result["seconds"] == 2.0
    assert (result["blocks"], result["blocksAcross"], result["blocksOver"]) == (1, 3, 3), result
