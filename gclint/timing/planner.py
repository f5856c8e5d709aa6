"""Moves -> time, as a firmware's planner runs them.

Each move becomes a block: its length (or, for a move of the extruder alone, the filament's), a cruise speed (the
feed, capped by each axis's largest speed), an acceleration (printing, travel or retraction, capped by each
axis's largest), and the largest speed it may enter at: the junction with the move before, limited by the jerk
of each axis (Marlin's classic jerk, which PrusaSlicer's estimator uses too) or by the junction deviation
(Marlin 2's default; Klipper's square corner velocity is a junction deviation, Klipper's toolhead.py:
``scv² (√2 - 1) / accel``).  A backward pass lowers each entry so that the block after can still be reached
braking; a forward pass lowers it so that it can be reached accelerating; then each block runs a trapezoid
(accelerate, cruise, brake).  Blocks wait in a window: when it holds ``REFRESH`` blocks, all but the last
``KEEP`` are planned, timed and dropped (the first kept block keeps the entry speed it was given, as Marlin's
planner keeps the block being executed), so time is linear and memory bounded.  A stop (a dwell, a tool change,
a wait) plans every block and ends at rest.  Where no junction rule is known (``Planner.from_rest``), every move
starts and ends at rest.
"""

from __future__ import annotations

import math

from gclint.timing.limits import MachineLimits

REFRESH = 256
KEEP = 64
_SQRT = math.sqrt


# A block is a list (the fastest to make and read): its length, acceleration, cruise speed, entry speed, the largest
# entry speed (its junction's), its safe speed (the speed it may stop from at once: its exit when nothing follows),
# whether it can reach its cruise speed from rest and back within its length, and its number in the job (``watch``).
DISTANCE, ACCEL, CRUISE, ENTRY, MAX_ENTRY, SAFE, NOMINAL, NUMBER = range(8)


def trapezoid_time(distance: float, accel: float, cruise: float, entry: float, exit_: float) -> float:
    """The time of one block: accelerate from ``entry`` towards ``cruise``, cruise, brake to ``exit_`` (a junction
    faster than the cruise speed, which classic jerk allows, is a jump: no time)."""
    if accel <= 0:
        return distance / cruise
    if entry > cruise:
        entry = cruise
    if exit_ > cruise:
        exit_ = cruise
    twice = 2 * accel
    up = (cruise * cruise - entry * entry) / twice
    down = (cruise * cruise - exit_ * exit_) / twice
    if up < 0:
        up = 0.0
    if down < 0:
        down = 0.0
    middle = distance - up - down
    if middle >= 0:
        return (cruise - entry) / accel + middle / cruise + (cruise - exit_) / accel
    # no room to reach the cruise speed: accelerate to where braking must begin
    up = (twice * distance - entry * entry + exit_ * exit_) / (2 * twice)
    if up < 0:
        up = 0.0
    elif up > distance:
        up = distance
    peak = _SQRT(entry * entry + twice * up)
    end = peak * peak - twice * (distance - up)
    end = _SQRT(end) if end > 0 else 0.0
    return (peak - entry) / accel + (peak - end) / accel


