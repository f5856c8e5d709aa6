"""Scaffold a new rule: its class, its fixture pair and a test, in the places the project keeps them.

    .venv/bin/python scripts/add_rule.py HY068 --name my-rule-name --summary "One line" [--family hyrel]
        [--codes M104,M109] [--severity warning] [--module temperature] [--root DIR]

What it writes (CONTRIBUTING.md, "Adding a rule", says what to do with each):

* the rule class, with every field the documentation and the tests read, and a ``check`` that reports every
  command it listens to (a placeholder: narrow it).  It goes into ``--module`` (an existing topic module of
  the family's package, or a new module it creates and registers where the package imports its rules); by
  default into the topic module whose rules already listen to the most of ``--codes``, else a new module
  named after the rule.  A rule that listens to G0, G1, G2 or G3 gets a ``trigger_letters`` that keeps plain
  moves on their fast route (docs/architecture.md, "Plain moves");
* ``tests/fixtures/rules/<CODE>_bad.gcode`` (one line the placeholder reports) and ``<CODE>_good.gcode``;
* ``tests/test_rule_<code>.py``: where the rule reports, as a table to extend;
* for an HY rule, the count in README.md and a row of docs/hy-rules.md.

It does not regenerate docs/rules.md or the findings snapshots (the rule's text is still a placeholder): it
prints the commands that do.  A code that is malformed, of a family the scaffold does not write (TR, PF), or
already used, is refused with one line on stderr and exit 2.  ``--root`` writes into another checkout (its
own test writes into a temporary copy).
"""

from __future__ import annotations

import argparse
import ast
import json
import re
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

CODE = re.compile(r"^([A-Z]{2})(\d{3})$")
NAME = re.compile(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$")
COMMAND = re.compile(r"^(?:[GM]\d+(?:\.\d+)?|T\*)$")
SEVERITIES = ("error", "warning", "info")
MOVES = ("G0", "G1", "G2", "G3")


@dataclass(frozen=True)
class Family:
    """Where the rules of one code prefix live."""

    title: str
    package: str | None  # a package with one module per topic (gclint/rules/<package>/), or None
    module: str | None  # the single module of the family (gclint/rules/<module>.py), or None
    default_families: tuple[str, ...] | None  # the dialect families its rules apply to by default


FAMILIES = {
    "HY": Family("Hyrel semantics", "hyrel", None, ("hyrel",)),
    "DL": Family("dialect conformance", None, "dialect", None),
    "SX": Family("syntax and structure", None, "syntax", None),
    "SC": Family("security", "security", None, None),
}
NOT_SCAFFOLDED = {
    "TR": "TR codes are translation findings, documented in gclint/rules/translation.py and reported by a "
    "translator (CONTRIBUTING.md, 'Adding a translation source')",
    "PF": "PF codes are slicer-profile findings (gclint/rules/profiles.py, reported by gclint/profiles/check.py)",
}


class Refused(Exception):
    """Why the scaffold will not write (one line)."""


# -- reading the tree ------------------------------------------------------------------------------------------


def rule_files(root: Path) -> list[Path]:
    return sorted((root / "gclint" / "rules").rglob("*.py"))


def used(root: Path, attribute: str) -> dict[str, Path]:
    """Every ``<attribute> = "..."`` value in the rule modules (codes, names), with the file it is in."""
    pattern = re.compile(rf'^\s+{attribute} = "([^"]+)"', re.MULTILINE)
    out: dict[str, Path] = {}
    for path in rule_files(root):
        for value in pattern.findall(path.read_text(encoding="utf-8")):
            out.setdefault(value, path)
    return out


def dialect_families(root: Path) -> dict[str, str]:
    """Dialect family -> the name of its first dialect (``hyrel`` -> ``hyrel``, ``linuxcnc`` -> ``machinekit``)."""
    out: dict[str, str] = {}
    declared = re.compile(r'= Dialect\(\s*name="([^"]+)",\s*title=.*?,\s*family="([^"]+)"', re.DOTALL)
    for path in sorted((root / "gclint" / "dialects").glob("*.py")):
        for name, family in declared.findall(path.read_text(encoding="utf-8")):
            out.setdefault(family, name)
    return out


def listened_codes(path: Path) -> set[str]:
    """The command codes the rules of a module listen to (their ``codes = (...)`` tuples of literals)."""
    out: set[str] = set()
    try:
        tree = ast.parse(path.read_text(encoding="utf-8"))
    except SyntaxError:
        return out
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Assign)
            and any(isinstance(t, ast.Name) and t.id == "codes" for t in node.targets)
            and isinstance(node.value, ast.Tuple)
        ):
            out.update(e.value for e in node.value.elts if isinstance(e, ast.Constant) and isinstance(e.value, str))
    return out


