"""Reading the viewer's screenshots: where a world point lands, and what colour is there."""

from __future__ import annotations

import io
import math
from typing import Sequence

from PIL import Image

FOV = 30.0  # the viewer's vertical field of view, degrees (parts.md)
BACKGROUND = (220, 220, 220)  # gainsboro


def _sub(a, b):
    return [x - y for x, y in zip(a, b)]


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _unit(a):
    length = math.sqrt(_dot(a, a))
    return [x / length for x in a]


DEFAULT_CAMERA = ((4, 4, 7), (0, 1, 0))  # the viewer's camera unless a scene moves it: position, target


def project(point: Sequence[float], eye: Sequence[float], target: Sequence[float],
            size: tuple[int, int]) -> tuple[int, int]:
    """The pixel where a world point appears for a camera at ``eye`` looking at ``target``."""
    width, height = size
    forward = _unit(_sub(target, eye))
    right = _unit(_cross(forward, [0, 1, 0]))
    up = _cross(right, forward)
    v = _sub(point, eye)
    depth = _dot(v, forward)
    half = math.tan(math.radians(FOV) / 2)
    x = _dot(v, right) / (depth * half * width / height)
    y = _dot(v, up) / (depth * half)
    return round((x + 1) / 2 * width), round((1 - y) / 2 * height)


class Picture:
    """A decoded screenshot."""

    def __init__(self, png: bytes) -> None:
        self.image = Image.open(io.BytesIO(png)).convert("RGB")
        self.size = self.image.size

    def at(self, pixel: tuple[int, int], radius: int = 2) -> tuple[int, int, int]:
        """The mean colour of a small square around a pixel."""
        x0, y0 = pixel
        box = [self.image.getpixel((x, y)) for x in range(x0 - radius, x0 + radius + 1)
               for y in range(y0 - radius, y0 + radius + 1)]
        return tuple(sum(c[i] for c in box) // len(box) for i in range(3))  # type: ignore[return-value]

    def share(self, test) -> float:
        """The fraction of pixels whose colour passes ``test``."""
        pixels = list(self.image.get_flattened_data())
        return sum(1 for p in pixels if test(p)) / len(pixels)


def reddish(colour: Sequence[int]) -> bool:
    r, g, b = colour
    return r > 110 and r > 1.8 * g and r > 1.8 * b


def background_like(colour: Sequence[int], tolerance: int = 40) -> bool:
    """Grey: the ground or the sky of the picture, nothing drawn on it."""
    return max(colour) - min(colour) < 12 and all(abs(c - 200) < tolerance for c in colour)
