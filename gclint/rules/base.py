"""What a rule is, what it reports, and the registry of rules.

A rule is a class that declares its metadata (code, name, default severity, summary, explanation with
a bad and a good example, the source it comes from) and the command codes it listens to.  The engine
makes one instance per file and calls ``check(line, cmd)`` for each command whose code the rule listens
to, with the machine state as it was *before* that command.  Rules read the state through
``self.state`` and never scan back through lines.

Third-party rules are registered through the ``gclint.rules`` entry point group: each entry point names
a module (importing it registers its rules) or a ``Rule`` subclass.
"""

from __future__ import annotations

import os
import re
import textwrap
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from enum import IntEnum
from functools import cache
from operator import attrgetter
from pathlib import Path
from typing import TYPE_CHECKING, ClassVar, NamedTuple

from gclint.syntax.nodes import Command, Comment, Line, Node

if TYPE_CHECKING:
    from gclint.filecontext import FileContext


class Severity(IntEnum):
    INFO = 0
    WARNING = 1
    ERROR = 2

    @property
    def label(self) -> str:
        return self.name.lower()

    @classmethod
    def parse(cls, text: str) -> Severity:
        try:
            return cls[text.strip().upper()]
        except KeyError:
            raise ValueError(f"unknown severity {text!r} (use error, warning or info)") from None


@dataclass(frozen=True, slots=True)
class Edit:
    """Replace columns ``start``..``end`` (1-based, end exclusive) of line ``line`` with ``text``."""

    line: int
    start: int
    end: int
    text: str


@dataclass(frozen=True, slots=True)
class Fix:
    """A fix for a finding.  ``safe`` fixes are applied by ``--fix``; unsafe ones need ``--unsafe-fixes``."""

    message: str
    edits: tuple[Edit, ...]
    safe: bool = True

    def to_dict(self) -> dict:
        return {
            "message": self.message,
            "applicability": "safe" if self.safe else "unsafe",
            "edits": [{"line": e.line, "column": e.start, "end_column": e.end, "content": e.text} for e in self.edits],
        }


@dataclass(slots=True)
class Finding:
    """One problem at one place in one file."""

    path: str
    line: int
    column: int
    code: str
    severity: Severity
    message: str
    name: str = ""
    fix: Fix | None = None
    end_column: int | None = None
    source: str | None = field(default=None, compare=False)  # the line's text, for reports

    def to_dict(self) -> dict:
        out = {
            "path": self.path,
            "line": self.line,
            "column": self.column,
            "end_column": self.end_column if self.end_column is not None else self.column,
            "code": self.code,
            "name": self.name,
            "severity": self.severity.label,
            "message": self.message,
        }
        if self.fix is not None:
            out["fix"] = self.fix.to_dict()
        return out

    # (path, line, column, code): the order of reports, as a key for sorting (``key=Finding.sort_key``)
    sort_key: ClassVar[Callable[[Finding], tuple]] = attrgetter("path", "line", "column", "code")


class RunFinding(NamedTuple):
    """A finding a rule's run filter makes on a line of a run (``run_filter``, docs/architecture.md) in
    place of having the line read: reading it would make exactly this finding (the rule's ``report``
    at these columns) and do nothing else but apply the move.  The engine adds it where the line is, in
    line order, unless another filter wants the line read (then reading it makes the finding)."""

    at: int  # the start of the line in the run's text
    rule: Rule
    column: int
    end_column: int | None
    message: str
    severity: Severity | None = None  # (None: the rule's)


# Every link to a rule's documentation (SARIF helpUri, the language server's codeDescription) is made
# here.  The rule reference is docs/rules.md (generated; each rule has a "### CODE" heading, hence the
# lower-case anchor).  Where it is published comes from the package's metadata ([project.urls]
# "Documentation" in pyproject.toml, or GCLINT_DOCS_URL); no address is invented: without one, a source
# checkout links to its own docs/rules.md, and an installed package gives no link.
_RULES_DOC = Path(__file__).resolve().parents[2] / "docs" / "rules.md"


def project_url(*labels: str) -> str | None:
    """The first of the package's [project.urls] entries named ``labels`` (case-insensitive), or None."""
    try:
        from importlib.metadata import PackageNotFoundError, metadata

        entries = metadata("gclint").get_all("Project-URL") or ()
    except (ImportError, PackageNotFoundError):
        return None
    found: dict[str, str] = {}
    for entry in entries:
        label, _, url = entry.partition(",")
        if url.strip():
            found.setdefault(label.strip().lower(), url.strip())
    return next((found[label] for label in labels if label in found), None)


