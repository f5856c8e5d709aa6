"""The black-box security review: secrets never leave gclint unmasked (the file's context evidence included,
in every output format and the cache), and human outputs (the --diff too) never print control characters or
invisible format characters raw."""

from __future__ import annotations

import json
import unicodedata
from pathlib import Path

import pytest

from gclint import secrets
from gclint.context import Context, infer
from gclint.dialects.base import HeadScan
from gclint.reports import formats
from gclint.textsafe import human, json_safe

from .conftest import run_cli

SECRET = "hunter22xyz"
SECRET_START = SECRET[:4]  # a message that quotes a secret cut short shows at least this much

# Jobs whose content decides the dialect through the line that holds the secret: the context's evidence
# quotes it (M587 is a Marlin/RepRap code only).
JOBS = {
    "m587": f'G1 X1 Y1 E1 F100\nM587 S"home" P"{SECRET}"\n',
    "m589": f'G1 X1 Y1 E1 F100\nM589 S"ap" P"{SECRET}" I192.168.1.1\n',
    "m551": f'G1 X1 Y1 E1 F100\nM551 P"{SECRET}"\n',
    "m551_unquoted": f"G1 X1 Y1 E1 F100\nM551 P{SECRET}\n",
    "m587_unquoted": f'G1 X1 Y1 E1 F100\nM587 S"x" P{SECRET}\n',
    "m587_single_quotes": f"G1 X1 Y1 E1 F100\nM587 S'x' P'{SECRET}'\n",
    "m587_repeated": f'G1 X1 Y1 E1 F100\nM587 S"x" P"{SECRET}" P"{SECRET}"\n',
    "docker_auth": f'; {{"auths": {{"registry.example": {{"auth": "{SECRET}Zm9vYmFy"}}}}}}\nG1 X1 Y1 E1 F100\n',
    "github_token": f"; ghp_{SECRET}{'a1B2' * 8}\nG1 X1 Y1 E1 F100\n",
    "github_token_after_underscore": f"; deploy_ghp_{SECRET}{'a1B2' * 7}\nG1 X1 Y1 E1 F100\n",
    "header_evidence": f"; password={SECRET} for the Duet 3\nG1 X1 Y1 E1 F100\n",
}


def _shown(text: str) -> bool:
    return SECRET_START.lower() in text.lower()


# -- secrets.find: what the review found undetected -----------------------------------------------------------


@pytest.mark.parametrize(
    "line",
    [
        f'M587 S"home" P"{SECRET}"',
        f'M589 S"ap" P"{SECRET}" I192.168.1.1',
        f'M551 P"{SECRET}"',
        f"M551 P{SECRET} ; set the password",
        f'M587 S"x" P{SECRET}',
        f"M587 S'x' P'{SECRET}'",
        f'M587 S"x" P "{SECRET}"',
        f'M587 S"x" P"{SECRET} and more',  # unterminated: to the end of the line
        f'M587 S"P""net" P"{SECRET}"',  # a P inside the network's name is not the password word
        f'M587 S"Pxyz" P"{SECRET}"',
        f'm0587 s"x" p"{SECRET}"',
        f'M587 S"x" P"decoy{SECRET}" P"{SECRET}"',
        f"(M551 P{SECRET})",
        f'{{"auths": {{"https://index.docker.io/v1/": {{"auth": "{SECRET}Zm9vYmFy"}}}}}}',
        f"; auth = {SECRET}",
        f"ghp_{SECRET}{'a' * 25}",  # 36 characters after ghp_ today; GitHub may change the length
        f"ghp_{SECRET}{'a' * 40}",
        f"; x_ghp_{SECRET}{'a' * 25}",
    ],
)
def test_secret_is_found_and_masked(line: str) -> None:
    masked = secrets.mask(line)
    assert SECRET not in masked and SECRET_START not in masked.lower(), masked
    assert len(masked) == len(line)


@pytest.mark.parametrize(
    "line",
    [
        'M587 S"net" P""',
        "M5870 P12",
        "M551 P{global.machine_password}",
        "; printhost_authorization_type = key",
        "; author = Jane",
        "; auth: none",
        "G1 X10 Y10 F3000",
        "; ghp_short",
    ],
)
def test_not_a_secret(line: str) -> None:
    assert secrets.mask(line) == line