# -- the plan ------------------------------------------------------------------------------------------------------


@dataclass
class Plan:
    code: str
    name: str
    summary: str
    severity: str
    codes: tuple[str, ...]
    families: tuple[str, ...] | None
    family: Family
    module: Path
    new_module: bool
    example_dialect: str | None  # the dialect the examples and fixtures are read as (None: detected)

    @property
    def class_name(self) -> str:
        return "".join(part.capitalize() for part in self.name.split("-"))

    @property
    def moves(self) -> tuple[str, ...]:
        return tuple(c for c in self.codes if c in MOVES)


def plan(args: argparse.Namespace, root: Path) -> Plan:
    code = args.code.strip().upper()
    m = CODE.match(code)
    if m is None:
        raise Refused(f"{args.code!r} is not a rule code: two capital letters and three digits (HY068)")
    prefix = m.group(1)
    if prefix in NOT_SCAFFOLDED:
        raise Refused(f"{code}: {NOT_SCAFFOLDED[prefix]}; the scaffold writes {', '.join(FAMILIES)} rules")
    if prefix not in FAMILIES:
        raise Refused(f"{code}: unknown code family {prefix} (known: {', '.join([*FAMILIES, *NOT_SCAFFOLDED])})")
    codes_used = used(root, "code")
    if code in codes_used:
        raise Refused(f"{code} is already used ({codes_used[code].relative_to(root)})")
    fixtures = root / "tests" / "fixtures" / "rules"
    for kind in ("bad", "good"):
        if (fixtures / f"{code}_{kind}.gcode").exists():
            raise Refused(f"{code} is already used (tests/fixtures/rules/{code}_{kind}.gcode exists)")
    name = args.name.strip()
    if not NAME.match(name):
        raise Refused(f"{name!r} is not a rule name: lower-case words joined by '-' (wait-on-group-address)")
    names_used = used(root, "name")
    if name in names_used:
        raise Refused(f"the name {name!r} is already used ({names_used[name].relative_to(root)})")
    summary = " ".join(args.summary.split())
    if not summary or '"' in summary or "\\" in summary:
        raise Refused("--summary must be one line of text without double quotes or backslashes")
    codes = tuple(c.strip().upper() for c in (args.codes or "").split(",") if c.strip())
    for c in codes:
        if not COMMAND.match(c):
            raise Refused(f"--codes: {c!r} is not a command code (G1, M104, G2.1, or T* for every T command)")
    family = FAMILIES[prefix]
    known = dialect_families(root)
    if args.family:
        families: tuple[str, ...] | None = tuple(f.strip() for f in args.family.split(",") if f.strip())
        for f in families:
            if f not in known:
                raise Refused(f"--family: unknown dialect family {f!r} (known: {', '.join(sorted(known))})")
    else:
        families = family.default_families
    example_dialect = known[families[0]] if families else None
    module, new_module = _module(args.module, family, codes, name, root)
    return Plan(code, name, summary, args.severity, codes, families, family, module, new_module, example_dialect)


