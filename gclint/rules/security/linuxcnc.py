"""LinuxCNC/Machinekit: the comments its interpreter runs ("active comments") and subroutine calls that read
another file.  The rules report them in every dialect (SC001, SC004, SC005): a job that a LinuxCNC or
Machinekit controller runs can claim any flavour.

LinuxCNC's sources and documentation (paths below) are at https://github.com/LinuxCNC/linuxcnc (master).

How LinuxCNC reads a comment (src/emc/rs274ngc/interp_convert.cc ``convert_comment``, called by
interp_execute.cc ``execute_block`` with the text between the parentheses): it steps over the leading
white space (C ``isspace``: space, tab, line feed, vertical tab, form feed, carriage return), lower-cases the
rest and compares its start with "log,", "logopen,", "logappend,", "py,", "pyrun," and "pyreload" (no blank
may stand between the word and its comma: "(LOG ,x)" is a plain comment).  What is left after the comma is
the file name or the text.  The comment then goes to the controller's ``COMMENT`` (src/emc/task/emccanon.cc),
which opens a probe log for "PROBEOPEN" as written, in upper case, with the file name after the blanks that
follow it.  LinuxCNC's G-code overview (docs/src/gcode/overview.adoc, "Comments") says that a comment after
";" is read for these too; its source reads ";py," at the very start of a line (interp_read.cc
``read_semicolon``).  A gate reads both kinds of comment, and every comment of a line (LinuxCNC acts on the
last one only).
"""

from __future__ import annotations

import re

from gclint.syntax.nodes import Command

# https://github.com/LinuxCNC/linuxcnc/blob/master/src/emc/rs274ngc/interp_convert.cc convert_comment and
# src/emc/task/emccanon.cc COMMENT (PROBEOPEN); docs/src/gcode/overview.adoc "Logging", "Probe Logging";
# docs/src/remap/remap.adoc "Executing Python statements from the interpreter" (";py,print(2*3)": the Python
# plugin, [PYTHON] in the INI file).
ACTIVE = re.compile(r"[ \t\n\v\f\r]*+(?:(?i:(logopen|logappend|log|pyrun|py),|(pyreload))|(PROBEOPEN)[ \t\n\v\f\r]*+)")
# What each one does, for the messages.
FILE_WRITES = {
    "LOGOPEN": "makes LinuxCNC/Machinekit open the file {target} on the controller and truncate it: the LOG"
    " comments that follow are written into it",
    "LOGAPPEND": "makes LinuxCNC/Machinekit open the file {target} on the controller to append to it: the LOG"
    " comments that follow are written into it",
    "LOG": "makes LinuxCNC/Machinekit write {target} into the log file a LOGOPEN or LOGAPPEND opened",
    "PROBEOPEN": "makes LinuxCNC/Machinekit open the file {target} on the controller for writing (an existing"
    " file is overwritten) and write each probed point into it",
}
CODE_RUNS = {
    "PY": "makes LinuxCNC/Machinekit run {target} as Python in its interpreter (the Python plugin)",
    "PYRUN": "makes LinuxCNC/Machinekit run {target} as Python in its interpreter (the Python plugin)",
    "PYRELOAD": "makes LinuxCNC/Machinekit reload its Python plugin (its modules run again)",
}
# A comment worth matching: "(" or ";" and blanks before one of the words (true of comment lines joined by
# line breaks when true of one: rules.base.Rule.comment_hint).
_HINT = re.compile(r"(?i)[;(][ \t\n\v\f\r]*+(?:log|py|probeopen)")


# LinuxCNC reads a file with C's fgets, so only a line feed ends a line (src/emc/rs274ngc/interp_read.cc
# ``read_text``); interp_internal.cc ``close_and_downcase`` then drops each carriage return outside a comment and
# keeps those inside one, and ``convert_comment`` steps over them as white space: "(<CR>LOGOPEN,x)" opens x and
# "o<sub><CR>call" calls sub.
JOINED_VIEW = "read as LinuxCNC/Machinekit reads lines joined by a bare carriage return (only a line feed ends a line)"


def read_as_one_line(text: str) -> str:
    """``text`` (lines joined by carriage returns) as LinuxCNC reads it: the carriage returns outside comments
    dropped (``close_and_downcase``), those inside kept."""
    out = []
    comment = semicomment = False
    for char in text:
        if semicomment or comment:
            out.append(char)
            comment = comment and char != ")"
        elif char == ";":
            semicomment = True
            out.append(char)
        elif char == "(":
            comment = True
            out.append(char)
        elif char != "\r":
            out.append(char)
    return "".join(out)


def may_be_active(comment: str) -> bool:
    """Whether the comment (with its ";" or "(") may be an active comment."""
    return _HINT.search(comment) is not None


def shown(keyword: str) -> str:
    """How the job writes ``keyword``'s comment: "(LOGOPEN,...)", "(PROBEOPEN ...)", "(PYRELOAD)"."""
    return {"PROBEOPEN": "(PROBEOPEN ...)", "PYRELOAD": "(PYRELOAD)"}.get(keyword, f"({keyword},...)")


