"""The manual's Sensor, with readings either exact (a round trip) or from the frames."""

from __future__ import annotations

from typing import Any

from .codec import from_wire
from .objects import Node, Part
from .session import Session


class Sensor(Part):
    """Manual ``Sensor(visible=True, laser_color=None)``: senses along its local +Y.

    An unwatched sensor asks the server at every reading, so the reading reflects every
    earlier call of this client. After :meth:`watch` the readings come with every frame
    and a reading is the last frame's, with no round trip (what an animation loop
    wants); ``exact=True`` asks the server anyway.
    """

    _type = "Sensor"

    def __init__(self, visible: bool | None = None, laser_color: Any = None, *,
                 scene: Session | None = None) -> None:
        self._watched = False
        self._create(scene, visible, laser_color)

    def watch(self, on: bool = True) -> Sensor:
        """Have every frame carry this sensor's readings (or stop); returns the sensor."""
        self._call("watch", on)
        self._watched = on
        return self

    def delete(self) -> None:
        """Remove the sensor; later readings raise :class:`~virtual_prosthetics.ServerError`."""
        self._watched = False
        super().delete()

    def _framed(self, exact: bool) -> dict[str, Any] | None:
        """The last frame's reading when watched (None until one has come)."""
        if exact or not getattr(self, "_watched", False):
            return None
        self._scene.connection.raise_deferred()
        with self._scene.lock:
            return self._scene.mirror.readings.get(self.id)

    def _ask(self, method: str, *args: Any) -> Any:
        return self._scene.call(self.id, method, args, wait=True)

    def sense_distance(self, exact: bool = False) -> float:
        """Manual ``senseDistance()``: distance along +Y to a body past 0.05, or inf."""
        reading = self._framed(exact)
        value = reading["distance"] if reading else self._ask("senseDistance")
        return float(from_wire(value))

    def sense_touch(self, exact: bool = False) -> float:
        """Manual ``senseTouch()``: 0 (nothing within 0.05) to 1 (touching the pad)."""
        reading = self._framed(exact)
        return float(reading["touch"] if reading else self._ask("senseTouch"))

    def sense_position(self, exact: bool = False) -> list[float]:
        """Manual ``sensePosition()``: the sensor's world position [x, y, z]."""
        reading = self._framed(exact)
        return list(reading["position"] if reading else self._ask("sensePosition"))

    def sense_force(self, other: Node | str | None = None, exact: bool = False) -> float:
        """Newtons pressing on the sensor's part (dynamic mode; 0 in kinematic mode), from
        everything, or from ``other`` alone (a part or "ground"): a fingertip's force on
        what it holds, not on the table beside it."""
        reading = self._framed(exact)
        if not reading:
            return float(self._ask("senseForce", *(() if other is None else (other,))))
        if other is None:
            return float(reading["force"])
        other_id = other if isinstance(other, str) else other.id
        return next((float(force["normal"]) for force in reading["contacts"]
                     if force["other"] == other_id), 0.0)

    def sense_contacts(self, exact: bool = False) -> list[dict[str, Any]]:
        """What presses on the sensor's part, body by body (dynamic mode; none in kinematic
        mode): ``{"other", "normal", "friction"}`` with ``other`` this client's object
        itself (other objects and the ground as ids), forces in newtons, the largest
        normal force first."""
        reading = self._framed(exact)
        forces = reading["contacts"] if reading else self._ask("senseContacts")
        return [{**force, "other": self._scene.resolve(force["other"])} for force in forces]

    def _objects(self, exact: bool) -> list[str]:
        reading = self._framed(exact)
        if reading:
            return list(reading["objects"])
        return [ref["ref"] for ref in self._ask("senseObjects")]

    def sense_objects(self, exact: bool = False) -> list[Node | str]:
        """Manual ``senseObjects()``: what the sensor's part touches.

        This client's objects come back as themselves; other clients' objects and the
        ground ("ground") as their ids.
        """
        return [self._scene.resolve(node_id) for node_id in self._objects(exact)]

    def sense_collision(self, exact: bool = False) -> bool:
        """Manual ``senseCollision()``: whether the sensor's part touches anything."""
        return bool(self._objects(exact))

    def sense_object(self, other: Node | str, exact: bool = False) -> bool:
        """Manual ``senseObject(other)``: whether the sensor's part touches ``other``."""
        if not isinstance(other, str) and not isinstance(other, Part):
            raise TypeError(f"sense_object needs a part or 'ground', got {other!r}")
        other_id = other if isinstance(other, str) else other.id
        return other_id in self._objects(exact)