def _module(wanted: str | None, family: Family, codes: tuple[str, ...], name: str, root: Path) -> tuple[Path, bool]:
    rules = root / "gclint" / "rules"
    if family.package is None:
        if wanted and wanted != family.module:
            raise Refused(f"--module: the {family.title} rules all live in gclint/rules/{family.module}.py")
        return rules / f"{family.module}.py", False
    package = rules / family.package
    if wanted:
        if not re.match(r"^[a-z][a-z0-9_]*$", wanted):
            raise Refused(f"--module: {wanted!r} is not a module name (lower_case)")
        path = package / f"{wanted}.py"
        return path, not path.exists()
    # the topic module whose rules already listen to the most of these codes
    best, overlap = None, 0
    for path in sorted(package.glob("*.py")):
        if path.name.startswith("_") or path.stem in ("base", "common", "views"):
            continue
        shared = len(listened_codes(path) & set(codes))
        if shared > overlap:
            best, overlap = path, shared
    if best is not None:
        return best, False
    return package / f"{name.replace('-', '_')}.py", True


# -- the text ------------------------------------------------------------------------------------------------------


def _examples(p: Plan) -> tuple[str, str]:
    """(the line the placeholder check reports, a line it does not)."""
    if p.codes:
        first = next((c for c in p.codes if c != "T*"), "T1")
        bad = f"{first} X10 Y10 H1" if first in MOVES else first
    else:
        bad = f"; {p.code}-EXAMPLE (the placeholder pattern)"
    good = next(c for c in ("G21", "G90", "G4 P0") if c.split()[0] not in p.codes)
    return bad, good


def _tuple(values: tuple[str, ...]) -> str:
    """A tuple of strings as ruff format writes it: ``("M104",)``, ``("M104", "M109")``."""
    items = ", ".join(f'"{v}"' for v in values)
    return f"({items},)" if len(values) == 1 else f"({items})"


def rule_source(p: Plan) -> str:
    bad, good = _examples(p)
    header = f"; gclint: dialect={p.example_dialect}\\n" if p.example_dialect and p.example_dialect != "hyrel" else ""
    lines = [
        f"# -- {p.code} " + "-" * (98 - len(p.code)),
        "",
        "",
        "@register",
        f"class {p.class_name}(Rule):",
        f'    code = "{p.code}"',
        f'    name = "{p.name}"',
        f"    severity = Severity.{p.severity.upper()}",
        f'    summary = "{p.summary}"',
        '    explanation = """',
        "        TODO: why it matters, in the machine's terms, quoting the page the fact comes from (markdown).",
        '    """',
        "    # TODO: a real case and its correction (the bad one must trigger the rule, the good one must not:",
        "    # tests/test_rule_fixtures.py checks both; docs/rules.md shows them)",
        f'    example_bad = "{header}{bad}"',
        f'    example_good = "{header}{good}"',
        '    source = "TODO: the public page and its section (docs/sources.md)"',
    ]
    if p.codes:
        lines.append(f"    codes = {_tuple(p.codes)}".replace('"T*"', "ANY_T"))
    else:
        lines += [
            "    # TODO: the lines check_view reads.  A multi-line pattern must match lines joined by line breaks when",
            "    # it matches one of them, and never at a line break (rules/base.py, on_line_matching).",
            f'    on_line_matching = re.compile(r"(?m){p.code}-EXAMPLE")',
        ]
    if p.families is not None:
        lines.append(f"    families = {_tuple(p.families)}")
    if p.moves:
        lines += [
            "",
            "    def trigger_letters(self, code: str) -> frozenset[str] | None:",
            "        # G0-G3 are the hot path: check sees only the moves with one of these letters, which a plain move",
            "        # (X Y Z E F) or an arc of a run (X Y Z I J E F) never has.  To read plain moves, declare",
            "        # plain_filter(mode, x, y, z, e, f) and run_filter(text, start, end) instead (CONTRIBUTING.md).",
            f'        return frozenset("H") if code in {_tuple(p.moves)} else None',
        ]
    if p.codes:
        lines += [
            "",
            "    def check(self, line: Line, cmd: Command) -> None:",
            "        # TODO: report only what is wrong (the state before cmd is self.state); as written, every",
            "        # command the rule listens to is reported",
            '        self.report(line, f"{cmd.code}: TODO say what is wrong and what to write instead", node=cmd)',
        ]
    else:
        lines += [
            "",
            "    def check_view(self, line: Line) -> None:",
            '        self.report(line, "TODO say what is wrong and what to write instead")',
        ]
    return "\n".join(lines) + "\n"