def active_comment(body: str) -> tuple[str, str] | None:
    """``(KEYWORD, argument)`` when LinuxCNC acts on the comment ``body`` (the text inside the parentheses,
    or after ";"), else None.  ``argument`` is the file name, the text or the Python code."""
    m = ACTIVE.match(body)
    if m is None:
        return None
    keyword = (m.group(1) or m.group(2) or m.group(3)).upper()
    return keyword, body[m.end() :].strip()


# "(" or ";" on a line the grammar refused: where a comment may start for LinuxCNC.
_COMMENT_START = re.compile(r"[(;]")


def comments_in(raw: str) -> list[tuple[int, str]]:
    """The comments LinuxCNC may read on a line the grammar refused, as ``(column, body)``: the text after
    each "(" up to its ")" (only those an active comment can start), and after the first ";" to the end."""
    out = []
    pos = 0
    while (m := _COMMENT_START.search(raw, pos)) is not None:
        start = m.end()
        if m.group() == ";":
            out.append((m.start() + 1, raw[start:]))
            break
        end = raw.find(")", start)
        pos = end + 1 if end >= 0 else len(raw)
        body = raw[start:end] if end >= 0 else raw[start:]
        if ACTIVE.match(body) is not None:
            out.append((m.start() + 1, body))
    return out


def as_linuxcnc_reads(text: str) -> str:
    """``text`` as interp_internal.cc ``close_and_downcase`` leaves it: outside a "(...)" comment the blanks
    (space, tab, carriage return) dropped and the letters lower-cased; inside one, everything kept as written
    (so "o<$(REBOOT)>" names "$(REBOOT)", and "o<foo(A B)>" names "foo(A B)"); from a ";" outside a comment on,
    the rest as written ("o<"x;B">" names "x;B")."""
    out = []
    comment = False
    for index, char in enumerate(text):
        if comment:
            out.append(char)
            comment = char != ")"
        elif char == ";":
            out.append(text[index:])
            break
        elif char == "(":
            comment = True
            out.append(char)
        elif char not in " \t\r":
            out.append(char.lower() if "A" <= char <= "Z" else char)
    return "".join(out)


# The O-word keywords (interp_read.cc ``read_o``), longest first where one starts another
_KEYWORDS = (
    "endsub", "endif", "endwhile", "endrepeat", "elseif", "else", "call", "sub", "return", "if", "do", "while",
    "break", "continue", "repeat",
)  # fmt: skip
_LINE_NUMBER = re.compile(r"/?(?:n[0-9.]*)?")


def read_oword(text: str) -> tuple[str, str | None] | None:
    """The keyword of the O-word ``text`` starts with and the subroutine it names, as LinuxCNC reads them; None
    when ``text`` is no O-word to LinuxCNC.  ``as_linuxcnc_reads`` first, so blanks count for nothing ("o 1 0 0
    c a l l" calls 100); then interp_read.cc ``read_o`` reads "o<name>" as "name" and "o0100" as the number 100
    (as "M98 P100" is); a name computed by an expression or a parameter ("o[#2 * 10] call", "o#<sub> call") is
    None."""
    s = as_linuxcnc_reads(text)
    number = _LINE_NUMBER.match(s)
    s = s[number.end() :] if number is not None else s
    if s[:1] != "o":
        return None
    i, name = 1, None
    if s[1:2] == "<":
        end = s.find(">", 1)
        if end < 0:
            return None
        name, i = s[2:end], end + 1
    elif s[1:2] == "[":
        depth = 0
        for i in range(1, len(s)):
            depth += {"[": 1, "]": -1}.get(s[i], 0)
            if depth == 0:
                break
        i += 1
    elif s[1:2] == "#":
        end = s.find(">", 2) + 1 if s[2:3] == "<" else 2 + len(s[2:]) - len(s[2:].lstrip("0123456789"))
        i = max(end, 2)
    else:
        digits = len(s) - 1 - len(s[1:].lstrip("0123456789"))
        if digits == 0:
            return None
        name, i = str(int(s[1 : 1 + digits])), 1 + digits
    keyword = next((k for k in _KEYWORDS if s.startswith(k, i)), "")
    return keyword, (name or None)


def oword(line_text: str, cmd: Command) -> tuple[str, str | None]:
    """The keyword and subroutine name of the O-word command ``cmd`` of a line as LinuxCNC reads them
    (``read_oword`` on the line from the command on; the grammar's reading where LinuxCNC would read none)."""
    found = read_oword(line_text[max(cmd.column - 1, 0) :])
    if found is not None:
        return found
    label = as_linuxcnc_reads(cmd.params.get("label") or "")
    name = label[1:-1] if label[:1] == "<" and label[-1:] == ">" and len(label) > 2 else None
    if label.isdigit():
        name = str(int(label))
    return (cmd.params.get("keyword") or "").lower(), name


def looked_up(name: str) -> str:
    """The name a call looks its subroutine up by: interp_o_word.cc ``control_back_to`` finds
    ``basename(o_name)`` in the subroutines defined so far (a definition is kept under its whole name, so a
    name with a "/" never matches one)."""
    return name.rpartition("/")[2]


# What the shell expands when LinuxCNC looks for the file of a subroutine it has not defined: rs274ngc_pre.cc
# ``find_ngc_file`` passes the name to wordexp(3) with no flags, which runs "$(...)" and "`...`" through the
# shell (WRDE_NOCMD would refuse them) and expands "$NAME" from the controller's environment.
SHELL_EXPANSION = re.compile(r"[$`]")
