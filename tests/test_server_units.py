"""The language server's pure parts, without a client: positions in UTF-16/UTF-8 units, incremental
edits, findings -> diagnostics, fixes and noqa comments -> text edits (checked by applying them and
checking again), hover text from ``explain`` with the state of the lines above, settings and
configuration, cancellation."""

from __future__ import annotations

import threading

import pytest

from gclint import dialects
from gclint.engine import Linter, Options
from gclint.fixes import fix_file
from gclint.ruledocs import rule_url
from gclint.rules.base import Edit, Finding, Fix, Severity
from gclint.server import analysis, convert
from gclint.server.text import UTF8, UTF16, UTF32, Snapshot, char_to_units, clean_surrogates, units_to_char

EMOJI = "\U0001f600"  # outside the BMP: one character, two UTF-16 units, four UTF-8 bytes


def apply_edits(text: str, edits: list[dict], encoding: str = UTF16) -> str:
    """Apply text edits as a client does: all ranges refer to the original text; inserts at the same
    place keep their array order."""
    snap = Snapshot(text)
    spans = []
    for order, e in enumerate(edits):
        start, end = e["range"]["start"], e["range"]["end"]
        a = snap.offset(start["line"], start["character"], encoding)
        b = snap.offset(end["line"], end["character"], encoding)
        spans.append((a, b, order, e["newText"]))
    out = text
    for a, b, _, new in sorted(spans, key=lambda s: (s[0], s[2]), reverse=True):
        out = out[:a] + new + out[b:]
    return out


def _chars(r: dict) -> tuple[int, int]:
    """The start and end characters of a range on one line."""
    return r["start"]["character"], r["end"]["character"]


# -- text and positions ----------------------------------------------------------------------------------


def test_units_for_characters_outside_the_bmp():
    line = f"({EMOJI}) M109 T40 S200"
    index = line.index("M109")
    assert index == 4
    assert char_to_units(line, index, UTF16) == 5
    assert char_to_units(line, index, UTF8) == 7
    assert char_to_units(line, index, UTF32) == 4
    for enc, units in ((UTF16, 5), (UTF8, 7), (UTF32, 4)):
        assert units_to_char(line, units, enc) == index
    # inside the emoji: its start; past the end: the line's length
    assert units_to_char(line, 2, UTF16) == 1
    assert units_to_char(line, 999, UTF16) == len(line)
    assert char_to_units("G1 X1", 3) == 3  # ASCII: units are characters


def test_lone_surrogates_count_one_unit_and_are_cleaned_in_place():
    line = "G1 ; \udc80x"
    assert char_to_units(line, len(line), UTF16) == len(line)
    cleaned = clean_surrogates(line)
    assert cleaned == "G1 ; \ufffdx" and len(cleaned) == len(line)


def test_lines_split_on_lsp_breaks_only():
    snap = Snapshot("G1 X1\r\nG1 X2\x0c ; form feed\rG1 X3\nlast")
    assert snap.line_count == 4
    assert [snap.line(i) for i in range(4)] == ["G1 X1", "G1 X2\x0c ; form feed", "G1 X3", "last"]
    assert snap.line(9) == ""
    assert snap.position(snap.text.index("last")) == (3, 0)


def test_incremental_edit_with_utf16_positions():
    snap = Snapshot(f"; {EMOJI} head\nM109 T40 S200\n")
    text = snap.edited((1, 5), (1, 8), "T0")
    assert text == f"; {EMOJI} head\nM109 T0 S200\n"
    # after the emoji on line 0: character 4 in UTF-16 is the space after it
    text = Snapshot(text).edited((0, 4), (0, 4), "!")
    assert text.startswith(f"; {EMOJI}! head")
    # past the end of the document: appended
    assert Snapshot("G1").edited((5, 0), (5, 0), "X") == "G1X"


# -- diagnostics -----------------------------------------------------------------------------------------