def needed_imports(p: Plan) -> dict[str, set[str]]:
    out: dict[str, set[str]] = {"gclint.rules.base": {"Rule", "Severity", "register"}, "gclint.syntax.nodes": {"Line"}}
    if p.codes:
        out["gclint.syntax.nodes"].add("Command")
    else:
        out[""] = {"re"}
    if "T*" in p.codes:
        out["gclint.rules.base"].add("ANY_T")
    return out


def new_module_text(p: Plan) -> str:
    imports = needed_imports(p)
    head = [
        f'"""{p.code}: {p.summary}',
        "",
        "Source: TODO, the public page and section the rule comes from (docs/sources.md).",
        '"""',
        "",
        "from __future__ import annotations",
        "",
    ]
    if "" in imports:
        head += [f"import {name}" for name in sorted(imports.pop(""))] + [""]
    head += [f"from {module} import {', '.join(sorted(names))}" for module, names in sorted(imports.items())]
    return "\n".join(head) + "\n\n" + rule_source(p)


def with_imports(text: str, p: Plan) -> str:
    """``text`` (a module) with the names the new rule needs imported, as isort (ruff's I001) would have them:
    added to the module's import from the same module, or as a new import in its sorted place."""
    lines = text.splitlines(keepends=True)
    imports = [node for node in ast.parse(text).body if isinstance(node, ast.Import | ast.ImportFrom)]
    edits: list[tuple[int, int, list[str]]] = []  # (first line index, end index, new lines)
    for module, names in needed_imports(p).items():
        if module == "":
            have = {a.asname or a.name for node in imports if isinstance(node, ast.Import) for a in node.names}
            missing = sorted(names - have)
            if not missing:
                continue
            plain = [node for node in imports if isinstance(node, ast.Import)]
            if plain:
                at = plain[-1].end_lineno or 0
                edits.append((at, at, [f"import {n}\n" for n in missing]))
            else:  # (after ``from __future__ import annotations`` and its blank line)
                future = [n for n in imports if isinstance(n, ast.ImportFrom) and n.module == "__future__"]
                at = (future[-1].end_lineno or 0) + 1 if future else 0
                edits.append((at, at, [f"import {n}\n" for n in missing] + ["\n"]))
            continue
        same = [node for node in imports if isinstance(node, ast.ImportFrom) and node.module == module]
        if same:
            node = same[0]
            have = {a.name for a in node.names}
            if names <= have or any(a.asname for a in node.names):
                continue
            merged = sorted(have | names, key=_isort_key)
            one = f"from {module} import {', '.join(merged)}\n"
            if len(one) > 121:
                one = f"from {module} import (\n" + "".join(f"    {n},\n" for n in merged) + ")\n"
            edits.append((node.lineno - 1, node.end_lineno or node.lineno, [one]))
            continue
        ours = [n for n in imports if isinstance(n, ast.ImportFrom) and (n.module or "").startswith("gclint")]
        after = [n for n in ours if (n.module or "") > module]
        at = after[0].lineno - 1 if after else (ours[-1].end_lineno or 0) if ours else len(lines)
        edits.append((at, at, [f"from {module} import {', '.join(sorted(names, key=_isort_key))}\n"]))
    for start, end, new in sorted(edits, key=lambda e: (e[0], e[1]), reverse=True):  # (bottom up)
        lines[start:end] = new
    return "".join(lines)


