"""Hyrel addressing rules (HY006, HY007, HY008, HY022, HY045, HY047, HY048) and the command line around
them: --statistics, suppression comments, [tool.gclint] configuration (issue "Hyrel rules", done
means 3).  CLI tests run the real command in a subprocess."""

from __future__ import annotations

import json
import re
import textwrap

import pytest

from gclint.engine import Linter, Options
from gclint.rules.base import Severity

from .conftest import run_cli


def lint(text: str, dialect: str = "hyrel", printer: str = "30m", loaded=None, codes: tuple[str, ...] = ()):
    options = Options(dialect=dialect, printer=printer, loaded=frozenset(loaded) if loaded is not None else None)
    found = Linter(options).check_text(textwrap.dedent(text)).findings
    return [f for f in found if not codes or f.code in codes]


def own_edit(finding):
    """The edit of a finding's fix at the finding's own word (an HY008 fix converts the whole file)."""
    return next(e for e in finding.fix.edits if e.line == finding.line and e.start == finding.column)


def where(findings) -> list[tuple[int, str, str]]:
    return [(f.line, f.code, f.severity.label) for f in findings]


# -- HY006 tool-not-loaded -----------------------------------------------------------------------------


def test_hy006_loaded_heads_from_the_command_line_win_over_the_header():
    text = """\
        M6 T0 O1 X0 Y0 Z0
        M6 T1 O2 X20 Y0 Z0
        T1
        T2
        T0
        """
    assert where(lint(text, codes=("HY006",))) == [(4, "HY006", "warning")]
    assert where(lint(text, loaded={0, 2}, codes=("HY006",))) == [(3, "HY006", "warning")]


def test_hy006_is_silent_when_nobody_says_which_heads_are_loaded():
    assert lint("T1\nT2\nT3\n", codes=("HY006",)) == []


def test_hy006_takes_the_whole_header_and_reports_each_position_once():
    text = """\
        T1
        M6 T0 O1 X0 Y0 Z0
        M6 T1 O2 X20 Y0 Z0
        T3
        T3
        T0
        """
    assert where(lint(text, codes=("HY006",))) == [(4, "HY006", "warning")]


def test_hy006_reads_v4_header_addresses():
    # v4: "M6 T12 O2" declares yoke 1 position 2, which the T command "T1" selects
    text = "M6 T12 O2 X70 Y60\nT1\nT2\n"
    assert where(lint(text, dialect="hyrel-v4", codes=("HY006",))) == [(3, "HY006", "warning")]


def test_hy006_an_m6_without_o_declares_nothing():
    # "M6 T1" is a CNC-style tool change (HY038), not Repetrel's "M6 T# O..." declaration
    assert where(lint("M6 T0 O1 X0 Y0\nM6 T1\nT1\nT0\n", codes=("HY006",))) == [(3, "HY006", "warning")]


def test_hy006_any_mismatch_includes_a_loaded_head_no_t_command_calls():
    # "If there is any mismatch, warning message popups will appear.  If you have your heads called out
    # in your gcode and the same tool positions loaded with heads, you will not see these warnings."
    text = """\
        M6 T0 O1 X0 Y0 Z0
        M6 T1 O2 X20 Y0 Z0
        M6 T2 O3 X40 Y0 Z0
        T0
        G1 X10 E1 F600
        T2
        G1 X20 E1
        """
    found = lint(text, codes=("HY006",))
    assert where(found) == [(2, "HY006", "warning")]
    assert "T1" in found[0].message and "no T command calls it" in found[0].message
    # from --loaded: reported at line 1
    assert where(lint("T0\nG1 X1 E1 F600\n", loaded={0, 3}, codes=("HY006",))) == [(1, "HY006", "warning")]
    # a head that prints through a clone squad, or copies another head, is called
    squad = text + "        M702 T0 S30\n        M703 T1 S30\n"
    assert lint(squad, codes=("HY006",)) == []


def test_hy006_default_mode_one_head_no_t_command_is_fine():
    # "the gcode will be executed with the only head loaded, regardless of what slot it is in"
    assert lint("M6 T1 O2 X0 Y0 Z0\nG1 X10 E1 F600\nM30\n", codes=("HY006",)) == []
    assert lint("G1 X10 E1 F600\n", loaded={2}, codes=("HY006",)) == []
    # two loaded heads and no T command: both are a mismatch
    found = lint("M6 T0 O1 X0 Y0 Z0\nM6 T1 O2 X20 Y0 Z0\nG1 X10 E1 F600\n", codes=("HY006",))
    assert where(found) == [(1, "HY006", "warning"), (2, "HY006", "warning")]