def test_diagnostic_has_code_severity_range_link_and_source():
    text = "; gclint: dialect=hyrel\nM109 T40 S200\n"
    result = Linter(Options()).check_text(text, "job.gcode")
    [f] = [f for f in result.findings if f.code == "HY003"]
    [d] = convert.diagnostics([f], convert.Geometry(Snapshot(text)))
    assert d["code"] == "HY003" and d["source"] == "gclint"
    assert d["severity"] == 1  # error
    assert d["codeDescription"]["href"] == rule_url("HY003")
    assert d["codeDescription"]["href"].startswith("file://") and d["codeDescription"]["href"].endswith(
        "/rules.md#hy003"
    )
    r = d["range"]
    assert (r["start"]["line"], r["start"]["character"], r["end"]["character"]) == (1, 5, 8)  # "T40"


def test_diagnostic_columns_after_a_non_bmp_comment():
    text = f"; gclint: dialect=hyrel\n({EMOJI}) M109 T40 S200\n"
    result = Linter(Options()).check_text(text, "job.gcode")
    [f] = [f for f in result.findings if f.code == "HY003"]
    assert f.column == 10  # gclint: characters
    geo = convert.Geometry(Snapshot(text), UTF16)
    d = convert.to_diagnostic(f, geo)
    assert _chars(d["range"]) == (10, 13)  # UTF-16: the emoji counts twice
    d8 = convert.to_diagnostic(f, convert.Geometry(Snapshot(text), UTF8))
    assert _chars(d8["range"]) == (12, 15)


def test_byte_order_mark_moves_line_one():
    text = "\ufeffM109 T40 S200 ; gclint: dialect=hyrel\n"
    result = Linter(Options()).check_text(text, "job.gcode")
    [f] = [f for f in result.findings if f.code == "HY003"]
    d = convert.to_diagnostic(f, convert.Geometry(Snapshot(text)))
    line = Snapshot(text).line(0)
    assert line[d["range"]["start"]["character"] : d["range"]["end"]["character"]] == "T40"


def test_range_without_end_column_covers_the_word_and_is_clamped():
    geo = convert.Geometry(Snapshot("G1 X10 Y20\nM30"))
    f = Finding("x", 1, 4, "SX002", Severity.ERROR, "m")
    r = convert.finding_range(f, geo)
    assert _chars(r) == (3, 6)
    past = Finding("x", 9, 1, "HY010", Severity.WARNING, "m")  # after the last line (end of file)
    r = convert.finding_range(past, geo)
    assert (r["start"]["line"], r["start"]["character"]) == (1, 3)


def test_diagnostics_limit():
    geo = convert.Geometry(Snapshot("G1\n" * 10))
    findings = [Finding("x", i, 1, "SX002", Severity.ERROR, "m") for i in range(1, 11)]
    assert len(convert.diagnostics(findings, geo, limit=3)) == 3


# -- fixes and noqa --------------------------------------------------------------------------------------


def test_quick_fix_edits_apply_like_check_fix(tmp_path):
    text = "N1 G1 X1*12\nN2 G1 X2*99\n"
    result = Linter(Options()).check_text(text, "job.gcode")
    fixable = [f for f in result.findings if f.fix is not None]
    assert len(fixable) == 2
    geo = convert.Geometry(Snapshot(text))
    one = apply_edits(text, convert.fix_edits(fixable[0].fix, geo))
    assert one.splitlines()[0] == "N1 G1 X1*96" and one.splitlines()[1] == "N2 G1 X2*99"
    # fix all == gclint check --fix
    job = tmp_path / "job.gcode"
    job.write_text(text)
    linter = Linter(Options())
    fix_file(linter.check_path(str(job)), linter)
    assert apply_edits(text, convert.fix_all_edits(result.findings, geo)) == job.read_text()