def _isort_key(name: str) -> tuple[int, str]:
    """isort's order of imported names: constants, then classes, then functions."""
    kind = 0 if name.isupper() else 1 if name[:1].isupper() else 2
    return kind, name


def register_module(p: Plan, root: Path) -> Path:
    """Add the new module to the import list of its package's ``__init__.py`` (importing registers the rules)."""
    init = root / "gclint" / "rules" / p.family.package / "__init__.py"  # type: ignore[operator]
    text = init.read_text(encoding="utf-8")
    package = f"gclint.rules.{p.family.package}"
    found = [
        node
        for node in ast.parse(text).body
        if isinstance(node, ast.ImportFrom) and node.module == package and not any(a.asname for a in node.names)
    ]
    if not found:
        raise Refused(f"{init.relative_to(root)}: no 'from {package} import ...' line to register the module in")
    node = found[0]
    lines = text.splitlines(keepends=True)
    first = lines[node.lineno - 1]
    comment = first[first.index("#") :].rstrip() if "#" in first else "# noqa: F401"
    names = sorted({a.name for a in node.names} | {p.module.stem})
    statement = f"from {package} import (  {comment}\n" + "".join(f"    {n},\n" for n in names) + ")\n"
    lines[node.lineno - 1 : node.end_lineno] = [statement]
    init.write_text("".join(lines), encoding="utf-8")
    return init


def fixture_texts(p: Plan) -> tuple[str, str]:
    bad, good = _examples(p)
    head = f"; gclint: dialect={p.example_dialect}\n" if p.example_dialect else ""
    return (
        f"{head}; {p.code} {p.name}: the line below must be reported (TODO: a real case from the page)\n{bad}\n",
        f"{head}; {p.code} {p.name}: nothing here is reported (TODO: the corrected case)\n{good}\n",
    )


def test_text(p: Plan) -> str:
    bad, good = _examples(p)
    dialect = p.example_dialect or "auto"
    return f'''"""{p.code} {p.name}: {p.summary}

tests/test_rule_fixtures.py checks the fixture pair (tests/fixtures/rules/{p.code}_bad.gcode, _good.gcode) and the
rule's examples, tests/test_rule_snapshots.py pins its findings on the bad fixture; this table holds the cases
the fixtures do not.
"""

from __future__ import annotations

import pytest

from gclint.engine import Linter, Options

CODE = "{p.code}"


def found(text: str, dialect: str = "{dialect}") -> list[tuple[int, int]]:
    """(line, column) of each {p.code} finding in ``text`` read as ``dialect``."""
    result = Linter(Options(dialect=dialect)).check_text(text, "<test>")
    return [(f.line, f.column) for f in result.findings if f.code == CODE]


@pytest.mark.parametrize(
    "text,expected",
    [
        # TODO: the cases the rule is about: reported (line, column), and close ones that are not
        ({json.dumps(bad + chr(10))}, [(1, 1)]),
        ({json.dumps(good + chr(10))}, []),
    ],
)
def test_where_{p.code.lower()}_reports(text: str, expected: list[tuple[int, int]]) -> None:
    assert found(text) == expected
'''


def hy_docs(p: Plan, root: Path) -> list[Path]:
    """The README's count of HY rules and docs/hy-rules.md's table (tests check the count)."""
    changed = []
    readme = root / "README.md"
    text = readme.read_text(encoding="utf-8")
    m = re.search(r"\((\d+) rules from the Hyrel pages\)", text)
    if m is not None:
        count = len([c for c in used(root, "code") if c.startswith("HY")])  # (the new rule is written by now)
        readme.write_text(text[: m.start(1)] + str(count) + text[m.end(1) :], encoding="utf-8")
        changed.append(readme)
    table = root / "docs" / "hy-rules.md"
    if table.exists():
        lines = table.read_text(encoding="utf-8").splitlines(keepends=True)
        rows = [i for i, line in enumerate(lines) if re.match(r"^\| HY\d{3} \|", line)]
        if rows:
            severity = p.severity[0].upper()
            row = f"| {p.code} | {p.name} | {severity} | {p.module.stem} | TODO (the page section) |\n"
            at = next((i for i in rows if lines[i][2:7] > p.code), rows[-1] + 1)
            lines.insert(at, row)
            table.write_text("".join(lines), encoding="utf-8")
            changed.append(table)
    return changed