# -- HY007 tool-beyond-model ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "printer,bad",
    [
        ("30m", ["T4", "M104 T5 S200"]),
        ("esr", ["T4"]),
        ("ehr", ["T5"]),
        ("16a", ["T5"]),
        ("16a-dual", ["M104 T19 S1", "T17"]),
    ],
)
def test_hy007_positions_per_model(printer, bad):
    for line in bad:
        assert [f.code for f in lint(line + "\n", printer=printer, codes=("HY007",))] == ["HY007"], (printer, line)


@pytest.mark.parametrize("printer,good", [("30m", "T3"), ("ehr", "T4"), ("16a", "M104 T4 S200"), ("16a-dual", "T9")])
def test_hy007_allows_the_positions_the_model_has(printer, good):
    assert lint(good + "\n", printer=printer, codes=("HY007",)) == []


def test_hy007_v4_numbers_are_translated_first():
    # v4 M104 T21 is yoke 2, position 1 = v5 T5: not on a 30M, fine on a dual-yoke 16A
    assert [f.code for f in lint("M104 T21 S200\n", dialect="hyrel-v4", codes=("HY007",))] == ["HY007"]
    assert lint("M104 T21 S200\n", dialect="hyrel-v4", printer="16a-dual", codes=("HY007",)) == []


# -- HY008 v4-addressing-in-v5 -------------------------------------------------------------------------


def test_hy008_only_in_v5_files():
    assert lint("M109 T12 S200\n", dialect="hyrel-v4", codes=("HY008",)) == []
    found = lint("M109 T12 S200\n", codes=("HY008",))
    assert where(found) == [(1, "HY008", "warning")]
    assert found[0].fix is not None and own_edit(found[0]).text == "T1"


@pytest.mark.parametrize(
    "line,v5",
    [
        ("M104 T100 S0", "T47"),  # v4 all heads -> v5 all non-bed devices
        ("M140 T90 S0", "T46"),  # all beds
        ("M140 T91 S60", "T24"),  # bed 1
        ("M3 T26 S50", "T20"),  # spindle
        ("M104 T10 S0", "T41"),  # yoke 1, all heads
        ("M104 T25 S200", "T9"),  # yoke 2, position 5
    ],
)
def test_hy008_rewrites_with_the_certain_map(line, v5):
    # in a file whose addresses say v4 (M6 T12 O2, M109 T12: v4 head 2, no head in v5)
    found = lint("M6 T12 O2\nM109 T12 S200\n" + line + "\n", printer="16a-dual", codes=("HY008",))
    assert [own_edit(f).text for f in found if f.line == 3] == [v5]


def test_hy008_aux_map_is_uncertain():
    # v4 aux T16 (Hyrel v4 firmware toolNumberMap: tool 10 -> 16) is certain for v4; that it is v5 Aux1 T22 is
    # inferred (confidence: medium, docs/sources.md): no fix, and the message says so
    # (in a file whose addresses say v4: M6 T12 O2, M109 T12 are v4 heads)
    found = lint("M6 T12 O2\nM109 T12 S200\nM104 T16 S0\n", printer="16a-dual", codes=("HY008",))
    found = [f for f in found if f.line == 3]
    assert len(found) == 1 and found[0].fix is None
    assert "uncertain" in found[0].message


def test_hy008_leaves_addresses_that_mean_the_same_in_v5():
    # Bed1, the CO2 laser and the spindle have these numbers in v5: no finding while nothing else is v4
    text = "M190 T24 S60\nM140 T25 S60\nM620 T21 E1\nM620 T21 E0\nM6 T21 O5 X10\nM3 T20 S50\n"
    assert lint(text, printer="16a-dual", codes=("HY008",)) == []