def test_fix_all_keeps_edits_apart_and_refuses_unparsable_files():
    geo = convert.Geometry(Snapshot("M104 T11 S200\n"))
    first = Fix("a", (Edit(1, 6, 9, "T0"),))
    overlapping = Fix("b", (Edit(1, 7, 9, "X"),))
    insert = Fix("c", (Edit(1, 1, 1, "; "),), safe=False)
    findings = [
        Finding("x", 1, 6, "HY008", Severity.WARNING, "m", fix=first),
        Finding("x", 1, 7, "HY008", Severity.WARNING, "m", fix=overlapping),
        Finding("x", 1, 1, "HY999", Severity.WARNING, "m", fix=insert),
    ]
    # as --fix: later columns first, an edit overlapping one already taken is dropped, unsafe ones left
    assert apply_edits("M104 T11 S200\n", convert.fix_all_edits(findings, geo)) == "M104 TX S200\n"
    broken = [*findings, Finding("x", 1, 1, "SX001", Severity.ERROR, "parse")]
    assert convert.fix_all_edits(broken, geo) == []


@pytest.mark.parametrize(
    "line,expected",
    [
        ("M109 T40 S200", "M109 T40 S200 ; noqa: HY003"),
        ("M109 T40 S200   ", "M109 T40 S200 ; noqa: HY003"),
        ("M109 T40 S200 ; wait for it", "M109 T40 S200 ; wait for it ; noqa: HY003"),
        ("M109 T40 S200 (wait)", "M109 T40 S200 (wait) ; noqa: HY003"),
        ("M109 T40 S200 ; noqa: HY002", "M109 T40 S200 ; noqa: HY003, HY002"),
        ("M109 T40 S200 (noqa: HY002) ; x", "M109 T40 S200 (noqa: HY003, HY002) ; x"),
        ("M109 T40 S200 ; NOQA:HY002 because", "M109 T40 S200 ; NOQA:HY003, HY002 because"),
        (f"M109 T40 S200 ; {EMOJI}", f"M109 T40 S200 ; {EMOJI} ; noqa: HY003"),
    ],
)
def test_noqa_edit_suppresses_the_finding(line, expected):
    text = f"; gclint: dialect=hyrel\n{line}\nM30\n"
    linter = Linter(Options())
    assert any(f.code == "HY003" for f in linter.check_text(text, "job.gcode").findings)
    edit = convert.noqa_edit(convert.Geometry(Snapshot(text)), 2, "HY003")
    fixed = apply_edits(text, [edit])
    assert fixed.splitlines()[1] == expected
    assert not any(f.code == "HY003" for f in linter.check_text(fixed, "job.gcode").findings)


def test_noqa_on_an_empty_line():
    edit = convert.noqa_edit(convert.Geometry(Snapshot("G1\n\nM30\n")), 2, "HY010")
    assert apply_edits("G1\n\nM30\n", [edit]) == "G1\n; noqa: HY010\nM30\n"


