"""Job flow on Hyrel: M0 and the actions it runs from its comment (SAY, PIC, VID, SEND, BEEP, SHELL)."""

from __future__ import annotations

from gclint.dialects.base import Code
from gclint.dialects.hyrel import ACTIONS
from gclint.explain.generic import does
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation
from gclint.rules.security import shell_offsets
from gclint.syntax.nodes import Command


def stop(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    does(exp, spec)
    line = exp.source
    comment = line.split(";", 1)[1] if ";" in line else ""
    warned = False
    for part in comment.split(";"):  # "Note that multiple options can be combined."
        part = part.strip()
        keyword = part.split(" ", 1)[0].upper() if part else ""
        if keyword in ACTIONS:
            argument = part[len(keyword) :].strip()
            exp.add(part, f"{ACTIONS[keyword]}: {argument}" if argument else ACTIONS[keyword])
            if keyword == "SHELL":
                exp.warn("SHELL runs a program on the Repetrel computer when the job reaches this line")
                warned = True
    if not warned and shell_offsets(line.split("M0", 1)[-1]):  # SHELLC:..., SAY hi SHELL..., SHE­LL (SC001)
        exp.warn("the text holds SHELL: Repetrel may run it as a program (SC001 reports it)")


def decoders(job: Job) -> dict[str, Decoder]:
    return dict.fromkeys(job.facts.codes_with("pause-with-actions"), stop)
