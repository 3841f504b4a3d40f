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


def test_box_and_blocks_scores_what_the_controller_moves(scene):
    def carries_one(stage):
        def control(t):
            if 0.5 < t < 0.6:  # a controller that teleports one block across, once
                stage.blocks[0].set_position(stage.scale.length(0.1), stage.floor + 1, 0)
        return control

    result = bb.box_and_blocks(scene, TaskHand(hand_source("edged", scene)), 0, controller=carries_one,
                               seconds=1.0, blocks=20)
    assert result["task"] == "box-and-blocks" and result["blocks"] == 1
    assert result["seconds"] == 1.0
