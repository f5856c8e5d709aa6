"""The script ``gclint cura-script`` writes for Cura's post-processing plugin.

It is imported the way Cura imports it (``PostProcessingPlugin/scripts/Gclint.py`` doing
``from ..Script import Script``), against a small stand-in for Cura's ``Script`` class and ``UM``'s
``Message``/``Logger``, and run on a real corpus job split the way Cura hands it over: the header
first, then one chunk per ``;LAYER:n``.
"""

from __future__ import annotations

import importlib
import json
import subprocess
import sys

import pytest

from tests.conftest import CORPUS, needs_corpus, run_cli

JOB = CORPUS / "marlin" / "cura-4.10.0_kreistest.gcode"

SCRIPT_STAND_IN = '''
import json


class Script:
    """The parts of Cura's PostProcessingPlugin/Script.py a script relies on."""

    def __init__(self):
        data = json.loads(self.getSettingDataString())
        for key in ("name", "key", "metadata", "version", "settings"):
            assert key in data, key
        self._values = {key: setting["default_value"] for key, setting in data["settings"].items()}

    def getSettingValueByKey(self, key):
        return self._values[key]
'''

UM_MESSAGE = """
SHOWN = []


class Message:
    def __init__(self, text="", title="", **kwargs):
        self.text, self.title = text, title

    def show(self):
        SHOWN.append(self)
"""

UM_LOGGER = """
LOGGED = []


class Logger:
    @staticmethod
    def log(level, message, *args):
        LOGGED.append((level, message % args if args else message))
"""


@pytest.fixture
def cura(tmp_path, monkeypatch):
    """Import the generated script inside a stand-in PostProcessingPlugin package; returns a factory."""
    plugin = tmp_path / "plugins" / "PostProcessingPlugin"
    (plugin / "scripts").mkdir(parents=True)
    (plugin / "__init__.py").write_text("")
    (plugin / "Script.py").write_text(SCRIPT_STAND_IN)
    (plugin / "scripts" / "__init__.py").write_text("")
    um = tmp_path / "plugins" / "UM"
    um.mkdir()
    (um / "__init__.py").write_text("")
    (um / "Message.py").write_text(UM_MESSAGE)
    (um / "Logger.py").write_text(UM_LOGGER)
    proc = run_cli("cura-script", "--output", str(plugin / "scripts"))
    assert proc.returncode == 0, proc.stderr
    assert b"cannot stop an export" in proc.stdout
    monkeypatch.syspath_prepend(str(tmp_path / "plugins"))
    for name in [m for m in sys.modules if m.split(".")[0] in ("PostProcessingPlugin", "UM")]:
        monkeypatch.delitem(sys.modules, name)
    module = importlib.import_module("PostProcessingPlugin.scripts.Gclint")
    message = importlib.import_module("UM.Message")

    def make(**settings):
        script = module.Gclint()
        script._values.update(settings)
        return script

    make.shown = message.SHOWN  # type: ignore[attr-defined]
    make.module = module  # type: ignore[attr-defined]
    return make


def cura_chunks(text: str) -> list[str]:
    """Header first, then one chunk per ';LAYER:n' (what Cura passes to execute)."""
    chunks = [""]
    for line in text.splitlines(keepends=True):
        if line.startswith(";LAYER:"):
            chunks.append("")
        chunks[-1] += line
    return chunks


def test_settings_are_what_cura_reads(cura):
    data = json.loads(cura().getSettingDataString())
    assert data["key"] == "Gclint" and data["version"] == 2
    for key, setting in data["settings"].items():
        assert {"label", "description", "type", "default_value"} <= set(setting), key
        assert setting["type"] in ("bool", "int", "float", "str", "enum"), key
        if setting["type"] == "enum":
            assert setting["default_value"] in setting["options"]