@cache
def rules_doc_base() -> str | None:
    """The address of the rule reference (without the anchor), or None when none is known."""
    configured = os.environ.get("GCLINT_DOCS_URL")
    if configured:
        return configured
    published = project_url("documentation")
    if published:
        return published
    return _RULES_DOC.as_uri() if _RULES_DOC.is_file() else None


def rule_url(code: str) -> str | None:
    """The address of a rule's documentation (``rule_url("HY003")`` -> ``.../docs/rules.md#hy003``)."""
    base = rules_doc_base()
    return f"{base}#{code.lower()}" if base else None


# Pseudo-codes a rule can listen to besides command codes.
ANY_T = "T*"  # every T<n> command line


class Rule:
    """Base class of all rules.  Subclasses set the class attributes and override the hooks they need."""

    code: ClassVar[str] = ""
    name: ClassVar[str] = ""
    severity: ClassVar[Severity] = Severity.WARNING
    summary: ClassVar[str] = ""
    explanation: ClassVar[str] = ""  # why it matters; markdown allowed
    example_bad: ClassVar[str] = ""  # G-code that triggers the rule
    example_good: ClassVar[str] = ""  # the corrected G-code
    source: ClassVar[str] = ""  # the public source (docs/sources.md) and section the rule comes from
    # command codes to listen to (ANY_T for T commands); a rule may set its own in __init__
    codes: tuple[str, ...] = ()
    families: ClassVar[tuple[str, ...] | None] = None  # dialect families it applies to; None = all
    dialects: ClassVar[tuple[str, ...] | None] = None  # or exact dialect names
    on_line: ClassVar[bool] = False  # call check_line for every line (use sparingly)
    on_line_longer_than: ClassVar[int | None] = None  # call check_line for lines longer than this
    on_line_after_m30: ClassVar[bool] = False  # call check_line for every line once the job has ended
    # call check_line for lines whose first character is one of these (never "G": plain moves stay fast)
    on_line_starting_with: ClassVar[frozenset[str]] = frozenset()
    on_comment: ClassVar[bool] = False  # call check_comment for every comment
    # With on_comment: a test (a staticmethod) that is true for every comment text check_comment may have
    # something to say about; the engine skips the comment lines it is false for.  It must also be true of
    # several comments joined by line breaks when it is true of one of them (a test for words, as
    # secrets.may_hold is): the engine tests the comment lines of a run of moves together.  None: every
    # comment is read.
    comment_hint: ClassVar[staticmethod[[str], bool] | None] = None
    # call check_view for lines this pattern finds.  A multi-line pattern ((?m)) must find a match in lines
    # joined by line breaks when it finds one in one of them, and none that starts at a line break: then the
    # engine tests the comment lines of a run together, else one by one.
    on_line_matching: ClassVar[re.Pattern | None] = None
    on_unknown_code: bool = False  # call check for codes the dialect does not have (a rule may set its own)
    # check's findings on a command depend only on the command's text and the file's settings (dialect,
    # options), never on the state or the line's number, and it keeps nothing: for an M-code line that
    # repeats in runs ("M204 S1000") the engine makes them once and repeats them (runs.CodeLines)
    pure: ClassVar[bool] = False
    on_numbered: ClassVar[bool] = False  # call check_line for lines with an N number or a checksum
    on_issue: ClassVar[bool] = False  # call check_issues for lines with syntax issues
    on_ignored_command: ClassVar[bool] = False  # call check_ignored for commands the dialect's machine never runs
    fixable: ClassVar[bool] = False
    # "safe" (--fix applies it), "unsafe" (--unsafe-fixes), or "sometimes" (depends on the finding)
    fix_applicability: ClassVar[str] = "safe"
    default_enabled: ClassVar[bool] = True

    # Hooks some rules have and the engine looks up with getattr (declared here, never set: a rule without
    # one has none): check_view (on_line_matching), check_joined (on_bare_cr: lines ending in a bare
    # carriage return, read with the next), and the plain-move and run filters (docs/architecture.md)
    check_view: Callable[[Line], None]
    check_joined: Callable[[Line, str, int], None]
    plain_filter: Callable[[str, str | None, str | None, str | None, str | None, str | None], bool]
    run_filter: Callable[[str, int, int], list[int] | list[int | RunFinding] | None]

    def __init__(self, ctx: FileContext) -> None:
        self.ctx = ctx
        self.state = ctx.state

    # -- hooks -----------------------------------------------------------------------------------------

    def check(self, line: Line, cmd: Command) -> None:
        """Called for each command the rule listens to, before the command changes the state."""

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        """Letters that make ``check`` worth calling for ``code``: the engine skips commands with none of
        them.  None (the default) means every command with the code."""
        return None

    def check_line(self, line: Line) -> None:
        """Called for every line (``on_line``), numbered lines (``on_numbered``), long lines
        (``on_line_longer_than``), lines after the end of the job (``on_line_after_m30``) or lines that
        start with one of ``on_line_starting_with``."""

    def check_comment(self, line: Line, comment: Comment) -> None:
        """Called for every comment (``on_comment``)."""

    def check_issues(self, line: Line) -> None:
        """Called for lines with syntax issues (``on_issue``)."""

    def check_ignored(self, line: Line, cmd: Command) -> None:
        """Called for each command of a line that the dialect's machine does not run (``on_ignored_command``:
        Marlin runs only a line's first command)."""

    def finish(self) -> None:
        """Called once after the last line."""

    # -- reporting -------------------------------------------------------------------------------------

    def report(
        self,
        line: Line | int,
        message: str,
        *,
        node: Node | Command | None = None,
        column: int | None = None,
        fix: Fix | None = None,
        severity: Severity | None = None,
    ) -> None:
        """Report a finding at ``node`` (or ``column``) of ``line``."""
        end = None
        if isinstance(node, Command):
            column = node.column
            word = node.word
            end = word.end_column if word is not None else None
        elif node is not None:
            column = node.column
            end = node.end_column
        self.ctx.add(self, line, column or 1, message, fix=fix, severity=severity, end_column=end)

    # -- documentation ---------------------------------------------------------------------------------

    @classmethod
    def applies_to(cls, dialect) -> bool:
        """Whether the rule checks files read as ``dialect`` (its ``dialects``/``families``; a ``generic`` file
        gets no HY or DL rule: nothing says which machine's tables apply)."""
        return dialect.runs_rules_of(cls.families, cls.code, cls.dialects)

    @classmethod
    def doc(cls) -> dict:
        """The rule's documentation as data (``gclint rules --format json``)."""
        bad, bad_options = _example(cls.example_bad)
        good, good_options = _example(cls.example_good)
        return {
            "code": cls.code,
            "name": cls.name,
            "severity": cls.severity.label,
            "summary": cls.summary,
            "explanation": textwrap.dedent(cls.explanation).strip(),
            "example_bad": bad,
            "example_good": good,
            "example_options": bad_options or good_options,  # ["--printer ehr"]: how the examples are checked
            "source": cls.source,
            "listens_to": list(cls.codes),
            "applies_to": list(cls.dialects or cls.families or ["all"]),
            "fixable": cls.fixable,
            "fix_applicability": cls.fix_applicability if cls.fixable else None,
            "url": rule_url(cls.code),
        }

    @classmethod
    def render_doc(cls) -> str:
        """The rule's documentation as text (``gclint rules CODE``)."""
        d = cls.doc()
        parts = [f"{d['code']} {d['name']} ({d['severity']})", "", d["summary"], ""]
        if d["explanation"]:
            parts += ["## Why", "", d["explanation"], ""]
        if d["example_bad"]:
            parts += ["## Example", ""]
            if d["example_options"]:
                parts += [f"(checked with {' '.join(d['example_options'])})", ""]
            parts += ["Bad:", "", textwrap.indent(d["example_bad"], "    "), ""]
        if d["example_good"]:
            parts += ["Good:", "", textwrap.indent(d["example_good"], "    "), ""]
        parts += [f"Applies to: {', '.join(d['applies_to'])}"]
        if d["source"]:
            parts += [f"Source: {d['source']}"]
        if d["fixable"]:
            parts += [f"Fix: {FIX_USAGE[cls.fix_applicability]}"]
        return "\n".join(parts).rstrip() + "\n"


