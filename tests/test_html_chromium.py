"""The HTML page in a real headless Chromium: it renders with no console error under its Content-Security-Policy,
its one script runs, file text that looks like markup stays text, and the toolpath viewer draws the part at a
readable size, follows its layer slider, and links markers and findings both ways.

Chromium is driven through its DevTools protocol over a pipe (``--remote-debugging-pipe``: file descriptors 3
and 4, JSON messages ended by a NUL byte), with the standard library only.  Screenshots go to the test's
temporary folder, or to ``GCLINT_SHOTS`` when set (``GCLINT_SHOTS=/tmp/shots pytest tests/test_html_chromium.py``).

Needs Debian's ``chromium`` (``apt-get install chromium``).  Outside CI the test is skipped when no Chromium is
installed; in CI (``CI`` set) it fails instead, because .ci/run installs it.
"""

from __future__ import annotations

import base64
import fcntl
import json
import os
import re
import shutil
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import CORPUS, corpus_available, run_cli

BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
CUBE = CORPUS / "marlin" / "prusaslicer-2.8.1_mini_cube.gcode"  # start G-code primes at Z15, purges at the edge


def chromium() -> str:
    for name in BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    if os.environ.get("CI"):
        pytest.fail("Chromium is not installed, but CI must run this test (.ci/run installs Debian's chromium)")
    pytest.skip("Chromium is not installed (apt-get install chromium); CI installs it and runs this test")