class Planner:
    """Feed it moves (``move``) and stops (``stop``); ``time`` is the total once ``finish`` ran.  ``watch(key)`` asks
    for the time at the end of the last move given so far: ``watched[key]`` holds it once that move is planned."""

    def __init__(self, limits: MachineLimits) -> None:
        self.limits = limits
        self.time = 0.0
        self.moves = 0  # blocks made so far
        self.watched: dict[str, float] = {}
        self._watches: dict[int, list[str]] = {}  # block number -> the keys waiting for its end
        self._blocks: list[list] = []
        # the last block, for the junction with the next: its cruise speed (0: none, the machine is at rest), its
        # safe speed, and its exit direction (x, y, z, e per mm)
        self._prev_cruise = 0.0
        self._prev_safe = 0.0
        self._prev_dir = (0.0, 0.0, 0.0, 0.0)
        self.refresh()

    def refresh(self) -> None:
        """Read the limits again (the job changed them)."""
        lim = self.limits
        self.accelerated = lim.accelerated
        self._max_feed = tuple(getattr(lim, f"max_feed_{a}") or 0.0 for a in "xyze")
        self._max_accel = tuple(getattr(lim, f"max_accel_{a}") or 0.0 for a in "xyze")
        jerks = tuple(getattr(lim, f"jerk_{a}") for a in "xyze")
        self._jerk = tuple(math.inf if j is None else j for j in jerks)
        print_ = lim.accel_print or lim.accel_travel or 0.0
        self._accel = (print_, lim.accel_travel or print_, lim.accel_retract or print_)
        self._low = (lim.min_feed_print or 0.0, lim.min_feed_travel or 0.0)
        self._top = lim.max_feed or 0.0
        deviation = lim.junction_deviation
        if deviation is None and lim.square_corner_velocity is not None and print_ > 0:
            deviation = lim.square_corner_velocity**2 * (math.sqrt(2) - 1) / print_
        self._deviation = deviation
        self.classic = deviation is None and any(j is not None for j in jerks[:3])
        # No jerk and no junction deviation known (a job that states an acceleration and nothing of its junctions,
        # for a firmware whose defaults are not cited here): every move starts and ends at rest, as a jerk of 0
        # asks, and as a firmware without look-ahead runs ("a dead stop every move", Teacup's config.h, LOOKAHEAD)
        self.from_rest = self.accelerated and deviation is None and not self.classic

    def move(
        self,
        dx: float,
        dy: float,
        dz: float,
        de: float,
        feed: float,
        length: float | None = None,
        entry_dir: tuple | None = None,
        exit_dir: tuple | None = None,
    ) -> None:
        """One move: its axes' displacements (mm; ``de`` the filament), its feed (mm/min); an arc gives its
        ``length`` and the XYZ directions it starts and ends in."""
        if feed <= 0:
            return
        xyz = length if length is not None else _SQRT(dx * dx + dy * dy + dz * dz)
        if xyz > 0:
            distance = xyz
        else:
            distance = -de if de < 0 else de
            if distance == 0:
                return
        speed = feed / 60
        low = self._low[1] if de == 0 else self._low[0]
        if speed < low:
            speed = low
        inv = 1 / distance
        ux, uy, uz, ue = dx * inv, dy * inv, dz * inv, de * inv
        ax = -ux if ux < 0 else ux
        ay = -uy if uy < 0 else uy
        az = -uz if uz < 0 else uz
        ae = -ue if ue < 0 else ue
        # the cruise speed: the feed, capped so that no axis runs above its largest speed
        fx, fy, fz, fe = self._max_feed
        cruise = speed
        if fx and speed * ax > fx:
            cruise = fx / ax
        if fy and cruise * ay > fy:
            cruise = fy / ay
        if fz and cruise * az > fz:
            cruise = fz / az
        if fe and cruise * ae > fe:
            cruise = fe / ae
        top = self._top
        if top and cruise > top:
            cruise = top
        self.moves += 1
        if not self.accelerated:
            self.time += distance / cruise
            return
        # the acceleration: of travel (no filament forward), of the extruder alone, or of printing; capped so
        # that no axis accelerates beyond its largest
        if xyz == 0:
            accel = self._accel[2]
        elif de <= 0:
            accel = self._accel[1]
        else:
            accel = self._accel[0]
        mx, my, mz, me = self._max_accel
        if mx and accel * ax > mx:
            accel = mx / ax
        if my and accel * ay > my:
            accel = my / ay
        if mz and accel * az > mz:
            accel = mz / az
        if me and accel * ae > me:
            accel = me / ae
        # the directions it starts and ends in (an arc's tangents; a line's own)
        if entry_dir is None:
            ix, iy, iz, ie = ux, uy, uz, ue
            out = (ux, uy, uz, ue)
        else:
            ix, iy, iz = entry_dir
            ie = ue
            out = (*exit_dir, ue) if exit_dir is not None else (ix, iy, iz, ue)
        prev_cruise = self._prev_cruise
        if self.classic:
            # Marlin's classic jerk (planner.cpp, HAS_CLASSIC_JERK): the speed it may start from, or stop at, at
            # once: no axis changing speed by more than its jerk
            jx, jy, jz, je = self._jerk
            safe = cruise
            v = cruise * (-ix if ix < 0 else ix)
            if v > jx and jx < safe:
                safe = jx
            v = cruise * (-iy if iy < 0 else iy)
            if v > jy and jy < safe:
                safe = jy
            v = cruise * (-iz if iz < 0 else iz)
            if v > jz and jz < safe:
                safe = jz
            v = cruise * (-ie if ie < 0 else ie)
            if v > je and je < safe:
                safe = je
            if prev_cruise > 0.0001:
                junction = self._jerk_junction(cruise, (ix, iy, iz, ie), safe, prev_cruise)
            else:
                junction = safe
        elif (deviation := self._deviation) is not None:
            safe = 0.0
            if prev_cruise > 0.0001:
                junction = self._deviation_junction(cruise, (ix, iy, iz, ie), accel, distance, prev_cruise, deviation)
            else:
                junction = 0.0
        else:  # no junction rule known: from rest (``from_rest``)
            safe = 0.0
            junction = 0.0
        allowable = _SQRT(safe * safe + 2 * accel * distance)
        self._prev_cruise = cruise
        self._prev_safe = safe
        self._prev_dir = out
        blocks = self._blocks
        blocks.append(
            [
                distance,
                accel,
                cruise,
                junction if junction < allowable else allowable,
                junction,
                safe,
                cruise <= allowable,
                self.moves,
            ]
        )
        if len(blocks) >= REFRESH:
            self._plan(KEEP)

    def _jerk_junction(self, cruise: float, into: tuple, safe: float, prev_cruise: float) -> float:
        """Marlin's classic jerk at the junction (planner.cpp, ``#if HAS_CLASSIC_JERK``): the previous block's exit
        and this one's entry may differ on each axis by that axis's jerk; coasting and reversals differ."""
        larger = prev_cruise > cruise
        junction = cruise if larger else prev_cruise
        smaller = junction / prev_cruise
        factor = 1.0
        limited = False
        prev_dir = self._prev_dir
        jerks = self._jerk
        for k in range(4):
            v_exit = prev_cruise * prev_dir[k] * smaller
            v_entry = cruise * into[k]
            if limited:
                v_exit *= factor
                v_entry *= factor
            if v_exit > v_entry:
                change = (v_exit - v_entry) if (v_entry > 0 or v_exit < 0) else max(v_exit, -v_entry)
            else:
                change = (v_entry - v_exit) if (v_entry < 0 or v_exit > 0) else max(-v_exit, v_entry)
            jerk = jerks[k]
            if change > jerk:
                factor *= jerk / change
                limited = True
        if limited:
            junction *= factor
        threshold = junction * 0.99
        if self._prev_safe > threshold and safe > threshold:
            junction = safe  # not coasting: both may start and stop at their safe speeds
        return junction

    def _deviation_junction(
        self, cruise: float, into: tuple, accel: float, distance: float, prev_cruise: float, deviation: float
    ) -> float:
        """Marlin 2's junction deviation (planner.cpp, ``#if HAS_JUNCTION_DEVIATION``): the speed at which the
        corner's centripetal acceleration, on a circle ``deviation`` from the corner, is the acceleration."""
        ox, oy, oz, oe = self._prev_dir
        ix, iy, iz, ie = into
        cos_theta = -(ox * ix + oy * iy + oz * iz + oe * ie)
        if cos_theta > 0.999999:
            return 0.0  # a reversal: from rest
        top = cruise if cruise < prev_cruise else prev_cruise
        if cos_theta < -0.999999:
            return top  # straight on
        # the acceleration along the junction's direction, capped per axis
        jx, jy, jz, je = ix - ox, iy - oy, iz - oz, ie - oe
        norm = _SQRT(jx * jx + jy * jy + jz * jz + je * je)
        junction_accel = accel
        if norm > 0:
            mx, my, mz, me = self._max_accel
            inv = 1 / norm
            part = (-jx if jx < 0 else jx) * inv
            if mx and junction_accel * part > mx:
                junction_accel = mx / part
            part = (-jy if jy < 0 else jy) * inv
            if my and junction_accel * part > my:
                junction_accel = my / part
            part = (-jz if jz < 0 else jz) * inv
            if mz and junction_accel * part > mz:
                junction_accel = mz / part
            part = (-je if je < 0 else je) * inv
            if me and junction_accel * part > me:
                junction_accel = me / part
        sin_half = _SQRT(0.5 * (1 - cos_theta))
        v2 = junction_accel * deviation * sin_half / (1 - sin_half)
        if distance < 1 and cos_theta < -0.7071067812:
            # a short segment of a curve: the curve's own radius (JD_HANDLE_SMALL_SEGMENTS)
            theta = math.acos(-cos_theta)
            if theta > 0:
                limit = distance * junction_accel / theta
                if limit < v2:
                    v2 = limit
        if v2 >= top * top:
            return top
        return _SQRT(v2)

    def watch(self, key: str) -> None:
        """Note the time when the last move given so far ends (``watched[key]``, once it is planned)."""
        if self._blocks and self._blocks[-1][NUMBER] == self.moves:
            self._watches.setdefault(self.moves, []).append(key)
        else:
            self.watched[key] = self.time  # (it is planned already, or there was none)

    def stop(self, seconds: float = 0.0) -> None:
        """The machine stops (a dwell, a wait, a tool change) for ``seconds``: every block is run, the last one
        to rest."""
        self._plan(0)
        self._prev_cruise = 0.0
        self.time += seconds

    def finish(self) -> float:
        self.stop()
        return self.time

    def _plan(self, keep: int) -> None:
        blocks = self._blocks
        n = len(blocks)
        if not n:
            return
        sqrt = _SQRT
        # backward: each block must be able to brake to the next one's entry
        following = blocks[-1][ENTRY]
        for i in range(n - 2, -1, -1):
            b = blocks[i]
            if b[NOMINAL]:
                following = b[ENTRY] = b[MAX_ENTRY]
            else:
                v = sqrt(following * following + 2 * b[ACCEL] * b[DISTANCE])
                if v > b[MAX_ENTRY]:
                    v = b[MAX_ENTRY]
                following = b[ENTRY] = v
        # forward: each block must be reachable accelerating from the previous one's entry
        prev = blocks[0]
        for i in range(1, n):
            b = blocks[i]
            if not prev[NOMINAL] and prev[ENTRY] < b[ENTRY]:
                v = sqrt(prev[ENTRY] * prev[ENTRY] + 2 * prev[ACCEL] * prev[DISTANCE])
                if v < b[ENTRY]:
                    b[ENTRY] = v
            prev = b
        done = n - keep
        total = self.time
        watches = self._watches
        for i in range(done):
            distance, accel, cruise, entry, _, safe, _, number = blocks[i]
            exit_ = blocks[i + 1][ENTRY] if i + 1 < n else safe
            # the trapezoid (``trapezoid_time``, inline: it runs for every move)
            if entry > cruise:
                entry = cruise
            if exit_ > cruise:
                exit_ = cruise
            if accel <= 0:
                total += distance / cruise
            else:
                twice = 2 * accel
                up = (cruise * cruise - entry * entry) / twice
                down = (cruise * cruise - exit_ * exit_) / twice
                middle = distance - (up if up > 0 else 0.0) - (down if down > 0 else 0.0)
                if middle >= 0:
                    total += (2 * cruise - entry - exit_) / accel + middle / cruise
                else:
                    total += trapezoid_time(distance, accel, cruise, entry, exit_)
            if watches and number in watches:
                for key in watches.pop(number):
                    self.watched[key] = total
        self.time = total
        if keep:
            del blocks[:done]
            first = blocks[0]
            first[MAX_ENTRY] = first[ENTRY]  # (already running into it: its entry no longer changes)
        else:
            blocks.clear()