class MoveListener:
    """One listener to the G0/G1 lines of a file on behalf of several rules, declared to the engine.

    Plain moves are millions a job: rules that all want a look at some G0/G1 lines (an E word, an S word,
    motors off...) do not each listen to G0/G1 (a call per rule per line), they share one listener that
    decides in one call which of them a line concerns.  A rule gets the file's listener of a kind with
    ``ctx.move_listener(Kind)`` (made on first ask, ``FileContext.move_listeners``) and joins it
    (``join``); it keeps G0 and G1 out of its own ``codes``.  The engine then, for that file:

    * calls ``move(line, cmd)`` for every G0/G1 line it reads (with the state before the line), at the
      place of the first member among the rules (the order findings are made in);
    * lets a plain move skip the tree unless ``wants_plain(mode, x, y, z, e, f)`` (the words' source texts,
      or None) is true, and asks ``wants_in_run(text, start, end)`` which lines of a run it must read (the
      contract of a rule's ``plain_filter`` and ``run_filter``, docs/architecture.md "Plain moves", "Runs");
    * on a member's failure (found in the traceback: the rule whose method was running) drops that member
      (``drop``) and goes on with the others;
    * lets go of it with the file (``FileContext.release`` calls ``release``).

    The defaults want every move: a subclass narrows ``wants_plain`` and ``wants_in_run``.
    """

    def __init__(self, ctx: FileContext) -> None:
        self.state = ctx.state
        self.members: list[Rule] = []  # the rules it calls, in the order they joined

    def join(self, rule: Rule) -> None:
        """Make ``rule`` a member (the engine blames it, and drops it, when its call fails)."""
        self.members.append(rule)

    def move(self, line: Line, cmd: Command) -> None:
        """Called for every G0/G1 line read (not for the plain moves ``wants_plain`` lets by)."""

    def wants_plain(self, mode: str, x: str | None, y: str | None, z: str | None, e: str | None, f: str | None) -> bool:
        """Whether ``move`` must see this plain move (``mode`` "G0" or "G1", the words' texts or None)."""
        return True

    def wants_in_run(self, text: str, start: int, end: int) -> list[int | RunFinding] | None:
        """The starts of the lines of the run ``text[start:end]`` to read on their own (more is allowed, never
        fewer), or findings in their place (``RunFinding``); None: it may want any line."""
        return None

    def drop(self, rule: Rule) -> None:
        """Stop calling ``rule`` (it failed: the engine dropped it for the rest of the file)."""
        if rule in self.members:
            self.members.remove(rule)

    def release(self) -> None:
        """Let go of the members once the file is done (they hold this listener and the file's context)."""
        self.members = []