# -- main ----------------------------------------------------------------------------------------------------------


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], prog="add_rule.py")
    parser.add_argument("code", help="the new rule's code: HY068, DL008, SX009, SC008")
    parser.add_argument("--name", required=True, help="kebab-case name (wait-on-group-address)")
    parser.add_argument("--summary", required=True, help="one line: what is wrong")
    parser.add_argument("--family", help="dialect families it applies to, comma-separated (default: hyrel for HY)")
    parser.add_argument("--codes", help="command codes it listens to, comma-separated (M104,M109; T* for T<n>)")
    parser.add_argument("--severity", choices=SEVERITIES, default="warning")
    parser.add_argument("--module", help="the topic module (HY, SC): an existing one, or a new one to create")
    parser.add_argument("--root", type=Path, default=ROOT, help="the checkout to write into (default: this one)")
    args = parser.parse_args(argv)
    root = args.root.resolve()
    if not (root / "gclint" / "rules" / "base.py").is_file():
        print(f"add_rule.py: {root} is not a gclint checkout (no gclint/rules/base.py)", file=sys.stderr)
        return 2
    try:
        p = plan(args, root)
        fixtures = root / "tests" / "fixtures" / "rules"
        test = root / "tests" / f"test_rule_{p.code.lower()}.py"
        if test.exists():
            raise Refused(f"{test.relative_to(root)} exists")
        written: list[Path] = []
        if p.new_module:
            p.module.write_text(new_module_text(p), encoding="utf-8")
            written += [p.module, register_module(p, root)]
        else:
            text = with_imports(p.module.read_text(encoding="utf-8"), p)
            p.module.write_text(text.rstrip("\n") + "\n\n\n" + rule_source(p), encoding="utf-8")
            written.append(p.module)
    except Refused as exc:
        print(f"add_rule.py: {exc}", file=sys.stderr)
        return 2
    bad, good = fixture_texts(p)
    (fixtures / f"{p.code}_bad.gcode").write_text(bad, encoding="utf-8")
    (fixtures / f"{p.code}_good.gcode").write_text(good, encoding="utf-8")
    test.write_text(test_text(p), encoding="utf-8")
    written += [fixtures / f"{p.code}_bad.gcode", fixtures / f"{p.code}_good.gcode", test]
    if p.code.startswith("HY"):
        written += hy_docs(p, root)
    print(f"{p.code} {p.name}: wrote")
    for path in written:
        print(f"  {path.relative_to(root)}")
    where = p.module.relative_to(root)
    print(
        "Next (CONTRIBUTING.md, 'Adding a rule'):\n"
        f"  1. {where}: write the check, the explanation, the examples and the source (every TODO)\n"
        f"  2. the fixtures and tests/test_rule_{p.code.lower()}.py: real cases\n"
        "  3. .venv/bin/python scripts/gen_rules_doc.py                      (docs/rules.md)\n"
        f"  4. GCLINT_UPDATE_SNAPSHOTS=1 .venv/bin/python -m pytest -q -n0 tests/test_rule_snapshots.py -k {p.code}\n"
        f"  5. .venv/bin/python -m pytest -q tests/test_rule_{p.code.lower()}.py tests/test_rule_fixtures.py "
        "tests/test_rule_docs.py tests/test_rule_snapshots.py tests/test_plain_moves.py tests/test_reports.py"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