def test_a_message_that_quotes_a_secret_word_alone_is_masked() -> None:
    line = f'M587 S"x" P"{SECRET}" P"{SECRET}"'
    assert SECRET not in secrets.mask_quoted(f'P"{SECRET}" is repeated in M587', line)
    assert secrets.mask_quoted("M587 is not a Marlin code", line) == "M587 is not a Marlin code"


# -- the context's evidence is masked where it is made --------------------------------------------------------


@pytest.mark.parametrize("name", sorted(JOBS))
def test_context_evidence_is_masked(name: str) -> None:
    context = infer(JOBS[name], "job.gcode")
    shown = context.why() + json.dumps(context.to_dict())
    assert not _shown(shown), shown


@pytest.mark.parametrize("name", ["m551_unquoted", "m587_unquoted"])
def test_evidence_shows_no_letter_of_an_unquoted_password(name: str) -> None:
    # "M551 Phunter22xyz" parses as the words P, H, U, N...: each is shown from the masked line
    why = infer(JOBS[name], "job.gcode").why()
    assert "M5" in why and " H " not in why and " U" not in why, why


def test_evidence_is_masked_before_it_is_cut_short() -> None:
    # the command is quoted as evidence at most 40 characters long: a password cut there has no closing quote
    job = f'G1 X1 Y1 E1 F100\nM587 S"a-long-network-name" P"{SECRET}{SECRET}"\n'
    assert not _shown(infer(job, "job.gcode").why())


def test_a_context_read_back_from_an_older_cache_entry_is_masked() -> None:
    data = {"dialect": "marlin", "origin": "content", "reasons": [f'M587 S"x" P"{SECRET}" at line 2: ...']}
    data["conflict"] = f'M551 P"{SECRET}" at line 3'
    context = Context.from_dict(data)
    assert not _shown(context.why()) and not _shown(json.dumps(context.to_dict()))


def test_header_text_quoted_as_evidence_is_masked() -> None:
    scan = HeadScan("; printhost_apikey = 4F1C2B7A9D8E4C3B8A7F6E5D4C3B2A19 Duet 3\n")
    found = scan.found(r"(?i)^[;(].*\b(?:RepRapFirmware|RRF|Duet ?[23W]\w*)\b")
    assert found is not None and "4F1C2B7A" not in found


# -- every output, the cache, explain, -v and --show-settings -------------------------------------------------


