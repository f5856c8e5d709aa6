"""Arc geometry for translations (docs/translation.md, rule X9).

Hyrel's plain G2/G3 draw in the XY plane only, take I/J centres (no R, no K) and compute their flow
natively even under ``M229 E1`` (Hyrel Gcode page, G2).  So an arc in the XZ or YZ plane, an arc with
extra turns, or an arc whose E amount matters is written as G1 segments; an R-form arc gets its centre.
Planes follow grbl's convention: G17 (X, Y; I, J; helix Z), G18 (Z, X; K, I; helix Y), G19 (Y, Z; J, K;
helix X).
"""

from __future__ import annotations

import math

PLANES: dict[int, tuple[str, str, str, str, str]] = {
    17: ("X", "Y", "I", "J", "Z"),
    18: ("Z", "X", "K", "I", "Y"),
    19: ("Y", "Z", "J", "K", "X"),
}

CHORD_TOLERANCE = 0.02  # mm: the largest distance between a segment and the true arc
MAX_SEGMENT = 1.0  # mm (Marlin's MM_PER_ARC_SEGMENT)
MAX_SEGMENTS = 5000


class ArcError(ValueError):
    """An arc that cannot be drawn (radius too small for the chord, unknown start)."""


def centre_from_radius(dx: float, dy: float, radius: float, clockwise: bool) -> tuple[float, float]:
    """The centre offset (I, J) of an R-form arc from the start to (dx, dy) (grbl's formula).

    A negative radius asks for the arc longer than a half circle.
    """
    chord2 = dx * dx + dy * dy
    if chord2 == 0:
        raise ArcError("R-form arc with the same start and end (a full circle needs I/J)")
    disc = 4 * radius * radius - chord2
    if disc < -1e-9 * max(1.0, 4 * radius * radius):
        raise ArcError(f"radius {radius:g} is too small for a chord of {math.sqrt(chord2):.4g}")
    h = -math.sqrt(max(disc, 0.0)) / math.sqrt(chord2)
    if not clockwise:
        h = -h
    if radius < 0:
        h = -h
    return (dx - dy * h) / 2, (dy + dx * h) / 2


def sweep(
    start: tuple[float, float], end: tuple[float, float], centre: tuple[float, float], clockwise: bool, turns: int = 0
) -> float:
    """The signed angle (radians) the arc sweeps: negative clockwise; a full circle when start == end."""
    a0 = math.atan2(start[1] - centre[1], start[0] - centre[0])
    a1 = math.atan2(end[1] - centre[1], end[0] - centre[0])
    angle = a1 - a0
    if clockwise:
        if angle >= -1e-9:
            angle -= 2 * math.pi
    else:
        if angle <= 1e-9:
            angle += 2 * math.pi
    extra = 2 * math.pi * turns
    return angle - extra if clockwise else angle + extra


def segments(
    start: dict[str, float],
    end: dict[str, float],
    offsets: tuple[float, float],
    clockwise: bool,
    plane: int = 17,
    turns: int = 0,
    *,
    tolerance: float = CHORD_TOLERANCE,
    max_segment: float = MAX_SEGMENT,
) -> list[dict[str, float]]:
    """Points along the arc from ``start`` to ``end`` (dicts of axis -> absolute value, the three axes
    of the plane), the last one being ``end`` exactly.  ``tolerance`` and ``max_segment`` are in the
    unit of the coordinates (an inch job: 0.02 mm is 0.02 / 25.4 in)."""
    a, b, _, _, helix = PLANES[plane]
    centre = (start[a] + offsets[0], start[b] + offsets[1])
    radius = math.hypot(offsets[0], offsets[1])
    if radius == 0:
        raise ArcError("arc with a zero radius")
    angle = sweep((start[a], start[b]), (end[a], end[b]), centre, clockwise, turns)
    length = abs(angle) * radius
    seg = min(max_segment, math.sqrt(8 * radius * tolerance)) if radius > tolerance / 2 else max_segment
    count = max(1, min(MAX_SEGMENTS, math.ceil(length / seg)))
    a0 = math.atan2(start[b] - centre[1], start[a] - centre[0])
    points = []
    for k in range(1, count):
        t = k / count
        theta = a0 + angle * t
        points.append(
            {
                a: centre[0] + radius * math.cos(theta),
                b: centre[1] + radius * math.sin(theta),
                helix: start[helix] + (end[helix] - start[helix]) * t,
            }
        )
    points.append({a: end[a], b: end[b], helix: end[helix]})
    return points
