"""Parts: the base part, the common shapes and the edged hand parts."""

from __future__ import annotations

from typing import Any, Sequence

from ..kit.math3d import ORIGIN, Vec3, euler_to_quat
from ..kit.numbers import Finite
from ..physics.geometry import scaled, volume
from . import part_figures
from .node import UNIT_SCALE, Node, Slot, World


class Part(Node):
    """A building element of a robot; the base part is invisible and has no shape."""

    type_name = "Part"
    listed = True  # one of its robot's getParts()

    def __init__(self, scene: World, node_id: str) -> None:
        super().__init__(scene, node_id)
        self._slot_count = 0
        self.mass: float | None = None      # kg in dynamic mode (None: volume × density)
        self.friction: float | None = None  # lateral friction in dynamic mode (None: the scene's)
        self.static = False                 # a top-level part that never moves in dynamic mode

    def new_slot(self, position: Vec3 = ORIGIN, rotation: Vec3 | None = None,
                 order: str = "XYZ") -> Slot:
        """Create one of this part's own slots (id ``<part>/s<k>``) and add it."""
        slot = Slot(self.scene, f"{self.id}/s{self._slot_count}", position)
        self._slot_count += 1
        if rotation is not None:
            slot.quaternion = euler_to_quat(*rotation, order)
        self.add_slot_node(slot)
        return slot

    def add_slot(self, position: Vec3 = ORIGIN) -> Slot:
        """Manual ``addSlot(x, y, z)``: a new slot at a position relative to the part."""
        return self.new_slot(position)

    def attach_to_slot(self, parent: Node, slot: int | Slot = 0) -> Part:
        """Manual ``attachToSlot(parent, slot=0)``: by index, by Slot object, or to the parent."""
        if isinstance(slot, Slot):
            if slot.parent is not parent:  # a child of parent, not one of parent.slots
                slot.leave_slots()
                slot._link(parent)
            target: Node = slot
        elif 0 <= slot < len(parent.slots):
            target = parent.slots[slot]
        else:
            target = parent
            if parent.slots or slot != 0:
                self.scene.warn(f"{parent.id} has {len(parent.slots)} slots and no slot {slot}: "
                                f"{self.id} is attached to {parent.id} itself, as 1.0 does")
        self._link(target)
        return self

    # --- dynamic mode (not in the manual) -------------------------------------------

    def set_mass(self, mass: float) -> Part:
        """The part's mass in kilograms in dynamic mode (instead of its volume times the
        scene's density); returns the part."""
        self._assign("mass", float(mass))
        return self

    def get_mass(self) -> float:
        """The part's mass in dynamic mode (kg): its own, or its volume (as stretched by the
        scales above it, in the scene's unit) times the scene's density; 0 for a part
        without a body."""
        if self.mass is not None:
            return self.mass
        geometry = self.geometry()
        if not self.physical or geometry is None:
            return 0.0
        scale = self.world_scale()
        shape = geometry if scale == UNIT_SCALE else scaled(geometry, scale)
        return self.scene.physics.density * volume(shape) * self.scene.physics.unit ** 3

    def set_friction(self, friction: float) -> Part:
        """The part's friction coefficient in dynamic mode (instead of the scene's); returns
        the part."""
        self._assign("friction", float(friction))
        return self

    def set_static(self, static: bool = True) -> Part:
        """In dynamic mode a part at the top of its tree never moves (a table, a box's
        walls); attached to anything it moves with it. Returns the part."""
        self._assign("static", bool(static))
        return self

    @property
    def saved_static(self) -> bool | None:
        """``static`` as documents keep it: only when set."""
        return True if self.static else None

    def geometry(self) -> dict[str, Any] | None:
        """What the part looks like (and, when physical, its collision envelope)."""
        return None

    def properties(self) -> dict[str, Any]:
        geometry = self.geometry()
        shape = {"geometry": geometry, "physical": self.physical} if geometry else {}
        return {**shape, "mass": self.mass, "friction": self.friction, "static": self.static}


class Ball(Part):
    """A sphere centred at the part's origin."""

    type_name = "Ball"
    physical = True

    def __init__(self, scene: World, node_id: str, radius: float = 1.0,
                 color: str | int = part_figures.DEFAULT_COLOR) -> None:
        super().__init__(scene, node_id)
        self.radius, self.color = radius, color

    def constructor_args(self) -> list[Any]:
        return [self.radius, self.color]

    def geometry(self) -> dict[str, Any]:
        return {"kind": "sphere", "radius": self.radius, "color": self.color}


class Box(Part):
    """A box centred at the part's origin."""

    type_name = "Box"
    physical = True

    def __init__(self, scene: World, node_id: str, sizex: float = 1.0, sizey: float = 1.0,
                 sizez: float = 1.0, color: str | int = part_figures.DEFAULT_COLOR) -> None:
        super().__init__(scene, node_id)
        self.size, self.color = (sizex, sizey, sizez), color

    def constructor_args(self) -> list[Any]:
        return [*self.size, self.color]

    def geometry(self) -> dict[str, Any]:
        return {"kind": "box", "size": list(self.size), "color": self.color}


class ConvexPart(Part):
    """A part whose shape and envelope are the convex hull of a few points."""

    physical = True
    points: Sequence[Vec3] = ()

    def geometry(self) -> dict[str, Any]:
        return {"kind": "convex", "points": Finite(Finite(p) for p in self.points),
                "color": "white", "edges": "black"}


class EdgedFinger(ConvexPart):
    """An edged finger segment: one slot at the top, (0, length, 0)."""

    type_name = "EdgedFinger"
    tip = False

    def __init__(self, scene: World, node_id: str, length: float = 1.0, width: float = 0.3,
                 thickness: float = 0.3) -> None:
        super().__init__(scene, node_id)
        self.length, self.width, self.thickness = length, width, thickness
        profile = part_figures.edged_finger_profile(length, thickness, self.tip)
        self.points = part_figures.extrude(profile, width)
        self.new_slot((0.0, length, 0.0))

    def constructor_args(self) -> list[Any]:
        return [self.length, self.width, self.thickness]


class EdgedTip(EdgedFinger):
    """The last segment of an edged finger; 1.0 gives it a top slot too."""

    type_name = "EdgedTip"
    tip = True


class EdgedPalm(ConvexPart):
    """An edged palm with five finger slots, the thumb's first."""

    type_name = "EdgedPalm"

    def __init__(self, scene: World, node_id: str, left: bool = False, length: float = 1.4,
                 width: float = 1.4, thickness: float = 0.3) -> None:
        super().__init__(scene, node_id)
        self.left, self.length, self.width, self.thickness = left, length, width, thickness
        self.points = part_figures.extrude(part_figures.edged_palm_profile(left, length, width), thickness)
        for position, rotation, order in part_figures.edged_palm_slots(left, length, width):
            self.new_slot(position, rotation, order)

    def constructor_args(self) -> list[Any]:
        return [self.left, self.length, self.width, self.thickness]