@pytest.fixture(scope="module")
def jobs(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("secret-jobs")
    for name, text in JOBS.items():
        (folder / f"{name}.gcode").write_text(text)
    return folder


@pytest.mark.parametrize("fmt", sorted(formats()))
def test_no_output_format_and_no_cache_entry_shows_the_secret(jobs: Path, tmp_path: Path, fmt: str) -> None:
    out = tmp_path / f"report.{fmt}"
    cache = tmp_path / "cache"
    proc = run_cli("check", "--cache-dir", str(cache), "--format", fmt, "--output", str(out), str(jobs))
    assert proc.returncode == 1, proc.stderr
    report = out.read_text(encoding="utf-8", errors="replace")
    assert "M587" in report or fmt == "github", report  # the report is about these files
    assert not _shown(report), f"{fmt}: the report shows the secret"
    assert not _shown(proc.stderr.decode("utf-8", "replace")), proc.stderr
    entries = [p for p in cache.rglob("*.json")]
    assert len(entries) == len(JOBS)
    for entry in entries:
        assert not _shown(entry.read_text(encoding="utf-8")), f"cache entry {entry} shows the secret"
    # and read back from the cache
    again = run_cli("check", "--cache-dir", str(cache), "--format", fmt, "--output", str(out), str(jobs))
    assert not _shown(out.read_text(encoding="utf-8", errors="replace") + again.stderr.decode("utf-8", "replace"))


@pytest.mark.parametrize("name", sorted(JOBS))
def test_explain_verbose_and_settings_do_not_show_the_secret(jobs: Path, name: str) -> None:
    job = str(jobs / f"{name}.gcode")
    shown = ""
    for args in (
        ("explain", job),
        ("explain", "--format", "json", job),
        ("check", "--no-cache", "-v", job),
        ("check", "--no-cache", "--show-settings", job),
    ):
        proc = run_cli(*args)
        shown += proc.stdout.decode("utf-8", "replace") + proc.stderr.decode("utf-8", "replace")
    assert "dialect" in shown
    assert not _shown(shown), shown


def test_diff_masks_secrets(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(
        f'; printhost_apikey = 4F1C2B7A9D8E4C3B8A7F6E5D4C3B2A19\nN1 G1 X1 F100*99\nM587 S"home" P"{SECRET}"\nM30\n'
    )
    proc = run_cli("check", "--no-cache", "--diff", "--unsafe-fixes", str(job))
    diff = proc.stdout.decode()
    assert "+N1 G1 X1 F100*55" in diff, diff
    assert "4F1C2B7A" not in diff and not _shown(diff), diff


# -- control characters and invisible format characters ---------------------------------------------------------


def test_diff_escapes_control_and_format_characters(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_bytes("N1 G1 X1 F100*99 ; \x1b]0;pwn\x07\x1b[2J \u202eevil\u00ad\u200b\nM30\n".encode())
    proc = run_cli("check", "--no-cache", "--diff", "--unsafe-fixes", str(job))
    diff = proc.stdout.decode()
    assert "+N1 G1 X1 F100*" in diff, diff
    for raw in ("\x1b", "\x07", "\u202e", "\u00ad", "\u200b"):
        assert raw not in diff, repr(diff)
    assert "\\x1b]0;pwn\\x07" in diff and "\\u202e" in diff


def test_human_escapes_every_format_character() -> None:
    for code in range(0x110000):
        char = chr(code)
        if unicodedata.category(char) == "Cf":
            assert char not in human(f"a{char}b"), f"U+{code:04X}"
            encoded = json_safe(json.dumps(f"a{char}b", ensure_ascii=False))
            assert char not in encoded and json.loads(encoded) == f"a{char}b", f"U+{code:04X}"


FORMAT_JOB = "; gclint: dialect=hyrel\nM0 ; he\u00adllo\u200bworld\nM792 ; \u200bhi x\nM30\n"


@pytest.mark.parametrize("fmt", sorted(formats()))
def test_format_characters_are_escaped_in_every_output(tmp_path: Path, fmt: str) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(FORMAT_JOB, encoding="utf-8")
    out = tmp_path / f"report.{fmt}"
    proc = run_cli("check", "--no-cache", "--format", fmt, "--output", str(out), str(job))
    assert proc.returncode == 0, proc.stderr
    report = out.read_text(encoding="utf-8")
    assert "HY059" in report
    assert "\u00ad" not in report and "\u200b" not in report, report
    if fmt == "json":  # the data is kept, escaped
        messages = [f["message"] for f in json.loads(report)]
        assert any("\u00ad" in m for m in messages) and any("\u200b" in m for m in messages)
    elif fmt in ("text", "full", "grouped", "github"):
        assert "he\\xadllo" in report and "\\u200bhi" in report, report


def test_explain_escapes_format_characters(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(FORMAT_JOB, encoding="utf-8")
    proc = run_cli("explain", str(job))
    text = proc.stdout.decode()
    assert proc.returncode == 0 and "\u00ad" not in text and "\u200b" not in text, text


HOSTILE_FOLDER = "out\x1b[31m\x07red\u202eevil"


def test_cura_script_escapes_the_folder(tmp_path: Path) -> None:
    folder = tmp_path / HOSTILE_FOLDER
    proc = run_cli("cura-script", "--output", str(folder))
    assert proc.returncode == 0, proc.stderr
    assert (folder / "Gclint.py").is_file()
    shown = proc.stdout.decode()
    assert "\x1b" not in shown and "\x07" not in shown and "\u202e" not in shown, repr(shown)
    assert "\\u202eevil" in shown


def test_clean_escapes_the_cache_folder(tmp_path: Path) -> None:
    proc = run_cli("clean", "--cache-dir", str(tmp_path / HOSTILE_FOLDER))
    assert proc.returncode == 0, proc.stderr
    shown = proc.stdout.decode()
    assert "\x1b" not in shown and "\x07" not in shown and "\u202e" not in shown, repr(shown)
    assert "\\u202eevil" in shown
