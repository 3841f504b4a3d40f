"""Robot hands as files, made by the tests: a URDF hand in a zip with ``package://`` meshes.

The hand is human-sized, in metres and kilograms: a palm (a box, 0.09 × 0.10 × 0.025 m),
a thumb and two fingers of three links each (cylinders, the tips STL meshes from the
package ``handpkg``), the middle and distal joints of each finger following the proximal
one (``<mimic>``), and a fixed camera mount. Its figures are module constants, so tests
check the import against what the file says.
"""

from __future__ import annotations

import io
import math
import zipfile

import trimesh

PALM = (0.09, 0.10, 0.025)
PALM_MASS = 0.4
SEGMENT = 0.04             # each finger link's length (m)
RADIUS = 0.009
DIGITS = {"thumb": (-0.05, 0.02, 0.6), "index": (-0.025, 0.05, 0.0), "middle": (0.02, 0.05, 0.0)}
LIMITS = (0.0, 1.6)        # radians, every joint
MIMIC = (0.8, 0.05)        # multiplier, offset of each middle and distal joint
TIP_COLOR = (0.9, 0.2, 0.2, 1.0)
AXIS = (1.0, 0.0, 0.0)     # the joints' axis: flexion about x


def tip_stl() -> bytes:
    """A fingertip: a capsule-like rounded cylinder, as a binary STL."""
    tip = trimesh.creation.capsule(height=SEGMENT - 2 * RADIUS, radius=RADIUS, count=[12, 6])
    tip.apply_translation((0, 0, SEGMENT / 2))
    return tip.export(file_type="stl")


def hand_urdf(mesh_ref: str = "package://handpkg/meshes/tip.stl", extra: str = "") -> str:
    """The hand's URDF; ``mesh_ref`` is how it names the tip mesh."""
    parts = [f"""<robot name="test_hand">
  <material name="skin"><color rgba="0.8 0.7 0.6 1"/></material>
  <link name="palm">
    <visual><geometry><box size="{PALM[0]} {PALM[1]} {PALM[2]}"/></geometry><material name="skin"/></visual>
    <collision><geometry><box size="{PALM[0]} {PALM[1]} {PALM[2]}"/></geometry></collision>
    <inertial><mass value="{PALM_MASS}"/><inertia ixx="4e-4" iyy="3e-4" izz="6e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <contact><lateral_friction value="0.9"/></contact>
  </link>
  <link name="camera_mount"><visual><geometry><sphere radius="0.01"/></geometry></visual></link>
  <joint name="camera_fix" type="fixed"><parent link="palm"/><child link="camera_mount"/>
    <origin xyz="0 -0.05 0.02"/></joint>"""]
    for digit, (x, y, spread) in DIGITS.items():
        parent = "palm"
        for k, segment in enumerate(("proximal", "middle", "distal")):
            link, joint = f"{digit}_{segment}", f"{digit}_{segment}_joint"
            if segment == "distal":
                shape = f'<mesh filename="{mesh_ref}"/>'
                colour = f'<material name="tip"><color rgba="{" ".join(map(str, TIP_COLOR))}"/></material>'
                offset = ""
            else:
                shape = f'<cylinder radius="{RADIUS}" length="{SEGMENT}"/>'
                colour, offset = "", f'<origin xyz="0 0 {SEGMENT / 2}"/>'
            origin = f'xyz="{x} {y} 0" rpy="{-math.pi / 2} 0 {spread}"' if k == 0 else \
                f'xyz="0 0 {SEGMENT}"'
            mimic = "" if k == 0 else \
                f'<mimic joint="{digit}_proximal_joint" multiplier="{MIMIC[0]}" offset="{MIMIC[1]}"/>'
            parts.append(f"""  <link name="{link}">
    <visual>{offset}<geometry>{shape}</geometry>{colour}</visual>
    <collision>{offset}<geometry>{shape}</geometry></collision>
    <inertial><origin xyz="0 0 {SEGMENT / 2}"/><mass value="0.02"/><inertia ixx="3e-6" iyy="3e-6" izz="1e-6" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="{joint}" type="revolute"><parent link="{parent}"/><child link="{link}"/>
    <origin {origin}/><axis xyz="{' '.join(map(str, AXIS))}"/>
    <limit lower="{LIMITS[0]}" upper="{LIMITS[1]}" effort="0.5" velocity="3"/>{mimic}</joint>""")
            parent = link
    return "\n".join(parts) + extra + "\n</robot>\n"


# a gripper's jaws on the palm: sliding (prismatic) along x, the second mirroring the first
SLIDE_LIMITS = (0.0, 0.03)  # m
SLIDE_EFFORT = 15.0         # N
JAW = """
  <link name="{0}"><visual><geometry><box size="0.01 0.02 0.02"/></geometry></visual>
    <collision><geometry><box size="0.01 0.02 0.02"/></geometry></collision>
    <inertial><mass value="0.01"/><inertia ixx="1e-6" iyy="1e-6" izz="1e-6" ixy="0" ixz="0" iyz="0"/></inertial></link>"""
JAWS = JAW.format("jaw_a") + JAW.format("jaw_b") + f"""
  <joint name="jaw_a_slide" type="prismatic"><parent link="palm"/><child link="jaw_a"/>
    <origin xyz="-0.04 -0.06 0.02" rpy="0 0 0.3"/><axis xyz="1 0 0"/>
    <limit lower="{SLIDE_LIMITS[0]}" upper="{SLIDE_LIMITS[1]}" effort="{SLIDE_EFFORT}" velocity="0.1"/></joint>
  <joint name="jaw_b_slide" type="prismatic"><parent link="palm"/><child link="jaw_b"/>
    <origin xyz="0.04 -0.06 0.02"/><axis xyz="-1 0 0"/>
    <limit lower="{SLIDE_LIMITS[0]}" upper="{SLIDE_LIMITS[1]}" effort="{SLIDE_EFFORT}" velocity="0.1"/>
    <mimic joint="jaw_a_slide" multiplier="1" offset="0.001"/></joint>"""


