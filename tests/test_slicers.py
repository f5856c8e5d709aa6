"""Real slicer output: PrusaSlicer slices a small cube with Hyrel's own profile (from the corpus) and with a spread
of the vendor profiles it ships, runs ``gclint postprocess`` as a user's export does, and each job is then checked
with no flags: no error, no warning a person would call false, and the right firmware named.

Needs Debian's ``prusa-slicer`` (2.5: ``apt-get install prusa-slicer``), which ``.ci/run`` installs.  Outside CI
these tests are skipped when it is not installed; in CI (``CI`` set) they fail instead.

A vendor profile's printer preset is resolved with its ``inherits`` chain and its default print and filament
presets into one flat configuration (gclint.profiles.bundle), as PrusaSlicer's configuration wizard would
install it, and loaded with ``--load``.  The slicer is run with ``--post-process "gclint postprocess"`` exactly
as a user sets it (PrusaSlicer appends the G-code path and exports every setting as ``SLIC3R_*``); a job with
an error makes gclint exit 1 and PrusaSlicer stop the export, so the job exists only if the gate passed it.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

from gclint.profiles.bundle import Bundle, write_ini
from tests.conftest import CORPUS, needs_corpus, run_cli

pytestmark = pytest.mark.slicer

PROFILES = Path("/usr/share/PrusaSlicer/profiles")  # Debian's prusa-slicer package
HYREL_PROFILE = "hyrel/oinkotariah__printer_30M-ESR_T1_Heated.ini"


def prusa_slicer() -> str:
    path = shutil.which("prusa-slicer")
    if path:
        return path
    if os.environ.get("CI"):
        pytest.fail("prusa-slicer is not installed, but CI must run the slicer tests (.ci/run installs it)")
    pytest.skip("prusa-slicer is not installed (apt-get install prusa-slicer); CI installs it and runs these tests")


def cube_stl(size: float = 10.0) -> str:
    """An ASCII STL cube of ``size`` mm (12 facets): small enough to slice in about a second."""
    s = size
    corners = [(0, 0, 0), (s, 0, 0), (s, s, 0), (0, s, 0), (0, 0, s), (s, 0, s), (s, s, s), (0, s, s)]
    faces = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4)]
    faces += [(1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    out = ["solid cube"]
    for face in faces:
        out.append(" facet normal 0 0 0\n  outer loop")
        out.extend("   vertex {:g} {:g} {:g}".format(*corners[i]) for i in face)
        out.append("  endloop\n endfacet")
    out.append("endsolid cube")
    return "\n".join(out) + "\n"


@dataclass
class Job:
    path: Path
    findings: list[tuple[str, str, str]]  # (code, severity, the line as printed)
    more: dict[str, int]  # code -> findings not printed ("... and 3 more like this (SX002)")
    checked_as: str
    output: str

    def codes(self, severity: str) -> set[str]:
        return {code for code, level, _ in self.findings if level == severity}


_FINDING = re.compile(r"^.*?:\d+:\d+: ([A-Z]{2}\d{3}) \[(error|warning|info)\] (.*)$")
_MORE = re.compile(r"\.\.\. and (\d+) more like this \(([A-Z]{2}\d{3})\)")


def slice_and_check(tmp_path: Path, config: Path, name: str) -> Job:
    """Slice the cube with ``config`` and ``gclint postprocess``, then ``gclint check`` the job, no flags."""
    slicer = prusa_slicer()
    stl = tmp_path / "cube.stl"
    stl.write_text(cube_stl())
    job = tmp_path / f"{name}.gcode"
    env = dict(os.environ)
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")  # (this gclint)
    env.pop("GCLINT_CACHE_DIR", None)
    cmd = [slicer, "--datadir", str(tmp_path / "prusa-datadir"), "--loglevel", "1", "--export-gcode"]
    cmd += ["--load", str(config), "--post-process", "gclint postprocess", str(stl), "-o", str(job)]
    proc = subprocess.run(cmd, capture_output=True, env=env, timeout=300, cwd=tmp_path)
    said = (proc.stdout + proc.stderr).decode("utf-8", "replace")
    assert job.is_file(), f"the export stopped (gclint postprocess fails a job with errors):\n{said[-3000:]}"
    assert Path(f"{job}.gclint.txt").is_file(), "gclint postprocess wrote no report: did the slicer run it?"
    checked = run_cli("check", job.name, cwd=tmp_path)
    output = checked.stdout.decode("utf-8", "replace")
    assert checked.returncode in (0, 1), checked.stderr.decode("utf-8", "replace")
    findings, more, checked_as = [], {}, ""
    for line in output.splitlines():
        if m := _FINDING.match(line):
            findings.append((m.group(1), m.group(2), line))
        elif m := _MORE.search(line):
            more[m.group(2)] = int(m.group(1))
        elif line.startswith("Checked as "):
            checked_as = line[len("Checked as ") :].rstrip(".")
    return Job(job, findings, more, checked_as, output)


def vendor_config(tmp_path: Path, vendor: str, printer: str) -> Path:
    """The flat configuration of a vendor's printer preset, with its default print and filament presets."""
    bundle_path = PROFILES / f"{vendor}.ini"
    if not bundle_path.is_file():
        prusa_slicer()  # (skips or fails first when the slicer itself is missing)
        pytest.fail(f"{bundle_path} is missing: the prusa-slicer package ships it")
    config = Bundle.from_file(str(bundle_path)).slicing_config(printer)
    if config.get("first_layer_height", "").endswith("%"):
        # PrusaSlicer 2.5 reads a percentage here as one of the nozzle diameter and refuses the Artillery
        # bundle's 150% ("First layer height can't be greater than nozzle diameter"): its wizard would not
        # install that, so the first layer is the layer height
        config["first_layer_height"] = config.get("layer_height", "0.2")
    path = tmp_path / "config.ini"
    path.write_text(write_ini(config))
    return path