# How a rule's fixes are applied, by their applicability (Rule.fix_applicability), for its documentation.
FIX_USAGE = {
    "safe": "gclint check --fix",
    "unsafe": "gclint check --fix --unsafe-fixes (the fix may change what the line does)",
    "sometimes": "gclint check --fix, or --unsafe-fixes where the fix may change what the line does",
}

# A rule's examples are also its test fixtures: "; gclint-test: printer=ehr" lines set the options the
# example is checked with (tests/test_rule_fixtures.py).  The documentation shows them as options.
_EXAMPLE_OPTIONS = re.compile(r"^;\s*gclint-test:\s*(.*)\n?", re.MULTILINE)


def _example(text: str) -> tuple[str, list[str]]:
    """(the example without its test lines, the command-line options those lines stand for)."""
    text = textwrap.dedent(text).strip("\n")
    options = [
        f"--{key} {value}"
        for m in _EXAMPLE_OPTIONS.finditer(text)
        for key, _, value in (item.partition("=") for item in m.group(1).split())
        if key != "expect"
    ]
    return _EXAMPLE_OPTIONS.sub("", text).strip("\n"), options


_REGISTRY: dict[str, type[Rule]] = {}


class RuleError(Exception):
    """A rule (or a plugin) that cannot be loaded; the message names it."""


def register(cls: type[Rule]) -> type[Rule]:
    """Class decorator: add a rule to the registry (codes must be unique)."""
    if not cls.code or len(cls.code) != 5 or not cls.code[:2].isalpha() or not cls.code[2:].isdigit():
        raise RuleError(f"rule {cls.__name__}: code {cls.code!r} is not two letters and three digits")
    existing = _REGISTRY.get(cls.code)
    if existing is not None and existing is not cls and existing.__qualname__ != cls.__qualname__:
        raise RuleError(f"rule {cls.__name__}: code {cls.code} is already used by {existing.__name__}")
    _REGISTRY[cls.code] = cls
    return cls


_LOADED = False


def all_rules() -> dict[str, type[Rule]]:
    """Every registered rule by code (built-in rules and plugins), sorted by code."""
    global _LOADED
    if not _LOADED:
        _LOADED = True
        import gclint.rules  # noqa: F401  (imports the built-in rule modules)

        _load_plugins()
    return dict(sorted(_REGISTRY.items()))


def _load_plugins() -> None:
    if not _may_declare_plugins():
        return
    import types
    from importlib.metadata import entry_points

    for ep in entry_points(group="gclint.rules"):
        plugin = f"rule plugin {ep.name!r} ({ep.value})"
        try:
            obj = ep.load()
        except (Exception, SystemExit) as exc:  # a broken plugin must name itself, not crash gclint
            detail = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
            raise RuleError(f"{plugin} failed to load: {detail}") from None
        if isinstance(obj, types.ModuleType):
            continue  # importing the module registered its rules
        items = obj if isinstance(obj, (list, tuple)) else [obj]
        for item in items:
            if not (isinstance(item, type) and issubclass(item, Rule)):
                raise RuleError(f"{plugin} is not a module, a Rule subclass or a list of them: {item!r}"[:300])
            try:
                register(item)
            except RuleError as exc:
                raise RuleError(f"{plugin}: {exc}") from None