def test_hy008_only_where_the_files_addresses_say_v4():
    # one v4-looking number among v5 ones: the file is v5, and T12 is what it is in v5 (issue 11)
    text = "M190 T24 S60\nM141 T25 S40\nM109 T12 S200\n"
    assert lint(text, printer="16a", codes=("HY008",)) == []
    hy007 = lint(text, printer="16a", codes=("HY007",))
    assert where(hy007) == [(3, "HY007", "error")] and "in v4 numbering T12 was yoke 1, position 2" in hy007[0].message
    # the same numbers in a file whose addresses say v4: all reported; where v5 also has a meaning, the
    # fix is unsafe (M190 T24 is Bed1 in v5)
    text = "M6 T12 O2\nM6 T13 O3\nM221 T12 S1\nM190 T24 S60\nM109 T12 S200\n"
    found = lint(text, codes=("HY008",))
    assert where(found) == [(n, "HY008", "warning") for n in (1, 2, 3, 4, 5)]
    # the file is converted as a whole (a half-converted file means something else): one of its
    # addresses also reads as v5, so every finding's fix is the whole, unsafe conversion
    assert [f.fix.safe for f in found] == [False] * 5
    assert all(f.fix.edits == found[0].fix.edits and len(f.fix.edits) == 5 for f in found)
    assert ["in v5 write" in f.message for f in found] == [True, True, True, False, True]


def test_hy008_takes_over_from_the_other_address_rules():
    # T100 is no v5 address (HY047) and T12 is beyond a 30M (HY007); HY008 says why, once
    found = lint("M104 T100 S0\nM109 T12 S200\nM109 T22 S200\n")
    assert sorted({f.code for f in found if f.line <= 3} - {"HY035"}) == ["HY008"]
    # with HY008 off, the other rules report them
    options = Options(dialect="hyrel", ignore=["HY008"])
    codes = {f.code for f in Linter(options).check_text("M104 T100 S0\nM109 T12 S200\nM109 T22 S200\n").findings}
    assert {"HY007", "HY046", "HY047"} <= codes


def test_hy008_offers_no_fix_in_a_file_that_does_not_parse():
    found = lint("M109 T12 S200\nG1 X10 Y20 )\n", codes=("HY008",))
    assert found and all(f.fix is None for f in found)


# -- HY022 / HY048 clone squads ------------------------------------------------------------------------


def test_hy022_v4_groups_are_50_to_57():
    assert lint("M702 T11 S51\n", dialect="hyrel-v4", codes=("HY022",)) == []
    assert [f.code for f in lint("M702 T11 S30\n", dialect="hyrel-v4", codes=("HY022",))] == ["HY022"]
    # v4 M703 gives aliases: "M703 T14 S12" (corpus) is fine there
    assert lint("M703 T14 S12\n", dialect="hyrel-v4", codes=("HY022", "HY048")) == []


def test_hy048_squad_dissolved_by_m30_is_an_error():
    text = "M702 T0 S30\nM703 T1 S30\nT30\nM30\nT30\nT30\n"
    assert where(lint(text, codes=("HY048",))) == [(5, "HY048", "error")]


# -- HY045 focus ---------------------------------------------------------------------------------------


def test_hy045_single_head_jobs_need_no_t():
    assert lint("M6 T0 O1 X0 Y0 Z0\nG1 X10 E1 F600\nM30\n", codes=("HY045",)) == []


def test_hy045_loaded_heads_make_a_job_multi_head():
    text = "G1 X10 E1 F600\nM30\n"
    assert lint(text, codes=("HY045",)) == []
    assert where(lint(text, loaded={0, 1}, codes=("HY045",))) == [(1, "HY045", "error")]


def test_hy045_t_after_the_first_move_is_a_warning():
    text = "M6 T0 O1 X0 Y0 Z0\nM6 T1 O2 X0 Y0 Z0\nG28 X0 Y0\nG0 X10 Y10\nT1\nG1 X20 E1 F600\nM30\n"
    assert where(lint(text, codes=("HY045",))) == [(4, "HY045", "warning")]


# -- HY047 ---------------------------------------------------------------------------------------------


def test_hy047_v4_tool_numbers():
    # v4 T commands are 0-9 and 10-14 (aux, laser, spindle, beds); 4.1+ firmware drops other T lines
    found = lint("T3\nT11\nT15\nT21\n", dialect="hyrel-v4", printer="16a-dual", codes=("HY047",))
    assert where(found) == [(3, "HY047", "error"), (4, "HY047", "error")]


def test_hy047_rrf_deselect():
    assert where(lint("T-1\n", codes=("HY047",))) == [(1, "HY047", "error")]


# -- the command line ----------------------------------------------------------------------------------

JOB = """\
; gclint: dialect=hyrel
M104 T27 S200
M104 T28 S200
; gclint: disable=HY047
M104 T29 S200
M104 T49 S200
; gclint: enable=HY047
M104 T50 S200 ; noqa: HY047
M104 T51 S200
M109 T40 S200
M30
"""