def test_code_actions_per_line_and_kind():
    # (M106 S300: HY011, no fix; a v5 group such as M109 T40 would leave HY008's v4 conversion unfixable)
    text = "M6 T12 O2 X0 Y0 Z0\nM109 T12 S200\nM106 S300\nT1\nN1 G1 F100 X1*12\nM30\n"
    result = Linter(Options(dialect="hyrel")).check_text(text, "job.gcode")
    geo = convert.Geometry(Snapshot(text))
    actions = convert.code_actions("file:///job.gcode", result.findings, geo, 0, 0)
    titles = [a["title"] for a in actions]
    assert any(t.startswith("HY008: ") for t in titles)
    # (line 1 is M6, whose comment the translator carries into an M0: no noqa there, as --add-noqa)
    second = [a["title"] for a in convert.code_actions("file:///job.gcode", result.findings, geo, 1, 1)]
    assert "HY008: suppress on this line (; noqa: HY008)" in second
    assert sum(1 for a in actions if a["kind"] == convert.FIX_ALL_KIND) == 1
    assert any(a["kind"] == "quickfix" and a["title"].startswith("Fix all safe") for a in actions)
    fix = next(a for a in actions if a["title"].startswith("HY008: ") and a["isPreferred"])
    assert fix["diagnostics"] and fix["diagnostics"][0]["code"] == "HY008"
    assert list(fix["edit"]["changes"]) == ["file:///job.gcode"]
    # an unsafe fix (the checksum) is offered, marked, never preferred
    fifth = convert.code_actions("file:///job.gcode", result.findings, geo, 4, 4)
    unsafe = next(a for a in fifth if a["title"].startswith("SX004: "))
    assert unsafe["title"].endswith("(unsafe fix)") and not unsafe["isPreferred"]
    # only source.fixAll: the fix-all action alone; versioned edits when the client takes them
    only = convert.code_actions("file:///job.gcode", result.findings, geo, 0, 0, only=["source.fixAll"], version=3)
    assert [a["kind"] for a in only] == [convert.FIX_ALL_KIND]
    assert only[0]["edit"]["documentChanges"][0]["textDocument"]["version"] == 3
    # line 3 (HY011, no fix): noqa only, and fix-all stays available as a source action
    third = convert.code_actions("file:///job.gcode", result.findings, geo, 2, 2)
    assert [a["kind"] for a in third] == ["quickfix", convert.FIX_ALL_KIND]
    assert convert.kind_wanted("source.fixAll.gclint", ["source"]) and not convert.kind_wanted("quickfix", ["source"])


# -- hover -----------------------------------------------------------------------------------------------


def _hover(text: str, line: int, char: int, dialect: str = "hyrel", loaded=None):
    return analysis.explain_at(Snapshot(text), line, char, dialects.get(dialect), loaded)


def test_hover_explains_the_command_under_the_cursor():
    target = _hover("M109 T0 S240 L10 U5\n", 0, 9)  # on S240
    assert target is not None
    assert target.explanation.code == "M109"
    assert target.word == "S240" and (target.start, target.end) == (9, 13)
    text = convert.hover_text(target, markdown=False)
    assert text.startswith("* M109 (wait for head temperature)")
    assert "** S240 (and set the temperature to 240°C)" in text
    md = convert.hover_text(target, markdown=True)
    assert md.startswith("**M109**") and "- `S240` **and set the temperature to 240°C**" in md


def test_hover_uses_the_state_of_the_lines_above():
    # the C range set on line 1 carries over to line 3 (49.8 % duty), as in `gclint explain`
    target = _hover("M106 C255\nG1 X1 Y1\nM106 T1 S127\n", 2, 0)
    assert target is not None
    assert "49.8" in target.explanation.render()
    alone = _hover("M106 T1 S127\n", 0, 0)
    assert alone is not None and "49.8" not in alone.explanation.render()


def test_hover_picks_the_command_and_skips_comments():
    text = "G90 G1 X5 ; comment\n"
    first = _hover(text, 0, 1)
    second = _hover(text, 0, 8)
    assert first is not None and first.explanation.code == "G90"
    assert second is not None and second.explanation.code == "G1" and second.word == "X5"
    assert _hover(text, 0, 14) is None  # on the comment
    assert _hover("; only a comment\n", 0, 3) is None
    assert _hover("G1 X1\n", 5, 0) is None  # past the end


def test_hover_in_the_dialect_of_the_file():
    marlin = _hover("M109 R180\n", 0, 0, "marlin")
    assert marlin is not None and "hotend" in marlin.explanation.title
    v4 = _hover("M109 T11 S240\n", 0, 6, "hyrel-v4")
    assert v4 is not None and "T0" in v4.explanation.render()


def test_hover_range_after_a_non_bmp_comment():
    text = f"({EMOJI}) M109 T40 S200\n"
    target = _hover(text, 0, 10)  # the T of T40 (character 10)
    assert target is not None and target.word == "T40"
    h = convert.hover(target, convert.Geometry(Snapshot(text)), 1, markdown=False)
    assert _chars(h["range"]) == (10, 13)


# -- settings, configuration, cancellation ---------------------------------------------------------------