_GROUP = b"gclint.rules"


def _may_declare_plugins() -> bool:
    """Whether some distribution may declare a ``gclint.rules`` entry point: False only when no
    ``entry_points.txt`` that ``importlib.metadata`` would read names the group.  (Importing
    ``importlib.metadata`` costs more than a one-file check's rules: it brings email, zipfile, csv...)  It
    looks where ``importlib.metadata`` looks (the ``.dist-info`` and ``.egg-info`` folders in the folders
    of ``sys.path``, the ``EGG-INFO`` of an ``.egg`` folder) and answers True, to let it look, wherever it
    cannot say: a zip file on the path, another finder of distributions, an unreadable file."""
    import sys
    from importlib.machinery import PathFinder

    for finder in sys.meta_path:
        if finder is not PathFinder and getattr(finder, "find_distributions", None) is not None:
            return True
    for entry in sys.path:
        root = entry or "."
        try:
            children = os.listdir(root)
        except OSError:
            if os.path.exists(root):
                return True  # (a zip file, or a folder it cannot list)
            continue
        egg = os.path.basename(entry).lower().endswith(".egg")
        for child in children:
            low = child.lower()
            if not (low.endswith((".dist-info", ".egg-info")) or egg and low == "egg-info"):
                continue
            try:
                with open(os.path.join(root, child, "entry_points.txt"), "rb") as fh:
                    if _GROUP in fh.read():
                        return True
            except (FileNotFoundError, NotADirectoryError):
                continue
            except OSError:
                return True
    return False


class UnknownSelector(ValueError):
    """A rule code, prefix or name that matches no rule; the message says what was meant, if it can."""


def resolve_selectors(values: Iterable[str], where: str = "") -> list[str]:
    """Upper-case rule selectors, checked: ``ALL``, a code, a prefix of some code (``HY``, ``HY0``) or a
    rule's name (``wait-on-group-address``, read as its code).  Anything else is an error with the
    nearest codes and names, as ruff does (a silently ignored ``--select HY999`` is a green build that
    checked nothing)."""
    registry = all_rules()
    names = {rule.name: code for code, rule in registry.items() if rule.name}
    out: list[str] = []
    for value in values:
        text = value.strip()
        if not text:
            continue
        upper = text.upper()
        if upper == "ALL" or any(code.startswith(upper) for code in registry):
            out.append(upper)
        elif text.lower() in names:
            out.append(names[text.lower()])
        else:
            import difflib

            near = difflib.get_close_matches(upper, list(registry), n=3, cutoff=0.6)
            near += difflib.get_close_matches(text.lower(), list(names), n=2, cutoff=0.6)
            hint = f" (did you mean {', '.join(near)}?)" if near else " (see 'gclint rules')"
            raise UnknownSelector(f"{where}unknown rule code, prefix or name {text!r}{hint}")
    return out


def select_rules(rules: Iterable[type[Rule]], select: Iterable[str] | None, ignore: Iterable[str]) -> list[type[Rule]]:
    """Rules whose code matches ``select`` (default: all rules enabled by default) and not ``ignore``.

    Selectors are codes or prefixes (``HY``, ``HY0``, ``HY003``) or ``ALL``.  The most specific
    selector wins, as in ruff: ``--select HY --ignore HY0`` drops HY0xx but ``--select HY003
    --ignore HY`` keeps HY003; on a tie, ignore wins.
    """
    select = [s.strip().upper() for s in select if s.strip()] if select is not None else None
    ignore = [s.strip().upper() for s in ignore if s.strip()]
    out = []
    for rule in rules:
        if select is None:
            sel = 0 if rule.default_enabled else -1
        else:
            sel = _specificity(rule.code, select)
        if sel >= 0 and sel > _specificity(rule.code, ignore):
            out.append(rule)
    return out


def _specificity(code: str, selectors: list[str]) -> int:
    best = -1
    for s in selectors:
        if s == "ALL":
            best = max(best, 0)
        elif code.startswith(s):
            best = max(best, len(s))
    return best


def matches(code: str, selectors: Iterable[str]) -> bool:
    """True when ``code`` starts with one of ``selectors`` (``ALL`` matches everything)."""
    return any(s == "ALL" or code.startswith(s) for s in selectors)