def write(tmp_path, name: str, text: str):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_cli_disable_enable_and_noqa(tmp_path):
    path = write(tmp_path, "job.gcode", JOB)
    proc = run_cli("check", "--format", "json", str(path))
    assert proc.returncode == 1, proc.stderr
    report = json.loads(proc.stdout)
    assert sorted((f["line"], f["code"]) for f in report if f["code"] == "HY047") == [
        (2, "HY047"),
        (3, "HY047"),
        (9, "HY047"),
    ]
    hy003 = [f for f in report if f["code"] == "HY003"]
    assert [(f["line"], f["severity"], f["column"]) for f in hy003] == [(10, "error", 6)]


def test_cli_statistics(tmp_path):
    path = write(tmp_path, "job.gcode", JOB)
    proc = run_cli("check", "--statistics", str(path))
    assert proc.returncode == 1
    out = proc.stdout.decode()
    rows = {
        m.group(2): (int(m.group(1)), m.group(3), m.group(4))
        for m in re.finditer(r"^\s*(\d+)\s+(HY\d{3})\s+(\S+)\s+\[(\w+)\]", out, re.MULTILINE)
    }
    assert rows["HY047"] == (3, "address-out-of-table", "error")
    assert rows["HY003"] == (1, "wait-on-group-address", "error")


def test_cli_config_printer_and_loaded_heads(tmp_path):
    job = "; gclint: dialect=hyrel\nM6 T0 O1 X0 Y0 Z0\nT0\nG1 X10 E1 F600\nT4\nG1 X20 E1\nM30\n"
    path = write(tmp_path, "job.gcode", job)

    def codes(proc):
        return sorted((f["line"], f["code"]) for f in json.loads(proc.stdout) if f["code"] in ("HY006", "HY007"))

    # a fifth slot tells the model (issue 24: T4 is no 30M's): an EHR's, where T4 exists but no head is loaded
    plain = run_cli("check", "--format", "json", str(path), cwd=tmp_path)
    assert codes(plain) == [(5, "HY006")]
    # a 30M has no T4
    small = run_cli("check", "--format", "json", "--printer", "30m", str(path), cwd=tmp_path)
    assert codes(small) == [(5, "HY007")]
    # an EHR has T4; the configuration says only T0 and T1 are loaded
    write(tmp_path, "pyproject.toml", '[tool.gclint]\nprinter = "ehr"\nloaded = ["T0", "T1"]\n')
    configured = run_cli("check", "--format", "json", str(path), cwd=tmp_path)
    # T4 is not loaded, and the loaded T1 is never called ("any mismatch")
    assert codes(configured) == [(1, "HY006"), (5, "HY006")]
    finding = [f for f in json.loads(configured.stdout) if f["code"] == "HY006" and f["line"] == 5][0]
    assert finding["severity"] == "warning" and "T0, T1" in finding["message"]
    # the command line wins over the configuration
    override = run_cli("check", "--format", "json", "--loaded", "T0,T4", str(path), cwd=tmp_path)
    assert codes(override) == []


def test_cli_fix_rewrites_v4_numbers(tmp_path):
    path = write(
        tmp_path, "job.gcode", "; gclint: dialect=hyrel\nM6 T21 O6 X0 Y0\nM104 T21 S200\nM109 T21 S200\nT5\nM30\n"
    )
    original = path.read_text(encoding="utf-8")
    run_cli("check", "--fix", "--printer", "16a-dual", str(path))
    # M6 T21 declares the CO2 laser in v5: a line valid in v5 is not rewritten by a safe fix, and the
    # others are not rewritten without it (M6 T21 would then declare the laser in a v5 file)
    assert path.read_text(encoding="utf-8") == original
    assert "HY008" in run_cli("check", "--printer", "16a-dual", str(path)).stdout.decode()
    path = write(tmp_path, "job2.gcode", "; gclint: dialect=hyrel\nM6 T21 O6 X0 Y0\nM104 T21 S200\nM109 T21 S200\n")
    run_cli("check", "--fix", "--unsafe-fixes", "--printer", "16a-dual", str(path))
    assert path.read_text(encoding="utf-8") == "; gclint: dialect=hyrel\nM6 T5 O6 X0 Y0\nM104 T5 S200\nM109 T5 S200\n"