# (vendor, printer preset, what gclint must name, text the job must carry)
VENDOR_CASES = [
    ("PrusaResearch", "Original Prusa i3 MK3S & MK3S+", "marlin (prusa-mk3)", "M862.3"),
    ("PrusaResearch", "Original Prusa MINI & MINI+", "marlin (prusa-buddy)", "M862.3"),
    # its M862.3/M862.1 and M115 U3.2.3 say Prusa firmware (read as plain Marlin, they were DL001 warnings)
    ("PrusaResearch", "Original Prusa i3 MK2S", "marlin (prusa-mk3)", "M115 U3"),
    ("Creality", "Creality Ender-3 V2 (0.4 mm nozzle)", "marlin", "G28"),
    ("Voron", "Voron_v2_250 0.4 nozzle", "marlin (klipper)", "print_start EXTRUDER="),  # Klipper macros
    ("RatRig", "RatRig V-Core-3-300", "marlin (klipper)", "START_PRINT"),
    ("Jubilee", "Jubilee", "reprap", "T-1"),  # RepRapFirmware 3: tool changes, its macros
    # (once read as Carvera for its header's M-codes, so Marlin's codes were DL001 warnings)
    ("Snapmaker", "Snapmaker A350", "marlin", "G28"),
    # an OctoPrint host command in its start G-code (before, seven SX002 "E is repeated")
    ("Artillery", "Artillery Sidewinder X1 BL-TOUCH", "marlin", "\n@BEDLEVELVISUALIZER"),
]


@pytest.mark.parametrize("vendor,printer,firmware,carries", VENDOR_CASES, ids=[c[1] for c in VENDOR_CASES])
def test_vendor_profile_job_passes_the_gate(tmp_path, vendor, printer, firmware, carries):
    job = slice_and_check(tmp_path, vendor_config(tmp_path, vendor, printer), "cube")
    assert carries in job.path.read_text(), f"the job does not carry {carries!r}: not the profile's G-code?"
    assert not job.codes("error"), job.output
    assert job.checked_as == firmware, job.output
    assert not job.codes("warning") and not job.more, job.output


@needs_corpus
def test_hyrel_profile_job(tmp_path):
    """Hyrel's own 30M/ESR profile: the job passes the gate, is read as Hyrel v4 (its M109 T12 is a v4 address)
    on a 30M, and warns only where the pages say so."""
    profile = CORPUS / HYREL_PROFILE
    job = slice_and_check(tmp_path, profile, "hyrel")
    assert not job.codes("error"), job.output
    assert job.checked_as.startswith("hyrel v4, printer 30m"), job.output
    # HY014 (info) is true: the profile's before_layer_gcode writes "M756 S[layer_height]" while its start G-code
    # enables E values (M229 E1 D1), and the Gcode page says M756 is then ignored; HY029 (info) on the
    # profile's 102- and 106-character banner comments: a cut comment changes nothing the printer does
    assert not job.codes("warning") and set(job.more) <= job.codes("info"), job.output
    assert {"HY014", "HY029"} <= job.codes("info"), job.output
