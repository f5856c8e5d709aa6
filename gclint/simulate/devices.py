"""What every device model (fdm.py, cnc.py, hyrel.py) adds to the shared reader (machine.py) for the meaning diff:

* marks: for each aspect of the state a working move runs in (trace.LOOK_ASPECTS; a bed or an aux device by
  itself), and for each device of the end state, the line whose command last changed it.  A translation
  finding on a line before that cannot explain a difference in it: whatever that line did (a macro call the
  reader cannot follow, a code dropped), the later line set the value again (compare.Explanations).  Marks
  are kept only where a diff asks for them (``anchoring``: the source side of an explained diff).
* unprimes and primes: the retractions a job makes between two working moves, in Hyrel terms (("unprime",
  head), ...), carried by the next working move or the end state (compare.py, aspect "prime").
* the trail of pauses: where a job pauses between two working moves, the pauses among the changes of the
  spindle's direction, so that a pause the translation adds (to stop a spindle before reversing it) and a
  pause it loses do not make the same count (compare.py, aspect "pause").
"""

from __future__ import annotations

from dataclasses import fields

from gclint.simulate.machine import Simulator
from gclint.simulate.trace import LOOK_ASPECTS, EndState, Look, Move

# aspects whose value is a tuple of devices, each marked by itself: beds ((address, set-point, waited), ...),
# aux ((device, value), ...)
_BY_DEVICE = frozenset({"beds", "aux"})
_END_PARTS = ("heaters", "fans", "spindles", "aux")
_LOOK_FIELDS = tuple(f.name for f in fields(Look))


class DeviceModel(Simulator):
    """A simulator with devices: see the module's docstring."""

    def __init__(self, dialect, mapping=None, *, cnc: bool = False) -> None:
        super().__init__(dialect, mapping, cnc=cnc)
        self.anchoring = False  # keep marks (compare.py: the source side of an explained diff)
        self.pure = False  # (while marking) build the look and end state without inferring anything
        self.marks: dict = {}
        self._seen_look: Look | None = None
        self._seen_end: EndState | None = None
        self.primes: list[tuple[str, int | str | None]] = []  # since the previous working move
        self.e_only = False  # (set by a model's ``motion``) the move has extruder words and no axis words
        self.trail: list[str] = []  # pauses and spindle directions since the previous working move
        self._direction: str | None = None

    def run(self, source):
        return super().run(self.reading(source))

    def events(self, source):
        return super().events(self.reading(source))

    def reading(self, source):
        """The source as this model reads it (native flow: its slicer's statements of the layer height)."""
        layers = getattr(self, "layers", None)
        return layers.read(source) if layers is not None else source

    # -- marks ---------------------------------------------------------------------------------------------

    def dirty(self) -> None:
        super().dirty()
        direction = self.spindle_direction()
        if direction != self._direction:
            self._direction = direction
            self.trail.append(direction or "off")
        if self.anchoring:
            self.mark()

    def spindle_direction(self) -> str | None:
        """The direction the spindle that works turns in (M3, M4), None when it stands."""
        return None

    def pause(self, cmd, n: int) -> None:
        super().pause(cmd, n)
        self.trail.append("pause")

    def take_trail(self) -> tuple:
        """The trail since the previous working move, where there was a pause (and start a new one)."""
        trail = tuple(self.trail) if "pause" in self.trail else ()
        self.trail.clear()
        return trail

    def mark(self) -> None:
        """Compare the state with the one last seen, and mark what changed on this line."""
        self.pure = True
        try:
            look, end = self.build_look(), self.end_state()
        finally:
            self.pure = False
        line = self.line
        marks = None
        seen = self._seen_look
        if seen is None or look != seen:
            for aspect in LOOK_ASPECTS:
                new = getattr(look, aspect)
                old = getattr(seen, aspect) if seen is not None else None
                if new == old:
                    continue
                if marks is None:
                    marks = dict(self.marks)
                if aspect in _BY_DEVICE:
                    before, after = _devices(old), _devices(new)
                    for device in set(before) | set(after):
                        if before.get(device) != after.get(device):
                            marks[f"{aspect}:{device}"] = line
                marks[aspect] = line
            self._seen_look = look
        last = self._seen_end
        for part in _END_PARTS:
            new_part = getattr(end, part)
            old_part = getattr(last, part) if last is not None else {}
            if new_part == old_part:
                continue
            for device in set(new_part) | set(old_part):
                if new_part.get(device) != old_part.get(device):
                    if marks is None:
                        marks = dict(self.marks)
                    marks[f"{part}:{device}"] = line
        if end.emitters != (last.emitters if last is not None else frozenset()):
            if marks is None:
                marks = dict(self.marks)
            for device in end.emitters ^ (last.emitters if last is not None else frozenset()):
                marks[f"emitters:{device}"] = line
        self._seen_end = end
        if marks is not None:
            self.marks = marks  # a new dict: the moves before keep theirs

    # -- unprimes and primes -------------------------------------------------------------------------------

    def unprime(self, head) -> None:
        self.primes.append(("unprime", head))

    def prime(self, head) -> None:
        self.primes.append(("prime", head))

    def retraction(self, delta: float) -> None:
        """A move of the source's extruder alone (no axis word): a retraction (an unprime) or a recovery (a prime) when the
        translation writes them (``retract=explicit``); left to Hyrel's heads otherwise."""

    def sync(self, start, arc, delta, feed, rapid, native=False):
        if self.e_only:
            self.e_only = False
            if delta and arc is None:
                self.retraction(delta)
        move = super().sync(start, arc, delta, feed, rapid, native=native)
        if move is not None:
            if self.anchoring:
                move.marks = self.marks
            if self.primes:
                move.primes = tuple(self.primes)
                self.primes.clear()
            if self.trail:
                move.trail = self.take_trail()
        return move

    def finish_end(self, end: EndState) -> EndState:
        """The end state with what happened after the last working move and the marks of its devices."""
        end.primes = tuple(self.primes)
        end.trail = tuple(self.trail) if "pause" in self.trail else ()
        if self.anchoring:
            end.marks = dict(self.marks)
        return end


def _devices(value) -> dict:
    """A beds or aux look value by device: {address or name: the rest}."""
    if not value:
        return {}
    return {item[0]: item[1:] for item in value}


__all__ = ["DeviceModel", "Move"]
