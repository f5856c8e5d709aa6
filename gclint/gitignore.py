"""``.gitignore`` files read as git reads them (gitignore(5)), matched in linear time by ``gclint.globs``.

A line is a pattern relative to the folder of its file: ``#`` starts a comment, trailing blanks are
dropped unless escaped, ``!`` negates, a trailing ``/`` matches folders only; a pattern with a ``/``
before its end is anchored to the folder of its ``.gitignore``, else it matches a name at any depth.
The last pattern that matches decides.  A pattern git could not read (``[z-a]``, an unclosed ``[``)
matches nothing, as in git: the file belongs to the checkout, not to the user, so it is no error.
"""

from __future__ import annotations

from dataclasses import dataclass

from gclint.globs import Glob, GlobError, Part


@dataclass(frozen=True)
class _Rule:
    negated: bool
    folders_only: bool
    anchored: bool
    matcher: Glob | Part

    def match(self, rel: str, is_dir: bool) -> bool:
        if self.folders_only and not is_dir:
            return False
        if self.anchored:
            return self.matcher.match(rel)
        return self.matcher.match(rel.rsplit("/", 1)[-1])


class GitIgnore:
    """The patterns of one ``.gitignore`` (or ``.git/info/exclude``)."""

    def __init__(self, rules: list[_Rule]) -> None:
        self.rules = rules

    @classmethod
    def from_lines(cls, lines: list[str]) -> GitIgnore:
        rules = []
        for line in lines:
            rule = _read(line)
            if rule is not None:
                rules.append(rule)
        return cls(rules)

    def decide(self, rel: str, is_dir: bool) -> bool | None:
        """True: ``rel`` (``/``-separated, relative to this file's folder) is ignored; False: a negated
        pattern keeps it; None: no pattern speaks about it."""
        for rule in reversed(self.rules):
            if rule.match(rel, is_dir):
                return not rule.negated
        return None


def _read(line: str) -> _Rule | None:
    if not line or line.startswith("#"):
        return None
    line = _strip_trailing_blanks(line)
    if not line:
        return None
    negated = line.startswith("!")
    if negated:
        line = line[1:]
    folders_only = line.endswith("/")
    if folders_only:
        line = line[:-1]  # (one slash: "?//" is anchored, as in git)
    if not line:
        return None
    anchored = "/" in line
    if line.startswith("/"):
        line = line[1:]
    try:
        matcher: Glob | Part = Glob(line) if anchored else Part(line)
    except GlobError:
        return None  # git's wildmatch gives up on such a pattern: it matches nothing
    return _Rule(negated, folders_only, anchored, matcher)


def _strip_trailing_blanks(line: str) -> str:
    """Trailing spaces and tabs go, unless a backslash escapes the last one (``foo\\ ``)."""
    end = len(line)
    while end and line[end - 1] in " \t":
        if end >= 2 and line[end - 2] == "\\":
            break
        end -= 1
    return line[:end]