def test_settings_shapes_and_bad_values():
    settings, problems = analysis.parse_settings(
        {"gclint": {"dialect": "RRF", "printer": "16a-dual", "select": "HY,SX", "ignore": ["hy029"], "x": 1}}
    )
    assert settings.dialect == "reprap" and settings.printer == "16a-dual"
    assert settings.select == ("HY", "SX") and settings.ignore == ("HY029",)
    assert problems and "unknown key 'x'" in problems[0]
    settings, problems = analysis.parse_settings({"dialect": "klingon", "printer": 5, "extend-select": ["SC"]})
    assert settings.dialect is None and settings.printer is None and settings.extend_select == ("SC",)
    assert len(problems) == 2
    assert analysis.parse_settings("nonsense")[1]
    # what VS Code sends for settings left at their default, and its own keys: nothing set, no warning
    untouched = {"path": "gclint", "dialect": "", "printer": "", "select": [], "ignore": [], "trace": {"server": "off"}}
    assert analysis.parse_settings({"gclint": untouched}) == (analysis.Settings(), [])
    assert analysis.parse_settings(None) == (analysis.Settings(), [])


def test_settings_with_an_unknown_rule_code_are_said_and_left_out():
    # a typo in select would otherwise turn every rule off in silence (the CLI exits 2 on it)
    settings, [problem] = analysis.parse_settings({"gclint": {"select": ["HY999"], "dialect": "hyrel"}})
    assert settings.select is None and settings.dialect == "hyrel"
    assert "'HY999'" in problem and "did you mean" in problem and "'select' setting is ignored" in problem
    settings, [problem] = analysis.parse_settings({"ignore": ["HY0O3", "HY010"], "select": "HY"})
    assert settings.ignore is None and settings.select == ("HY",) and "'HY0O3'" in problem
    settings, problems = analysis.parse_settings({"extendSelect": "wait-on-group-address"})  # a rule's name
    assert settings.extend_select == ("HY003",) and problems == []


def test_options_from_the_configuration_file_then_the_settings(tmp_path):
    (tmp_path / "gclint.toml").write_text('dialect = "marlin"\nignore = ["DL"]\nprinter = "esr"\n')
    job = tmp_path / "sub" / "job.gcode"
    job.parent.mkdir()
    options, problem = analysis.document_options(str(job), analysis.Settings())
    assert problem is None and options.dialect == "marlin" and options.ignore == ["DL"] and options.printer == "esr"
    options, _ = analysis.document_options(str(job), analysis.Settings(dialect="hyrel", ignore=("HY029",)))
    assert options.dialect == "hyrel" and options.ignore == ["HY029"] and options.printer == "esr"
    (tmp_path / "gclint.toml").write_text("dialect = [\n")
    options, problem = analysis.document_options(str(job), analysis.Settings(printer="ehr"))
    assert problem is not None and "invalid TOML" in problem and options.printer == "ehr"
    assert analysis.document_options(None, analysis.Settings())[0] == Options()


def test_check_text_cancels_and_survives_bad_text():
    cancel = threading.Event()
    cancel.set()
    with pytest.raises(analysis.Cancelled):
        analysis.check_text("G1 X1\n" * 10, "job.gcode", Options(), cancel)
    binary = analysis.check_text("G1\n\x00\x00\x01\x02" * 50, "job.gcode", Options())
    assert binary.error and "binary" in binary.error
    surrogates = analysis.check_text("G1 X1 ; \ud83d\udc80 \udcff\n", "job.gcode", Options())
    assert surrogates.error is None


