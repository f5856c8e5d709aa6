"""What a decoder reads besides the command: the dialect, and the job so far as the machine
``Interpreter`` keeps it (the head with focus, relative moves, the fan range, stored offsets...)."""

from __future__ import annotations

from collections.abc import Callable

from gclint.dialects.base import Code, Dialect
from gclint.explain.model import Explanation
from gclint.machine.interpreter import Interpreter
from gclint.machine.state import MachineState
from gclint.syntax.nodes import Command


class Job:
    """The dialect a job is explained in and the state its lines so far have set."""

    def __init__(self, dialect: Dialect, state: MachineState | None = None) -> None:
        self.dialect = dialect
        self.facts = dialect.semantics  # what the dialect's machine does (gclint.dialects.semantics)
        # T commands and T variables name devices by address (Hyrel): heads, beds, groups, clone squads
        self.addressed = self.facts.tool_select == "address"
        self.state = state if state is not None else MachineState()
        self.interpreter = Interpreter(dialect, self.state)
        self.firmware = dialect.extras.get("firmware")


# A decoder adds to the explanation of one command what its words do: (job, explanation, command, spec).
Decoder = Callable[[Job, Explanation, Command, Code | None], None]
