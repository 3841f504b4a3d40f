"""The class of each type a client may make, by its manual name."""

from __future__ import annotations

from ..model.hands import AnthroHand, EdgedHand, RoundHand
from ..model.imported import ImportedRobot
from ..model.gltf_parts import AnthroPalm, AnthroThumb, GLTFPart, RoundFinger, RoundPalm
from ..model.motor import Motor, MotorX, MotorY, MotorZ, Slider
from ..model.node import Node, Slot
from ..model.page_meshes import SceneMesh
from ..model.parts import Ball, Box, EdgedFinger, EdgedPalm, EdgedTip, Part
from ..model.robot import Robot
from ..model.sensor import Sensor


NODE_CLASSES: dict[str, type[Node]] = {cls.type_name: cls for cls in (
    Slot, Part, Motor, Slider, MotorX, MotorY, MotorZ, Ball, Box, EdgedFinger, EdgedTip, EdgedPalm,
    Sensor, Robot, EdgedHand, GLTFPart, RoundFinger, RoundPalm, AnthroPalm, AnthroThumb,
    RoundHand, AnthroHand, SceneMesh, ImportedRobot)}