def motor_names() -> list[str]:
    """The hand's joints that become motors, in the order the robot lists them."""
    return [f"{digit}_{segment}_joint" for digit in DIGITS for segment in ("proximal", "middle", "distal")]


def zipped(files: dict[str, bytes | str]) -> bytes:
    """A zip of ``files`` (path → content)."""
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for path, content in files.items():
            archive.writestr(path, content)
    return out.getvalue()


def hand_zip(extra: str = "") -> bytes:
    """The hand as a ROS package would ship it: ``handpkg/urdf/hand.urdf`` and its mesh
    (``extra``: more of the URDF, such as :data:`JAWS`)."""
    return zipped({"handpkg/package.xml": "<package><name>handpkg</name></package>",
                   "handpkg/urdf/hand.urdf": hand_urdf(extra=extra),
                   "handpkg/meshes/tip.stl": tip_stl()})


def stored_hand(library, extra: str = "") -> str:
    """The hand read and kept in an asset library (as an upload is); its robot file's name."""
    from server.core.kit.limits import DEFAULT
    from server.core.physics.robot_archive import open_archive
    from server.core.physics.urdf_reading import read_urdf
    from server.web.storage.upload_folder import UploadFolder

    robot = read_urdf(open_archive(hand_zip(extra), None, DEFAULT), DEFAULT,
                      lambda glb: UploadFolder(library).store(glb, DEFAULT)["name"])
    return UploadFolder(library).store_robot(robot, DEFAULT)["name"]


# --- an MJCF hand: includes, default classes, degrees, meshdir, a tendon and an equality ---

MJCF_LIMITS_DEG = (0.0, 95.0)
MJCF_EQUALITY = (0.7, 0.02)   # the index's distal joint follows its middle: ratio, offset
MJCF_MASS = 0.35


def mjcf_files() -> dict[str, bytes | str]:
    """A three-digit MJCF hand as a zip's files: ``hand/scene.xml`` includes the defaults
    and the hand (``hand/parts/*.xml``); the tips are STL meshes from ``meshdir``; the
    thumb's two outer joints are one fixed tendon pulled by an actuator, the index's
    distal joint follows its middle one by an equality; the middle finger's knuckle turns
    about an anchor away from its body's origin, and its base has two hinges (spread,
    flex)."""
    defaults = """<mujoco><default>
  <default class="digit"><joint type="hinge" axis="1 0 0" range="0 95" damping="0.05"/>
    <geom type="capsule" size="0.009 0.015" pos="0 0 0.02" rgba="0.8 0.7 0.6 1" mass="0.015"/>
    <default class="tip"><geom type="mesh" mesh="tip" pos="0 0 0" rgba="0.9 0.2 0.2 1"/></default>
  </default></default></mujoco>"""
    digits = []
    for name, x, spread in (("thumb", -0.05, 35), ("index", -0.025, 0), ("middle", 0.02, 0)):
        base = (f'<joint name="{name}_spread" axis="0 1 0" range="-20 20"/>' if name == "middle" else "")
        anchor = ' pos="0 0 -0.005"' if name == "middle" else ""
        digits.append(f"""<body name="{name}_proximal" childclass="digit" pos="{x} 0.05 0" euler="-90 0 {spread}">
      {base}<joint name="{name}_knuckle"{anchor}/><geom/>
      <body name="{name}_middle" pos="0 0 0.04"><joint name="{name}_middle_joint"/><geom/>
        <body name="{name}_distal" pos="0 0 0.04"><joint name="{name}_distal_joint"/><geom class="tip"/></body>
      </body></body>""")
    hand = f"""<mujoco><worldbody>
  <body name="palm" pos="0 0.2 0"><geom type="box" size="0.045 0.05 0.0125" rgba="0.8 0.7 0.6 1" mass="{MJCF_MASS}"/>
    <geom type="box" size="0.045 0.05 0.0125" contype="0" conaffinity="0" group="2" rgba="0 0 1 1"/>
    {''.join(digits)}
  </body></worldbody></mujoco>"""
    scene = f"""<mujoco model="mjcf_hand">
  <compiler angle="degree" meshdir="meshes"/>
  <include file="parts/defaults.xml"/>
  <asset><mesh name="tip" file="tip.stl"/></asset>
  <include file="parts/hand.xml"/>
  <worldbody><geom name="floor" type="plane" size="1 1 0.1"/></worldbody>
  <tendon><fixed name="thumb_curl"><joint joint="thumb_middle_joint" coef="1"/><joint joint="thumb_distal_joint" coef="1"/></fixed></tendon>
  <equality><joint joint1="index_distal_joint" joint2="index_middle_joint" polycoef="{MJCF_EQUALITY[1]} {MJCF_EQUALITY[0]} 0 0 0"/></equality>
  <actuator><position name="thumb_pull" tendon="thumb_curl" kp="2"/><position name="index" joint="index_knuckle" kp="2"/></actuator>
</mujoco>"""
    return {"hand/scene.xml": scene, "hand/parts/defaults.xml": defaults, "hand/parts/hand.xml": hand,
            "hand/meshes/tip.stl": tip_stl()}


def mjcf_zip() -> bytes:
    return zipped(mjcf_files())
