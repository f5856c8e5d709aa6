"""Simulation of G-code jobs in their own dialect, and the meaning diff built on it (``gclint diff``).

``simulator_for`` gives the simulator of a dialect (fdm.py: Marlin, RepRapFirmware; cnc.py: Machinekit,
Carvera; hyrel.py: Hyrel v5 and v4; what they share beyond the reader, devices.py).  Each reads its dialect's
pages on its own, not the translator's tables, and describes every working move in Hyrel terms (trace.py).
``diff_sources`` runs two of them side by side and compares them (compare.py).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gclint.dialects.base import Dialect
from gclint.simulate.cnc import CarveraSimulator, MachinekitSimulator
from gclint.simulate.compare import Diff, Difference, Explanations
from gclint.simulate.devices import DeviceModel
from gclint.simulate.fdm import MarlinSimulator, RepRapSimulator
from gclint.simulate.hyrel import HyrelSimulator
from gclint.simulate.machine import Simulator
from gclint.simulate.trace import EndState, Mapping
from gclint.syntax.source import Source

__all__ = ["DiffResult", "Difference", "Explanations", "Mapping", "diff_sources", "simulator_for", "is_cnc"]

_SIMULATORS: dict[str, type[Simulator]] = {
    "hyrel": HyrelSimulator,
    "marlin": MarlinSimulator,
    "reprap": RepRapSimulator,
    "machinekit": MachinekitSimulator,
    "carvera": CarveraSimulator,
}


def is_cnc(dialect: Dialect) -> bool:
    """CNC jobs synchronise on every feed move; printing jobs on the moves that print."""
    return dialect.semantics.working == "feeds"


def simulator_for(dialect: Dialect, mapping: Mapping | None = None, *, cnc: bool | None = None) -> Simulator:
    """The reader of ``dialect``'s jobs: the machine's devices as its documentation says (the registry below,
    by dialect; a version of another dialect is read as that one, Hyrel v4 through its addresses); ``cnc``
    (default: the dialect's machine cuts) makes every feed move a working move."""
    factory = _SIMULATORS.get(dialect.variant_of or dialect.name, Simulator)
    return factory(dialect, mapping, cnc=is_cnc(dialect) if cnc is None else cnc)


@dataclass
class DiffResult:
    differences: list[Difference] = field(default_factory=list)
    source_end: EndState = field(default_factory=EndState)
    output_end: EndState = field(default_factory=EndState)
    pairs: int = 0  # working moves matched
    notes: list[str] = field(default_factory=list)

    def unexplained(self) -> list[Difference]:
        return [d for d in self.differences if d.explained_by is None]


def diff_sources(
    source: Source,
    output: Source,
    source_dialect: Dialect,
    output_dialect: Dialect,
    mapping: Mapping | None = None,
    explanations: Explanations | None = None,
) -> DiffResult:
    """Simulate both jobs, each in its own dialect, and compare them move by move and at the end."""
    cnc = is_cnc(source_dialect) or is_cnc(output_dialect)
    first = simulator_for(source_dialect, mapping, cnc=cnc)
    second = simulator_for(output_dialect, mapping, cnc=cnc)
    if explanations is not None and explanations.reference is None and isinstance(first, DeviceModel):
        first.anchoring = True  # which source line last set each thing (what a finding may explain)
    diff = Diff(explanations, native=mapping is not None and mapping.flow == "native")
    diff.run(first.run(source), second.run(output))
    diff.finish(first.trace.end, second.trace.end)
    return DiffResult(
        differences=diff.differences,
        source_end=first.trace.end,
        output_end=second.trace.end,
        pairs=diff.pairs,
        notes=first.trace.notes + [n for n in second.trace.notes if n not in first.trace.notes],
    )
