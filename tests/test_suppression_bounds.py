"""Suppression comments use memory in proportion to what they say, not to how often they say it (the
attacker review's case B): noqa comments and gclint: disable/enable directives are kept as arrays of line
numbers and shared lists of codes; suppressed findings take no place under the per-file bound of findings
kept (a job could hide a real error behind 20,000 silenced ones); unused-noqa findings are bounded too.

Structural checks only; the memory itself is measured in bench/bench_reports.py.
"""

from __future__ import annotations

from gclint.engine import MAX_FINDINGS, Linter, Options


def test_noqa_comments_are_kept_as_arrays_of_shared_code_lists() -> None:
    linter = Linter(Options(dialect="hyrel"))
    text = (
        "G28 X0 Y0\n" + "G1 X1 F100 ; noqa: HY001\n" * 5000 + "; gclint: disable=HY003\n; gclint: enable=HY003\n" * 100
    )
    source_ctx = {}
    real_prepare = linter.prepare

    def keep(source):
        ctx, result = real_prepare(source)
        source_ctx["ctx"] = ctx
        return ctx, result

    linter.prepare = keep  # type: ignore[method-assign]
    linter.check_text(text)
    ctx = source_ctx["ctx"]
    assert len(ctx.noqa) == 5000 and len(ctx.noqa.sets) == 1 and ctx.noqa.lines.itemsize == 8
    assert ctx.noqa.get(2) == ("HY001",) and ctx.noqa.get(1) is None
    assert len(ctx.directives) == 200 and len(ctx.directives.sets) == 1
    assert list(ctx.directives)[:2] == [(5002, "disable", ("HY003",)), (5003, "enable", ("HY003",))]


def test_suppressed_findings_do_not_use_up_the_bound_of_findings_kept() -> None:
    """20,000 findings silenced by noqa (or a disabled range) must not turn the next, unsilenced one into a
    count on a silenced one: it was lost, and the run passed."""
    for text in (
        "G28 X0 Y0\n" + "M109 T40 S200 ; noqa: HY003\n" * (MAX_FINDINGS + 5) + "M109 T40 S200\nM30\n",
        "G28 X0 Y0\n; gclint: disable=HY003\n"
        + "M109 T40 S200\n" * (MAX_FINDINGS + 5)
        + "; gclint: enable=HY003\nM109 T40 S200\nM30\n",
    ):
        found = [f for f in Linter(Options(dialect="hyrel")).check_text(text).findings if f.code == "HY003"]
        assert [f.line for f in found] == [text.count("\n") - 1], found


def test_unused_noqa_findings_are_bounded_and_counted() -> None:
    text = "G28 X0 Y0\n" + "G1 X1 F100 ; noqa: HY003\n" * (MAX_FINDINGS + 7) + "M30\n"
    found = Linter(Options(dialect="hyrel", extend_select=["SX008"])).check_text(text).findings
    unused = [f for f in found if f.code == "SX008"]
    assert len(unused) <= MAX_FINDINGS
    listed = len(unused)
    assert (
        f"(and {MAX_FINDINGS + 7 - listed:,} more SX008 findings later in the file, not listed)" in unused[-1].message
    )
