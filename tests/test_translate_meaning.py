"""Issue 27: what the translator must keep of a job's meaning, beyond a line's own words."""

from __future__ import annotations

from pathlib import Path

from gclint import dialects
from gclint.syntax.source import Source
from gclint.translate import TranslationResult, translate_source, translator_for
from gclint.translate.options import TranslateOptions
from tests.conftest import CORPUS, needs_corpus

from .test_translate_tables import translate


def test_a_single_nozzle_job_heats_and_cools_the_one_head() -> None:
    """``single_extruder_multi_material = 1`` (an MMU, an AMS): every tool is a filament through one nozzle and
    heater; the job's last ``M104 S0`` switches that heater off, whatever tool was last."""
    job = "T0\nM104 S220\nG1 X1 Y1 E1 F600\nT2\nM104 S230\nG1 X2 Y1 E1\nM104 S0\n; single_extruder_multi_material = 1\n"
    out, result = translate("marlin", job)
    lines = out.splitlines()
    assert "M104 T0 S0" in lines and not any(line.startswith(("M104 T2", "T2")) for line in lines), lines
    assert any("single-nozzle" in f.message for f in result.findings)
    several, _ = translate("marlin", job.replace("= 1", "= 0"))
    assert "M104 T2 S0" in several.splitlines()  # (a head per tool when the job says so)


@needs_corpus
def test_annotated_output_stays_within_hyrel_lines(tmp_path: Path) -> None:
    """``--annotate`` notes are comments Repetrel would cut at 100 characters: they are wrapped onto lines of
    their own, so a translated job passes its own linter's HY029."""
    [job] = sorted(CORPUS.rglob("cds.ngc"))
    translator = translator_for(dialects.get("machinekit"), dialects.get("hyrel"), TranslateOptions(annotate=True))
    result = TranslationResult(str(job), "machinekit", "hyrel")
    out = "".join(translate_source(Source.open(str(job)), translator, result))
    assert max(len(line) for line in out.splitlines()) <= 100