class Browser:
    """One headless Chromium with one page, driven by the DevTools protocol over a pipe."""

    def __init__(self, profile: Path, width: int = 1200, height: int = 1000) -> None:
        to_child, self._to_browser = os.pipe()
        self._from_browser, from_child = os.pipe()

        def descriptors() -> None:  # (in the child) the pipe's ends as fds 3 and 4, left open across exec
            for fd, wanted in ((to_child, 3), (from_child, 4)):
                os.dup2(fcntl.fcntl(fd, fcntl.F_DUPFD, 10), wanted)

        args = [
            chromium(),
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--remote-debugging-pipe",
            f"--user-data-dir={profile}",
            "about:blank",
        ]
        self.proc = subprocess.Popen(
            args,
            preexec_fn=descriptors,
            close_fds=False,  # (the parent's ends are not inheritable: only 3 and 4 reach the browser)
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        os.close(to_child)
        os.close(from_child)
        self._buffer = b""
        self._id = 0
        self.events: list[dict] = []
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        self.session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        for domain in ("Page", "Runtime", "Log"):
            self.call(f"{domain}.enable")
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=False)

    def call(self, method: str, timeout: float = 60, **params) -> dict:
        self._id += 1
        message = {"id": self._id, "method": method, "params": params}
        if hasattr(self, "session") and not method.startswith("Target."):
            message["sessionId"] = self.session
        os.write(self._to_browser, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            while b"\0" in self._buffer:
                raw, self._buffer = self._buffer.split(b"\0", 1)
                reply = json.loads(raw)
                if reply.get("id") == self._id:
                    assert "error" not in reply, (method, reply["error"])
                    return reply.get("result", {})
                if "method" in reply:
                    self.events.append(reply)
            assert time.monotonic() < deadline, f"no answer to {method}"
            chunk = os.read(self._from_browser, 1 << 20)
            assert chunk, "Chromium closed the pipe"
            self._buffer += chunk

    def open(self, page: Path) -> None:
        self.call("Page.navigate", url=page.as_uri())
        self.wait("document.body && document.body.dataset.ready === '1'")

    def js(self, expression: str):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        assert "exceptionDetails" not in result, result["exceptionDetails"]
        return result["result"].get("value")

    def wait(self, condition: str, timeout: float = 20) -> None:
        deadline = time.monotonic() + timeout
        while not self.js(f"!!({condition})"):
            assert time.monotonic() < deadline, f"never true: {condition}"
            time.sleep(0.05)

    def console(self) -> list[str]:
        """Console messages and browser log entries (a CSP violation is one) so far."""
        out = []
        for event in self.events:
            if event["method"] == "Runtime.consoleAPICalled":
                out.append(
                    event["params"]["type"] + ": " + " ".join(str(a.get("value")) for a in event["params"]["args"])
                )
            elif event["method"] == "Runtime.exceptionThrown":
                out.append("exception: " + json.dumps(event["params"]["exceptionDetails"])[:500])
            elif event["method"] == "Log.entryAdded":
                out.append(event["params"]["entry"]["level"] + ": " + event["params"]["entry"]["text"])
        return out

    def screenshot(self, path: Path, selector: str) -> None:
        box = self.js(
            f"(function () {{ var r = document.querySelector({json.dumps(selector)}).getBoundingClientRect();"
            " return [r.left + scrollX, r.top + scrollY, r.width, r.height]; })()"
        )
        clip = {"x": box[0], "y": box[1], "width": box[2], "height": box[3], "scale": 1}
        shot = self.call("Page.captureScreenshot", format="png", clip=clip, captureBeyondViewport=True)
        path.write_bytes(base64.b64decode(shot["data"]))

    def click(self, x: float, y: float) -> None:
        for kind in ("mousePressed", "mouseReleased"):
            self.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left", clickCount=1)

    def key(self, key: str, code: str, key_code: int) -> None:
        for kind in ("rawKeyDown", "keyUp"):
            self.call("Input.dispatchKeyEvent", type=kind, key=key, code=code, windowsVirtualKeyCode=key_code)

    def close(self) -> None:
        try:
            os.close(self._to_browser)
            os.close(self._from_browser)
        finally:
            self.proc.kill()
            self.proc.wait(timeout=30)


@pytest.fixture
def browser(tmp_path: Path):
    b = Browser(tmp_path / "profile")
    try:
        yield b
    finally:
        b.close()


def shots(tmp_path: Path) -> Path:
    folder = Path(os.environ.get("GCLINT_SHOTS") or tmp_path)
    folder.mkdir(parents=True, exist_ok=True)
    return folder


# What the canvas shows: the box of its drawn pixels (anything not white) and of the pixels in a head's own colour
# at full strength (the shown layer's working moves; the layers below are faded), and a digest of its pixels.
CANVAS = """(function () {
  var fig = document.querySelector("figure.toolpath"), c = fig.querySelector("canvas");
  var d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data, W = c.width, H = c.height;
  var color = %s, drawn = [W, H, -1, -1], strong = [W, H, -1, -1], sum = 0, count = 0;
  for (var y = 0; y < H; y++) for (var x = 0; x < W; x++) {
    var i = 4 * (y * W + x), r = d[i], g = d[i + 1], b = d[i + 2];
    sum = (sum * 31 + r * 7 + g * 3 + b) %% 1000000007;
    if (r > 245 && g > 245 && b > 245) continue;
    drawn = [Math.min(drawn[0], x), Math.min(drawn[1], y), Math.max(drawn[2], x), Math.max(drawn[3], y)];
    if (Math.abs(r - color[0]) + Math.abs(g - color[1]) + Math.abs(b - color[2]) < 40) {
      count++;
      strong = [Math.min(strong[0], x), Math.min(strong[1], y), Math.max(strong[2], x), Math.max(strong[3], y)];
    }
  }
  return {width: W, height: H, drawn: drawn, strong: strong, count: count, digest: sum,
          label: fig.querySelector(".tp-label").textContent, layer: fig.querySelector("input.tp-layer").value};
})()"""


def canvas(b: Browser, color: tuple[int, int, int] = (0x1F, 0x77, 0xB4)) -> dict:
    b.js("new Promise(function (done) { requestAnimationFrame(function () { requestAnimationFrame(done); }); })")
    return b.js(CANVAS % json.dumps(list(color)))


def share(box: list[int], length: int, axis: int) -> float:
    return (box[2 + axis] - box[axis] + 1) / length


JOB = (
    "; gclint: dialect=hyrel\n"
    "; <script>document.title='pwned'</script> </svg><b>bold</b>\n"
    "; printhost_apikey = 0123456789abcdef\n"
    "M6 T0 O1 X0 Y0 Z0\nM6 T1 O2 X0 Y0 Z0\n"
    "T0\nG28 X0 Y0\nG1 X10 Y10 Z0.3 E1 F1200\nG1 X40 Y10 E1\nG1 X40 Y40 E1\nG1 X10 X12 Y40 E1\n"  # SX002 on line 11
    "T1\nG0 X60 Y10\nG1 X90 Y10 E1\nG1 X90 Y40 E1 ; <img src=x onerror=alert(1)>\nM9999\nG1 X60 Y40 E1\n"
    "G1 Z0.6\nG1 X90 Y10 E1\n"
)


def test_html_report_renders_in_chromium(tmp_path: Path, browser: Browser):
    job = tmp_path / "two heads.gcode"
    job.write_text(JOB)
    page = tmp_path / "report.html"
    proc = run_cli("check", "--no-cache", str(job), "--format", "html", "--output", str(page))
    assert proc.returncode == 1, proc.stderr
    browser.open(page)
    browser.wait("document.querySelector('figure.toolpath').dataset.drawn")
    messages = browser.console()
    assert any("gclint report ready: 1 toolpath(s)" in m for m in messages), messages
    assert not [m for m in messages if re.search(r"Uncaught|Error|Refused|violat|exception", m)], messages

    dom = browser.js("document.documentElement.outerHTML")
    assert browser.js("document.title").startswith("gclint report")  # the comment's script never ran
    assert "<img src=" not in dom and "<b>bold</b>" not in dom and "0123456789abcdef" not in dom
    assert browser.js("document.scripts.length") == 1  # only the report's own script, with its nonce
    heads = browser.js("Array.from(document.querySelectorAll('button.tp-head')).map(b => b.textContent)")
    assert [h.split(":")[0] for h in heads] == ["head T0 (yoke 1, position 1)", "head T1 (yoke 1, position 2)"]
    data = browser.js("JSON.parse(document.querySelector('figure.toolpath').dataset.toolpath)")
    assert len(data["layers"]) == 2 and {m[3] for m in data["markers"]} >= {11, 16}

    # a finding leads to its marker (the layer it is in, selected), and a marker to its finding
    browser.js("document.querySelector('tr[data-line=\"11\"] button.goto').click()")
    browser.wait("document.querySelector('.tp-label').textContent.startsWith('layer 1 of 2')")
    assert browser.js("document.querySelector('tr[data-line=\"11\"]').classList.contains('sel')")
    browser.js("document.querySelectorAll('tr.sel').forEach(r => r.classList.remove('sel'))")
    at = browser.js(
        "(function () { var c = document.querySelector('canvas.tp-canvas'); c.scrollIntoView(); "
        "var r = c.getBoundingClientRect(); return [r.left, r.top]; })()"
    )
    # the markers of layer 1 as drawn: dots in the error colour; the rightmost is line 16's (X90 Y40)
    # (drawn on an animation frame, which comes late on a loaded machine: wait for it)
    browser.js(
        """window.errorDots = function () { var c = document.querySelector('canvas.tp-canvas'), g = c.getContext('2d');
        var d = g.getImageData(0, 0, c.width, c.height).data, hits = [];
        for (var i = 0; i < d.length; i += 4) if (d[i] > 200 && d[i + 1] < 60 && d[i + 2] < 60)
          hits.push([(i / 4) % c.width, Math.floor(i / 4 / c.width)]);
        return hits; }"""
    )
    browser.wait("window.errorDots().length > 0")
    dots = browser.js("window.errorDots()")
    assert dots, "no marker drawn"
    px, py = sorted(dots)[-1]
    browser.click(at[0] + px - 2, at[1] + py)
    browser.wait("document.querySelector('tr[data-line=\"16\"]').classList.contains('sel')")
    browser.screenshot(shots(tmp_path) / "two-heads-marker-selected.png", "section.file")


@pytest.mark.skipif(not corpus_available(), reason="corpus not found")
def test_toolpath_shows_the_part_and_follows_the_layer_slider(tmp_path: Path, browser: Browser):
    """A 20 mm cube whose start G-code primes at Z15 and purges along the bed's edge: the view is fitted to the
    part, not to the purge line, and the slider shows one layer over the faded ones below."""
    page = tmp_path / "cube.html"
    proc = run_cli("check", "--no-cache", str(CUBE), "--format", "html", "--output", str(page), "--exit-zero")
    assert proc.returncode == 0, proc.stderr
    browser.open(page)
    browser.wait("document.querySelector('figure.toolpath').dataset.drawn")
    top = canvas(browser)
    shots_dir = shots(tmp_path)
    browser.screenshot(shots_dir / "cube-top-layer.png", "figure.toolpath")
    assert top["label"].startswith("layer 31 of 31, Z 6.2 mm"), top["label"]
    # the part fills the view: its drawn box spans most of the canvas's height (a square part in a 4:3 view)
    assert share(top["drawn"], top["height"], 1) > 0.8 and share(top["drawn"], top["width"], 0) > 0.55, top
    assert share(top["strong"], top["height"], 1) > 0.8 and top["count"] > 1000, top

    # move the slider (a click on its track, a fifth of the way along): a lower layer is drawn
    x, y, w, h = browser.js(
        "(function () { var r = document.querySelector('input.tp-layer').getBoundingClientRect();"
        " return [r.left, r.top, r.width, r.height]; })()"
    )
    browser.click(x + w * 0.2, y + h / 2)
    browser.wait("document.querySelector('input.tp-layer').value !== '31'")
    lower = canvas(browser)
    browser.screenshot(shots_dir / "cube-lower-layer.png", "figure.toolpath")
    assert lower["label"] != top["label"] and lower["label"].startswith("layer ")
    assert int(lower["layer"]) < 31 and lower["digest"] != top["digest"]

    # the keyboard: Home on the plot goes to the first layer, End back to the top
    browser.js("document.querySelector('canvas.tp-canvas').focus()")
    browser.key("Home", "Home", 36)
    browser.wait("document.querySelector('input.tp-layer').value === '1'")
    assert canvas(browser)["label"].startswith("layer 1 of 31, Z 0.2 mm")
    messages = browser.console()
    assert not [m for m in messages if re.search(r"Uncaught|Error|Refused|violat|exception", m)], messages


@pytest.mark.skipif(not corpus_available(), reason="corpus not found")
def test_summary_page_of_a_big_corpus_job_renders(tmp_path: Path, browser: Browser):
    job = CORPUS / "marlin" / "prusaslicer-2.6.1_benchy.gcode"
    page = tmp_path / "benchy.html"
    proc = run_cli("summary", str(job), "--format", "html", "--output", str(page))
    assert proc.returncode == 0, proc.stderr
    assert page.stat().st_size < 3_000_000  # compact data, sampled past a bound
    browser.open(page)
    browser.wait("document.querySelector('figure.toolpath').dataset.drawn")
    assert "Job summary" in browser.js("document.body.textContent")
    shown = canvas(browser, (0x1F, 0x77, 0xB4))
    assert shown["label"].startswith("layer 160 of 160") and shown["count"] > 100, shown
    assert not [m for m in browser.console() if re.search(r"Uncaught|Error|Refused|violat|exception", m)]