def test_no_noqa_is_offered_where_it_would_do_nothing_or_change_the_command():
    """Issue 25: the server offered "; noqa" for SC findings (a job cannot silence them) and on M0/M792 lines
    (the comment is what the printer says or runs: a noqa there changes it)."""
    text = "M792 ; SHELL C:\\x.exe\nM0 T40 ; SAY hello\nM109 T40 S200\nM98 P1234\n"
    result = Linter(Options(dialect="hyrel")).check_text(text, "job.gcode")
    geo = convert.Geometry(Snapshot(text))
    codes = {(f.line, f.code[:2]) for f in result.findings}
    assert {(1, "SC"), (2, "DL"), (3, "HY"), (4, "DL"), (4, "SC")} <= codes, codes

    def noqa(line: int) -> list[str]:
        actions = convert.code_actions("file:///job.gcode", result.findings, geo, line - 1, line - 1)
        return [a["title"].split(":")[0] for a in actions if "noqa" in a["title"]]

    assert noqa(1) == [] and noqa(2) == []  # SC001; and the M0 line whose comment is what it says
    assert noqa(3) == ["HY003"] and noqa(4) == ["DL001"]  # (M98 P1234: DL001 may be silenced, SC004 not)


def test_settings_that_switch_security_rules_off_are_said():
    assert analysis.security_off(Options()) is None
    said = analysis.security_off(Options(ignore=["SC001", "SC003"]))
    assert said is not None and "SC001, SC003" in said and "not shown" in said
    # a configuration found beside the document cannot switch them off (gclint.trust): nothing to say
    assert analysis.security_off(analysis.document_options(None, analysis.Settings(ignore=("SC",)))[0]) is not None


def test_a_found_configuration_does_not_switch_security_rules_off_in_the_editor(tmp_path):
    (tmp_path / ".gclint.toml").write_text('ignore = ["SC"]\n')
    options, problem = analysis.document_options(str(tmp_path / "job.gcode"), analysis.Settings())
    assert problem is None and analysis.security_off(options) is None
    result = analysis.check_text("M792 ; SHELL C:\\x.exe\n", str(tmp_path / "job.gcode"), options)
    assert [f.code for f in result.findings if f.code.startswith("SC")] == ["SC001"]


def test_rule_links_in_any_install(tmp_path, monkeypatch):
    """Issue 28: a rule's link (codeDescription.href, SARIF helpUri) existed only in editable installs.  The
    build copies docs/rules.md into the package (setup.py); the copy is linked first, then the checkout's."""
    from gclint import ruledocs

    packaged = tmp_path / "site-packages" / "gclint" / "_docs" / "rules.md"
    packaged.parent.mkdir(parents=True)
    packaged.write_text("### HY003\n")
    monkeypatch.delenv("GCLINT_DOCS_URL", raising=False)
    monkeypatch.setattr(ruledocs, "PACKAGED", packaged)
    ruledocs.reference.cache_clear()
    try:
        assert ruledocs.rule_url("HY003") == packaged.as_uri() + "#hy003"
        geo = convert.Geometry(Snapshot("M109 T40 S200\n"))
        d = convert.to_diagnostic(Finding("x", 1, 6, "HY003", Severity.ERROR, "m"), geo)
        assert d["codeDescription"]["href"] == packaged.as_uri() + "#hy003"
        monkeypatch.setattr(ruledocs, "PACKAGED", tmp_path / "missing.md")  # an editable install: the checkout's
        ruledocs.reference.cache_clear()
        assert ruledocs.rule_url("SX002") == ruledocs.CHECKOUT.as_uri() + "#sx002"
        monkeypatch.setenv("GCLINT_DOCS_URL", "https://docs.example/rules.md")  # a published copy wins
        ruledocs.reference.cache_clear()
        assert ruledocs.rule_url("SX002") == "https://docs.example/rules.md#sx002"
    finally:
        ruledocs.reference.cache_clear()


def test_a_document_that_is_not_gcode_is_an_error_result_not_an_internal_error():
    from gclint.server.protocol import _dialect_for

    text = "\0\0\0\0binary\0\0\0\nG1 X1\n"
    result = analysis.check_text(text, "bin.gcode", Options())
    assert result.error and "internal error" not in result.error and "NUL" in result.error
    dialect, _ = _dialect_for(None, Options(), Snapshot(text), "bin.gcode")
    assert dialect.name