V4_JOB = (
    "M6 T11 O1 X0 Y0 Z0\nM6 T12 O2 X20 Y0 Z0\nM140 T91 S60\nM109 T11 S215\nM109 T12 S215\nT0\n"
    "G1 X10 Y10 E1 F1200\nT1\nG1 X20 Y10 E1\nM104 T0 S0\nM140 T0 S0\nM107 T0\nM620 T0 E0\nM30\n"
)


def test_cli_fix_converts_every_v4_address_or_none(tmp_path):
    # a v4 job checked as v5: v4 T0 is "all devices" (v5 T40; T_v4 page and HH_BROADCAST_ALL 0 in the v4
    # firmware, confidence: high); the
    # fix converts it with the others, as the translator does, or the switch-offs would reach head T0 only
    path = write(tmp_path, "job.gcode", V4_JOB)
    run_cli("check", "--dialect", "hyrel", "--fix", str(path))
    assert path.read_text(encoding="utf-8") == V4_JOB  # T0 also reads as v5: the conversion is unsafe
    proc = run_cli("check", "--dialect", "hyrel", "--unsafe-fixes", "--fix", str(path))
    fixed = path.read_text(encoding="utf-8")
    assert "M104 T40 S0\nM140 T40 S0\nM107 T40\nM620 T40 E0\n" in fixed, fixed
    assert fixed.startswith("M6 T0 O1 X0 Y0 Z0\nM6 T1 O2 X20 Y0 Z0\nM140 T24 S60\nM109 T0 S215\nM109 T1 S215\n")
    assert "HY008" not in proc.stdout.decode()


def test_cli_fix_is_the_translators_conversion(tmp_path):
    path = write(tmp_path, "job.gcode", V4_JOB)
    copy = write(tmp_path, "copy.gcode", V4_JOB)
    run_cli("check", "--dialect", "hyrel", "--unsafe-fixes", "--fix", str(path))
    out = tmp_path / "out.gcode"
    run_cli("translate", "--from", "hyrel-v4", "--to", "hyrel", "-o", str(out), str(copy))
    assert path.read_text(encoding="utf-8") == out.read_text(encoding="utf-8")


def test_cli_fix_refuses_a_v4_job_with_an_uncertain_address(tmp_path):
    # v4 T16 (the aux port) -> v5 T22 is inferred (confidence: medium, docs/sources.md): nothing is converted,
    # and the other findings say why
    job = V4_JOB.replace("M30\n", "M104 T16 S0\nM30\n")
    path = write(tmp_path, "job.gcode", job)
    proc = run_cli("check", "--dialect", "hyrel", "--unsafe-fixes", "--fix", "--format", "json", str(path))
    assert path.read_text(encoding="utf-8") == job
    found = [f for f in json.loads(proc.stdout) if f["code"] == "HY008"]
    assert found and all(f.get("fix") is None for f in found)
    assert "no certain v5 counterpart" in next(f["message"] for f in found if f["line"] == 1)


def test_cli_fix_recomputes_a_right_checksum(tmp_path):
    # a CRLF v4 job with right checksums: the fix rewrites the T words and recomputes each checksum
    def numbered(lines):
        out = []
        for n, text in enumerate(lines, 1):
            body = f"N{n} {text}"
            out.append(f"{body}*{_xor(body)}")
        return "\r\n".join(out) + "\r\n"

    before = ["M6 T11 O1 X0 Y0 Z0", "M109 T11 S215", "T0", "G1 X10 Y10 E1 F1200", "M104 T100 S0", "M30"]
    after = ["M6 T0 O1 X0 Y0 Z0", "M109 T0 S215", "T0", "G1 X10 Y10 E1 F1200", "M104 T47 S0", "M30"]
    path = tmp_path / "cs.gcode"
    path.write_bytes(numbered(before).encode())
    proc = run_cli("check", "--dialect", "hyrel", "--fix", str(path))
    assert path.read_bytes() == numbered(after).encode(), proc.stderr
    assert b"not applied" not in proc.stderr
    # a checksum that was already wrong stays wrong (SX004 reports it; recomputing would bless the damage)
    text = numbered(before).replace("*24\r\n", "*25\r\n")
    assert "N2 M109 T11 S215*25" in text
    path.write_bytes(text.encode())
    run_cli("check", "--dialect", "hyrel", "--fix", str(path))
    assert b"N2 M109 T0 S215*25\r\n" in path.read_bytes()


def _xor(text: str) -> int:
    value = 0
    for byte in text.encode():
        value ^= byte
    return value