@needs_corpus
def test_checks_a_real_cura_job_and_shows_the_findings(cura):
    text = JOB.read_text(encoding="utf-8", errors="surrogateescape")
    data = cura_chunks(text)
    assert len(data) > 3 and data[1].startswith(";LAYER:0")
    original = list(data)
    result = cura().execute(list(data))

    expected = json.loads(
        run_cli(
            "check",
            "-",
            "--no-cache",
            "--format",
            "json",
            "--stdin-filename",
            "cura-output.gcode",
            input=JOB.read_bytes(),
        ).stdout
    )
    assert len(result) == len(original) and result[1:] == original[1:]  # layers untouched
    header = result[0]
    assert header.endswith(original[0])
    summary = header.splitlines()[0]
    assert summary.startswith(";gclint: ")
    counts = {s: sum(1 for f in expected if f["severity"] == s) for s in ("error", "warning", "info")}
    if expected:
        assert summary == f";gclint: {counts['error']} error(s), {counts['warning']} warning(s), {counts['info']} info"
    else:
        assert summary == ";gclint: no findings"
    assert cura.shown and cura.shown[-1].title.startswith("gclint: ")


def test_findings_are_annotated_and_shown(cura):
    data = [
        ";FLAVOR:Marlin\n;Generated with Cura_SteamEngine 4.10.0\nM9999\nG28\n",
        ";LAYER:0\nG1 X1 X2 Y1 E1\n",
        ";LAYER:1\nG1 X5 Y5 E2\n",
    ]
    result = cura().execute(list(data))
    assert result[0].startswith(";gclint: 1 error(s), 1 warning(s), 0 info\n"), result[0]
    saved = "".join(result).splitlines()
    assert ";gclint: line 9: SX002" in result[0]  # line 6 of the job, after the 3 comment lines
    assert saved[8] == "G1 X1 X2 Y1 E1" and saved[5] == "M9999" and ";gclint: line 6: DL001" in result[0]
    assert result[1:] == data[1:]
    shown = cura.shown[-1]
    assert "SX002" in shown.text and "DL001" in shown.text


def test_translation_keeps_cura_chunks(cura):
    data = [
        ";FLAVOR:Marlin\n;Generated with Cura_SteamEngine 4.10.0\nM104 S200\nM109 S200\nG28\n",
        ";LAYER:0\nG1 Z0.2 F600\nG1 X10 Y10 E1 F1200\n",
        ";LAYER:1\nG1 X20 Y10 E2\nM107\n",
        "M84\n",
    ]
    result = cura(translate_to="hyrel").execute(list(data))
    assert len(result) == len(data)
    assert result[1].startswith(";LAYER:0") and result[2].startswith(";LAYER:1")
    shown = " ".join(m.text for m in cura.shown)
    if "could not translate" in shown:  # the translation engine lacks the pair: nothing changed, the user is told
        assert result[1:] == data[1:]
    else:
        joined = "".join(result)
        assert "M109 T" in joined and "gclint-cura-chunk" not in joined
        # issue 28: the M30 the translation writes after the last chunk was dropped, then reported missing
        assert joined.rstrip().endswith("M30") and result[-1].startswith("M84")
        assert "HY010" not in shown and "no M30" not in shown


def test_a_missing_gclint_is_reported_not_raised(cura):
    data = [";FLAVOR:Marlin\nG28\n", ";LAYER:0\nG1 X1 Y1\n"]
    result = cura(command="/nonexistent/gclint-binary").execute(list(data))
    assert result == data
    assert "could not run" in cura.shown[-1].text


def test_script_text_is_written_with_this_gclint(tmp_path):
    proc = run_cli("cura-script", "--print")
    text = proc.stdout.decode()
    assert "class Gclint(Script):" in text and repr(sys.executable) in text
    compile(text, "Gclint.py", "exec")
    assert (
        subprocess.run(
            [sys.executable, "-m", "gclint", "cura-script", "-o", str(tmp_path)], capture_output=True
        ).returncode
        == 0
    )
    assert (tmp_path / "Gclint.py").read_text() == text
