"""``gclint server`` end to end: a real process driven over stdio by a small JSON-RPC client
(tests/lsp_client.py), as an editor drives it.  Initialize with no client capabilities, open, change,
hover, code actions, configuration, bad input, shutdown and exit status."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.lsp_client import LspClient
from tests.test_server_units import apply_edits

EMOJI = "\U0001f600"

JOB = (
    "; gclint: dialect=hyrel\n"
    f"({EMOJI} warm up) M109 T40 S200\n"  # HY003 after a non-BMP comment
    "N1 G1 F600 X1*12\n"  # SX004, with an unsafe fix
    "M106 C255\n"
    "M106 T0 S127\n"
    "M6 T12 O2 X0 Y0 Z0\n"  # HY008 (v4 numbering): no fix (lines 2 and 5: T40, T0)
    "M109 T12 S200\n"
    "T1\n"
    "M30\n"
)


@pytest.fixture
def client():
    c = LspClient()
    yield c
    c.kill()


def _by_code(diagnostics: list[dict]) -> dict[str, dict]:
    return {d["code"]: d for d in diagnostics}


def _hover(client: LspClient, uri: str, line: int, character: int) -> dict | None:
    return client.request(
        "textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}
    )


def _code_actions(client: LspClient, uri: str, line: int, diagnostics: list[dict] | None = None) -> list[dict]:
    return (
        client.request(
            "textDocument/codeAction",
            {
                "textDocument": {"uri": uri},
                "range": {"start": {"line": line, "character": 0}, "end": {"line": line, "character": 0}},
                "context": {"diagnostics": diagnostics or []},
            },
        )
        or []
    )


def _apply(text: str, edit: dict, uri: str) -> str:
    return apply_edits(text, edit["changes"][uri])


def test_session_without_client_capabilities(client, tmp_path):
    result = client.initialize(capabilities={})
    caps = result["capabilities"]
    assert caps["positionEncoding"] == "utf-16"
    assert caps["textDocumentSync"]["change"] == 2  # incremental
    assert caps["hoverProvider"] and "quickfix" in caps["codeActionProvider"]["codeActionKinds"]
    assert result["serverInfo"]["name"] == "gclint"

    job = tmp_path / "job.gcode"
    uri = job.as_uri()
    client.open(uri, JOB, version=1)
    diagnostics = client.diagnostics(uri, version=1)
    found = _by_code(diagnostics)
    assert {"HY003", "SX004"} <= set(found), diagnostics
    hy003 = found["HY003"]
    # "T40" after "(😀 warm up) M109 ": 17 characters, 18 UTF-16 units (the emoji counts twice)
    assert hy003["range"] == {"start": {"line": 1, "character": 18}, "end": {"line": 1, "character": 21}}
    assert hy003["severity"] == 1 and hy003["source"] == "gclint"
    assert hy003["codeDescription"]["href"].endswith("docs/rules.md#hy003")

    # hover: the explain text, plain (the client declared no markdown), with the state of the lines above
    hover = _hover(client, uri, 4, 9)
    assert hover["contents"]["kind"] == "plaintext"
    assert hover["contents"]["value"].startswith("* M106 (fan / UV LED duty)")
    assert "49.8" in hover["contents"]["value"]  # S127 of the C255 range set on line 4
    assert hover["range"] == {"start": {"line": 4, "character": 8}, "end": {"line": 4, "character": 12}}
    assert _hover(client, uri, 0, 3) is None

    # code actions on the checksum line: the fix, noqa, fix all; applying the fix removes the finding
    actions = _code_actions(client, uri, 2, [found["SX004"]])
    titles = [a["title"] for a in actions]
    fix = next(a for a in actions if a["title"].startswith("SX004: "))
    assert fix["title"].endswith("(unsafe fix)") and not fix.get("isPreferred")
    assert "SX004: suppress on this line (; noqa: SX004)" in titles
    # no "fix all": HY008 converts the job's v4 addresses together or not at all, and line 2's T40 (v4:
    # yoke 4) has no certain v5 counterpart; line 5's T0 (v4: all devices) would become head T0 if the
    # others were converted without it
    assert not any(a["kind"] == "source.fixAll.gclint" for a in actions)
    fixed = _apply(JOB, fix["edit"], uri)
    assert fixed.splitlines()[2] == "N1 G1 F600 X1*48"

    # noqa on the HY003 line, sent back as an incremental change: the finding goes
    noqa = next(a for a in _code_actions(client, uri, 1) if "noqa: HY003" in a["title"])
    [edit] = noqa["edit"]["changes"][uri]
    client.notify(
        "textDocument/didChange",
        {
            "textDocument": {"uri": uri, "version": 2},
            "contentChanges": [{"range": edit["range"], "text": edit["newText"]}],
        },
    )
    after = client.diagnostics(uri, version=2)
    assert "HY003" not in _by_code(after) and "SX004" in _by_code(after)
    # the fix of the new text, then a whole-document change
    client.notify(
        "textDocument/didChange", {"textDocument": {"uri": uri, "version": 3}, "contentChanges": [{"text": fixed}]}
    )
    assert "SX004" not in _by_code(client.diagnostics(uri, version=3))

    client.notify("textDocument/didSave", {"textDocument": {"uri": uri}})
    client.notify("textDocument/didClose", {"textDocument": {"uri": uri}})
    assert client.wait_notification(
        "textDocument/publishDiagnostics", lambda p: p["uri"] == uri and not p["diagnostics"]
    )
    assert client.shutdown_and_exit() == 0
    assert "Traceback" not in client.stderr


def test_exit_without_shutdown_is_status_1(client):
    client.initialize()
    client.notify("exit")
    assert client.proc.wait(30) == 1


def test_configuration_file_and_client_settings(client, tmp_path):
    (tmp_path / "gclint.toml").write_text('dialect = "hyrel"\nignore = ["HY010"]\n')
    job = tmp_path / "jobs" / "part.gcode"
    job.parent.mkdir()
    uri = job.as_uri()
    text = "M109 T40 S200\nG1 X1 F100\n"  # HY003 (hyrel from the file), HY010 ignored by it
    client.initialize(options={"gclint": {"select": ["HY003", "HY010"]}})
    client.open(uri, text)
    assert set(_by_code(client.diagnostics(uri))) == {"HY003"}
    # settings from the client override the file, as the command line does
    seen = len(client.notifications)
    client.notify("workspace/didChangeConfiguration", {"settings": {"gclint": {"dialect": "marlin", "bogus": 1}}})
    assert "HY003" not in _by_code(client.diagnostics(uri, since=seen))
    assert any("unknown key 'bogus'" in m for m in client.logs())
    # a `; gclint: dialect=` directive in the file does not override them (a job does not choose how it is read)
    client.notify(
        "textDocument/didChange",
        {"textDocument": {"uri": uri, "version": 2}, "contentChanges": [{"text": "; gclint: dialect=hyrel\n" + text}]},
    )
    assert "HY003" not in _by_code(client.diagnostics(uri, version=2))
    assert client.shutdown_and_exit() == 0


def test_security_rules_switched_off_by_the_settings_are_said_and_not_by_a_found_file(client, tmp_path):
    """Issue 25: settings that ignore SC dropped SC diagnostics without a word; a .gclint.toml beside the
    job cannot drop them at all."""
    (tmp_path / ".gclint.toml").write_text('ignore = ["SC"]\n')
    uri = (tmp_path / "job.gcode").as_uri()
    client.initialize()
    client.open(uri, "M792 ; SHELL C:\\x.exe\n")
    assert "SC001" in _by_code(client.diagnostics(uri))
    seen = len(client.notifications)
    client.notify("workspace/didChangeConfiguration", {"settings": {"gclint": {"ignore": ["SC"]}}})
    said = client.wait_notification("window/showMessage", lambda p: "SC001" in p["message"], since=seen)
    assert "not shown" in said["message"] and said["type"] == 2  # a warning
    assert "SC001" not in _by_code(client.diagnostics(uri, since=seen))
    assert client.shutdown_and_exit() == 0


@pytest.mark.parametrize("bad", [["NOPE"], ["HY999"]])
def test_an_unknown_rule_code_in_select_is_logged_and_the_setting_left_out(client, tmp_path, bad):
    client.initialize(options={"gclint": {"select": bad}})
    uri = (tmp_path / "a.gcode").as_uri()
    client.open(uri, "M109 T40 S215\n")
    assert "HY003" in _by_code(client.diagnostics(uri))  # the default selection, not no rule at all
    [said] = [m for m in client.logs() if repr(bad[0]) in m]
    assert "unknown rule code" in said and "'select' setting is ignored" in said
    if bad == ["HY999"]:
        assert "did you mean" in said
    # the same through workspace/didChangeConfiguration, for ignore
    seen = len(client.notifications)
    client.notify("workspace/didChangeConfiguration", {"settings": {"gclint": {"ignore": ["HY0O3"]}}})
    client.wait_notification("window/logMessage", lambda p: "'HY0O3'" in p["message"], since=seen)
    seen = len(client.notifications)
    client.notify("workspace/didChangeConfiguration", {"settings": {"gclint": {"ignore": ["HY003"]}}})
    assert "HY003" not in _by_code(client.diagnostics(uri, since=seen))
    assert client.shutdown_and_exit() == 0


def test_markdown_hover_and_configuration_pulled_from_the_client(client, tmp_path):
    client.answers["workspace/configuration"] = lambda request: [{"dialect": "marlin"}]
    caps = {
        "general": {"positionEncodings": ["utf-8", "utf-16"]},
        "textDocument": {"hover": {"contentFormat": ["markdown", "plaintext"]}},
        "workspace": {"configuration": True, "workspaceEdit": {"documentChanges": True}},
    }
    assert client.initialize(capabilities=caps)["capabilities"]["positionEncoding"] == "utf-8"
    uri = (tmp_path / "a.gcode").as_uri()
    request = client.wait_request("workspace/configuration")  # asked after "initialized"
    assert request["params"]["items"] == [{"section": "gclint"}]
    client.open(uri, "M109 R180\n")
    client.diagnostics(uri)
    hover = _hover(client, uri, 0, 6)
    assert hover["contents"]["kind"] == "markdown"
    value = hover["contents"]["value"]
    assert value.startswith("**M109**") and "dialect: marlin" in value and "`R180` **" in value
    other = (tmp_path / "b.gcode").as_uri()
    # positions in UTF-8 bytes: the repeated "S210" after "(😀) M109 S200 " is at byte 17 (character 14)
    client.open(other, f"({EMOJI}) M109 S200 S210\n")
    sx002 = _by_code(client.diagnostics(other))["SX002"]
    assert sx002["range"]["start"] == {"line": 0, "character": 17}
    actions = client.request(
        "textDocument/codeAction",
        {"textDocument": {"uri": other}, "range": sx002["range"], "context": {"diagnostics": [sx002]}},
    )
    noqa = next(a for a in actions if "noqa" in a["title"])
    assert noqa["edit"]["documentChanges"][0]["textDocument"] == {"uri": other, "version": 1}
    assert client.shutdown_and_exit() == 0


def test_rapid_edits_publish_the_last_text(client, tmp_path):
    client.initialize()
    uri = (tmp_path / "typing.gcode").as_uri()
    text = "; gclint: dialect=hyrel\nM30\n"
    client.open(uri, text)
    client.diagnostics(uri, version=1)
    line = ""
    for version, char in enumerate("M109 T40 S200", start=2):  # typed one character at a time
        position = {"line": 1, "character": len(line)}
        client.notify(
            "textDocument/didChange",
            {
                "textDocument": {"uri": uri, "version": version},
                "contentChanges": [{"range": {"start": position, "end": position}, "text": char}],
            },
        )
        line += char
    last = version
    assert "HY003" in _by_code(client.diagnostics(uri, version=last))
    published = [
        n["params"]["version"]
        for n in client.notifications
        if n.get("method") == "textDocument/publishDiagnostics" and n["params"]["uri"] == uri
    ]
    assert published[-1] == last and len(published) < last  # debounced: not one check per keystroke
    assert client.shutdown_and_exit() == 0


def test_bad_input_never_kills_the_server(client, tmp_path):
    client.initialize()
    base = tmp_path.as_uri()
    # binary text: no diagnostics, a line in the client's log
    client.open(f"{base}/bin.gcode", "G1 X1\n\x00\x00\x01\x02" * 100)
    assert client.diagnostics(f"{base}/bin.gcode") == []
    assert any("binary" in m for m in client.logs())
    # a message body that is not valid UTF-8 (read with U+FFFD in place of the bad bytes)
    client.send_raw(
        b'{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{"textDocument":{"uri":"'
        + f"{base}/latin1.gcode".encode()
        + b'","languageId":"gcode","version":1,"text":"; gclint: dialect=hyrel\\nM109 T40 S200 ; caf\xe9\\n"}}}'
    )
    assert "HY003" in _by_code(client.diagnostics(f"{base}/latin1.gcode"))
    # lone surrogates from JSON escapes
    client.send_raw(
        b'{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{"textDocument":{"uri":"'
        + f"{base}/surrogates.gcode".encode()
        + b'","languageId":"gcode","version":1,"text":"; \\udc80 \\ud83d\\nM109 T40 S200 ; gclint: dialect=hyrel\\n"}}}'
    )
    assert "HY003" in _by_code(client.diagnostics(f"{base}/surrogates.gcode"))
    # not JSON at all, then a request for a document nobody opened
    client.send_raw(b"{ this is not json")
    client.send_raw(b"\x00\xff\x00")
    assert (
        client.request(
            "textDocument/hover",
            {"textDocument": {"uri": f"{base}/nope.gcode"}, "position": {"line": 0, "character": 0}},
        )
        is None
    )
    # a very long line (20 MB) and a change after it
    long_uri = f"{base}/long.gcode"
    client.open(long_uri, "G1 X1 ; gclint: dialect=hyrel " + "a" * 20_000_000 + "\nM109 T40 S200\n")
    assert "HY003" in _by_code(client.diagnostics(long_uri, timeout=120))
    assert _hover(client, long_uri, 0, 2) is None
    hover = _hover(client, long_uri, 1, 0)
    assert hover["contents"]["value"].startswith("* M109")
    # a hover and a code action on positions far outside the text
    assert _hover(client, long_uri, 99, 99) is None
    _code_actions(client, long_uri, 500)
    # still serving
    ok = f"{base}/ok.gcode"
    client.open(ok, "; gclint: dialect=hyrel\nM109 T40 S200\n")
    assert "HY003" in _by_code(client.diagnostics(ok))
    assert any("server error" in m for m in client.logs())
    assert client.shutdown_and_exit(timeout=60) == 0
    assert "Traceback" not in client.stderr


def test_a_request_whose_params_do_not_fit_is_answered_invalid_params(client, tmp_path):
    # (pygls, which the server used before, never answered it: the client waited forever)
    client.initialize()
    uri = (tmp_path / "a.gcode").as_uri()
    client.open(uri, "M109 T40 S215\n")
    client.diagnostics(uri)
    bad = [
        ("textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": -1, "character": -5}}),
        ("textDocument/codeAction", {"textDocument": {"uri": uri}}),  # no range, no context
        ("textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": "x", "character": 0}}),
    ]
    for method, params in bad:
        response = client.wait_response(client.request_async(method, params), timeout=10)
        assert response["error"]["code"] == -32602, response  # InvalidParams
        assert method in response["error"]["message"] and "params" in response["error"]["message"]
    assert "$.params.position" in " ".join(client.logs())
    # a notification that does not fit: a line in the log, no answer, and the server goes on
    seen = len(client.notifications)
    client.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2}})
    client.wait_notification("window/logMessage", lambda p: "textDocument/didChange" in p["message"], since=seen)
    assert _hover(client, uri, 0, 1)["contents"]["value"].startswith("* M109")
    assert client.shutdown_and_exit() == 0
    assert "Traceback" not in client.stderr and "cattrs" not in client.stderr
    assert len(client.stderr.strip().splitlines()) <= len(bad) + 1, client.stderr


def test_the_server_needs_no_package_beyond_gclints_own(tmp_path):
    """The server is the standard library and gclint: it starts and answers where pygls, lsprotocol and
    cattrs cannot be imported, and imports none of them where they can (importing lsprotocol's types
    alone took longer than checking a 20,000-line job)."""
    script = (
        "import sys\n"
        "for name in ('pygls', 'lsprotocol', 'cattrs', 'attrs'):\n"
        "    sys.modules[name] = None\n"
        "from gclint.cli import main\n"
        "main(['server'])\n"
    )
    client = LspClient(args=[sys.executable, "-c", script], cwd=str(Path(__file__).parent.parent))
    try:
        assert client.initialize()["serverInfo"]["name"] == "gclint"
        uri = (tmp_path / "a.gcode").as_uri()
        client.open(uri, "; gclint: dialect=hyrel\nM109 T40 S215\n")
        assert "HY003" in _by_code(client.diagnostics(uri))
        assert client.shutdown_and_exit() == 0
    finally:
        client.kill()
    imported = subprocess.run(
        [sys.executable, "-c", "import sys, gclint.server.protocol; print(sorted(sys.modules))"],
        capture_output=True,
        text=True,
        timeout=60,
        cwd=str(Path(__file__).parent.parent),
    ).stdout
    assert "'lsprotocol" not in imported and "'pygls" not in imported and "'cattrs" not in imported


def test_requests_before_initialize_and_after_shutdown_are_refused(client, tmp_path):
    uri = (tmp_path / "a.gcode").as_uri()
    early = client.wait_response(
        client.request_async(
            "textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": 0, "character": 0}}
        )
    )
    assert early["error"]["code"] == -32002  # ServerNotInitialized
    client.initialize()
    unknown = client.wait_response(client.request_async("gclint/nonsense", {}))
    assert unknown["error"]["code"] == -32601  # MethodNotFound
    client.request("shutdown")
    late = client.wait_response(client.request_async("textDocument/hover", {}))
    assert late["error"]["code"] == -32600  # InvalidRequest
    client.notify("exit")
    assert client.proc.wait(30) == 0