MIXED_V5 = (
    "M6 T0 O1 X0 Y0 Z0\nM109 T0 S215 W0\nM190 T91 S60 W0\nM116\nT0\nG1 X1 Y1 E1 F100\nM104 T100 S0\nM140 T90 S0\nM30\n"
)


def test_cli_unsafe_fix_writes_the_v5_address_of_a_v4_footer(tmp_path):
    # a v5 job (W0, M116) with Hyrel's old footer: T100, T90, T91 name nothing in v5 and map to v5 T47,
    # T46, T24 with high confidence (T_v4 page; v4 firmware hyrel.h, docs/sources.md): an unsafe HY047 fix
    path = write(tmp_path, "job.gcode", MIXED_V5)
    run_cli("check", "--dialect", "hyrel", "--fix", str(path))
    assert path.read_text(encoding="utf-8") == MIXED_V5  # the file mixes numberings: not a safe fix
    proc = run_cli("check", "--dialect", "hyrel", "--unsafe-fixes", "--fix", str(path))
    assert path.read_text(encoding="utf-8") == MIXED_V5.replace("T91", "T24").replace("T100", "T47").replace(
        "T90", "T46"
    )
    assert "HY047" not in proc.stdout.decode()


def test_hy047_fix_only_in_a_file_whose_addresses_say_v5():
    # a v4 file with HY008 ignored: converting one number would leave the others in v4 (HY008's job)
    options = Options(dialect="hyrel", ignore=["HY008"])
    found = Linter(options).check_text("M6 T12 O2\nM109 T12 S200\nM104 T100 S0\n").findings
    found = [f for f in found if f.code == "HY047"]
    assert where(found) == [(3, "HY047", "error")] and found[0].fix is None
    # and only where the device fits the command (v4 T91 is a bed: not for M104)
    found = lint("M109 T0 S200 W0\nM116\nM104 T91 S0\n", codes=("HY047",))
    assert where(found) == [(3, "HY047", "error")] and found[0].fix is None


@pytest.mark.parametrize("dialect", ["hyrel", "hyrel-v4"])
def test_cli_reports_t_values_that_are_no_address(tmp_path, dialect):
    # a fraction or a number beyond every address: the Chart of Addresses has no such device
    job = (
        "M104 T0.5 S200\nM104 T99999999999999999999 S200\nM6 T99999999999999999999 O2\n"
        "T99999999999999999999\nM109 T0 S200\nT0\nG1 X1 Y1 F100\nM30\n"
    )
    path = write(tmp_path, "t.gcode", job)
    proc = run_cli("check", "--dialect", dialect, "--format", "json", str(path))
    found = sorted((f["line"], f["code"]) for f in json.loads(proc.stdout) if f["code"] == "HY047")
    assert found == [(1, "HY047"), (2, "HY047"), (3, "HY047"), (4, "HY047")]
    # a long spelling of a real address is that address
    assert lint("M104 T000000000000001 S200\n", codes=("HY047",)) == []


def test_cli_reports_a_set_temperature_aimed_at_the_wrong_kind_of_device(tmp_path):
    # Gcode page: M140 "T# is the target bed", M141 "the target chamber", M104 "T# (target head)"
    job = (
        "M109 T0 S200 W0\nM116\nM140 T0 S60\nM141 T1 S40\nM104 T24 S200\nM104 T20 S0\n"
        "M140 T24 S60\nM141 T25 S40\nM104 T0 S0\nT0\nG1 X1 Y1 F100\nM30\n"
    )
    path = write(tmp_path, "job.gcode", job)
    proc = run_cli("check", "--dialect", "hyrel", "--format", "json", str(path))
    found = {f["line"]: f["message"] for f in json.loads(proc.stdout) if f["code"] == "HY046"}
    assert sorted(found) == [3, 4, 5, 6]
    assert found[3].startswith("M140 sets a bed, but T0 is head T0") and "use M104" in found[3]
    assert "use M140 (bed) or M141 (chamber)" in found[5]


def test_severities_are_the_documented_ones():
    from gclint.rules.base import all_rules

    rules = all_rules()
    expected = {
        "HY006": Severity.WARNING,
        "HY007": Severity.ERROR,
        "HY008": Severity.WARNING,
        "HY022": Severity.ERROR,
        "HY045": Severity.ERROR,
        "HY047": Severity.ERROR,
        "HY048": Severity.WARNING,
    }
    assert {code: rules[code].severity for code in expected} == expected
