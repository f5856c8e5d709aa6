"""TR: translation findings.  ``gclint translate`` reports them; ``gclint check`` never runs them.

Each class documents one kind of loss, so ``gclint rules TR003`` explains it like any other rule.  The
translators in gclint/translate/ report them through ``HyrelTranslator.report`` (gclint/translate/writer.py);
the numbering is documented in docs/translation.md:

    TR001 dropped                      info     no Hyrel counterpart, no effect on the job
    TR002 dropped-behaviour-lost       warning  no Hyrel counterpart, the source firmware did something here
    TR003 approximate                  warning  translated to the nearest Hyrel command, behaviour differs
    TR004 translated-with-note         info     translated; a documented difference that does not change the job
    TR005 untranslatable               error    cannot be translated (program flow, variables, macros, probing)
    TR006 address-without-counterpart  error    Hyrel v4 <-> v5: a T number with no certain counterpart
    TR007 tool-not-on-printer          error    a tool, fan or device maps to an address the printer lacks
    TR008 after-end-of-program         info     code after the source's end of program (never ran there)
    TR009 comment-becomes-action       warning  a comment Hyrel would run as a host action after M0 (removed)

``families = ()`` keeps them out of every check: ``Rule.applies_to`` is false for all dialects.
"""

from __future__ import annotations

from gclint.rules.base import Rule, Severity, register


class TranslationRule(Rule):
    """Base of the TR rules: documentation only, reported by ``gclint translate``."""

    families = ()  # never run by ``gclint check``
    default_enabled = False

    @classmethod
    def doc(cls) -> dict:
        out = super().doc()
        out["applies_to"] = ["gclint translate (target hyrel, hyrel-v4)"]
        return out


@register
class Dropped(TranslationRule):
    code = "TR001"
    name = "dropped"
    severity = Severity.INFO
    summary = "A command with no Hyrel counterpart was dropped; it has no effect on the job"
    explanation = """
        Display messages (M117), progress (M73), host reports (M105, M114, M115), the source firmware's
        own configuration (M500-M503, M563, M950) and waits for the move queue (M400) have no Hyrel
        command.  They do not change what the machine makes, so the translator drops them (only codes of
        the Hyrel Gcode page's Code_Chart are written: docs/translation.md) and reports them at info level.
    """
    example_bad = "M117 Printing..."
    example_good = "; (the line is dropped; with --annotate: '; gclint: dropped ...')"
    source = (
        "Gcode page, Code_Chart (the only codes written); Marlin G-code reference (M117, M73, M105, M400); "
        "docs/translation.md (output is allow-listed)"
    )


@register
class DroppedBehaviourLost(TranslationRule):
    code = "TR002"
    name = "dropped-behaviour-lost"
    severity = Severity.WARNING
    summary = "A command was dropped although the source firmware did something with it"
    explanation = """
        Acceleration and jerk limits (M201, M204, M205), linear/pressure advance (M900, M572), bed
        levelling (G29), maximum feed rates (M203, which on Hyrel sets the G0 speed in mm/min instead),
        speed factors (M220) and the like have no Hyrel counterpart.  Several of these numbers mean
        something else on Hyrel firmware (M204 no-ramp speed, M205 homing speed), so passing them through
        would be wrong.  The translation drops them; the printed part may differ (ringing, seams, first
        layer), so review the job.
    """
    example_bad = "M204 P1500"
    example_good = "; (dropped: Hyrel has no acceleration setting in G-code)"
    source = (
        "Marlin G-code reference (M201, M203, M204, M205, M900); Gcode page, M203 Set G0 Speed and Code_Chart; "
        "Hyrel firmware source, inc/GCode.h (M204 no-ramp speed, M205 homing speed)"
    )


@register
class Approximate(TranslationRule):
    code = "TR003"
    name = "approximate"
    severity = Severity.WARNING
    summary = "Translated to the nearest Hyrel command; the behaviour differs in a documented way"
    explanation = """
        Some commands have a Hyrel counterpart that does not do exactly the same thing: a bare Marlin
        G28 homes X, Y and Z but is written as "G28 X0 Y0" (Hyrel homes only the listed axes and Z
        homing needs a Z home), RepRapFirmware's G10 tool temperatures lose the standby temperature,
        M600 becomes a plain pause, a spindle speed in rpm becomes a percentage of the spindle's maximum.
        The message says what differs.
    """
    example_bad = "G28"
    example_good = "G28 X0 Y0"
    source = (
        "docs/translation.md (per-dialect tables); Gcode page, G28 Send X, Y to Physical Home; Duet G-code "
        "dictionary, G10; Marlin G-code reference, M600"
    )


@register
class TranslatedWithNote(TranslationRule):
    code = "TR004"
    name = "translated-with-note"
    severity = Severity.INFO
    summary = "Translated; a documented difference that does not change the job"
    explanation = """
        The translation is faithful, but the Hyrel command works differently: Marlin's "M109 R200"
        (wait for 200 C heating or cooling) becomes "M109 T0 S200 R2" because Hyrel's R is a tolerance
        window; retraction moves are left to the head's automatic unprime/prime; a Machinekit dwell in
        seconds becomes G4 S.
    """
    example_bad = "M109 R200"
    example_good = "M109 T0 S200 R2"
    source = (
        "Marlin G-code reference, M109 (R: wait when heating or cooling); Gcode page, M109 Wait for Temp (Head) "
        "(Rn: a tolerance); docs/translation.md"
    )


@register
class Untranslatable(TranslationRule):
    code = "TR005"
    name = "untranslatable"
    severity = Severity.ERROR
    summary = "A construct that cannot be translated; it was dropped and the output is incomplete"
    explanation = """
        Program flow and variables (LinuxCNC O-words and # parameters, RepRapFirmware meta commands and
        {expressions}), macro calls (M98), HAL I/O (M62-M68), probing, automatic tool changers, homing
        moves and emergency stops have no Hyrel equivalent.  The translator cannot evaluate them, so it
        drops them and reports an error: the job will not do what the source did.  With
        ``--unsupported error`` nothing is written.
    """
    example_bad = "o100 if [#1 GT 2]"
    example_good = "; (no translation: rewrite the job without program flow)"
    source = (
        "LinuxCNC docs, o-code.html and m-code.html#mcode:m62-m65; Carvera M-code table (ATC, probing); Gcode "
        "page, Code_Chart (no counterpart); docs/translation.md"
    )


@register
class AddressWithoutCounterpart(TranslationRule):
    code = "TR006"
    name = "address-without-counterpart"
    severity = Severity.ERROR
    summary = "Hyrel v4 <-> v5: a T number with no certain counterpart in the other addressing"
    explanation = """
        Hyrel v4 T variables are CAN device addresses (T11-T15 yoke 1, T21-T25 yoke 2, T16 aux, T41 laser,
        T26 spindle, T91/T92 beds, wildcards T0, T10, T20, T90, T100); v5 uses one address table for T
        commands and variables (T0-T19 heads, T20-T25 devices, T30-T48 groups).  The map is certain for
        the numbers the Hyrel firmware tables and wiki confirm (docs/sources.md); for the others
        (v4 clone groups T50-T57, v5 Aux2 T23, yoke 3 and 4, and the aux port: v4 T16 / tool T10 is v5
        Aux1 T22 by inference only, "mapping to v5 Aux1 is I - medium") the number is left unchanged and
        reported, and where one is inferred the finding names it as uncertain.
    """
    example_bad = "M104 T23 S0"
    example_good = "M104 T22 S0"
    source = (
        "T_v5, Chart of Addresses; T_v4 page; Hyrel v4 firmware source, Hydra4/main.c toolNumberMap and "
        "Hydra4/common/inc/hyrel.h (confidence per address: docs/sources.md)"
    )


@register
class ToolNotOnPrinter(TranslationRule):
    code = "TR007"
    name = "tool-not-on-printer"
    severity = Severity.ERROR
    summary = "A source tool, fan or device maps to a Hyrel address the printer does not have"
    explanation = """
        Source tool numbers become Hyrel head addresses through the tool map (--tool-map, default
        0->T0, 1->T1 ...).  A 30M or ESR has head positions T0-T3, an EHR T0-T4, a dual-yoke 16A T0-T9:
        a tool that lands outside the printer's positions (a five-tool MMU job on a 30M) cannot be
        translated; the command is dropped.  Map the tools with --tool-map or choose the printer with
        --printer.
    """
    example_bad = "T5"
    example_good = "T1"
    source = (
        "T_v5, Using the T with the ESR and 30M / EHR and 16A / 16A (Dual Yoke) (T-address map per model); "
        "docs/translation.md (every head command addressed)"
    )


@register
class AfterEndOfProgram(TranslationRule):
    code = "TR008"
    name = "after-end-of-program"
    severity = Severity.INFO
    summary = "Code after the source's end of program was dropped (it never ran in the source either)"
    explanation = """
        LinuxCNC/Machinekit and Carvera stop at M2/M30; RepRapFirmware at M0/M1/M2.  Hyrel ends a job at
        M30 and reports any code after it, so the translator writes its footer (emitters off, spindles
        off, M30) at the source's end of program and drops the commands that follow.
    """
    example_bad = "M2\nG0 X0"
    example_good = "M30"
    source = (
        "Hyrel Gcode page, M30 End of Program; LinuxCNC docs, m-code.html#mcode:m2-m30; Carvera M-code table (M2, "
        "M30); Duet G-code dictionary (M0, M1, M2); docs/translation.md (the footer)"
    )


@register
class CommentBecomesAction(TranslationRule):
    code = "TR009"
    name = "comment-becomes-action"
    severity = Severity.WARNING
    summary = "A comment that Hyrel would run as a host action (SHELL, PIC, SAY...) was removed from an M0/M792"
    explanation = """
        On Marlin, RepRapFirmware, Machinekit and Carvera a comment after M0 is only a comment.  On Hyrel,
        Repetrel reads the text after M0 and M792 as actions, one per segment: "SHELL C:\\program.exe - the
        computer will execute the file at the specified location", PIC and VID open files, SAY speaks, SEND
        writes to the Aux port, BEEP beeps.  Carried over as it was, `M0 ; SHELL C:\\evil.exe` would make
        the PC that runs the printer start a program.  The translator removes such a comment from the
        pause and reports it; the pause itself stays.  Actions are read as the SC rules read them: a
        keyword starting a segment in any case, or SHELL anywhere, also with invisible characters inside.

        Every line a translation writes is checked the same way: one that would still carry SHELL after
        M0, M1 or M792 (a Hyrel source's own action, which the identity and the v4/v5 renumbering copy)
        is an error, and nothing is written (exit 1, whatever --unsupported says).
    """
    example_bad = "M0 ; SHELL C:\\evil.exe"
    example_good = "M0"
    source = (
        "Hyrel Gcode page, M0 Stop Until Resume and M792 Execute Action (SAY, PIC, VID, SEND, BEEP, SHELL); "
        "gclint/rules/security/ (SC rules)"
    )


TR_SEVERITY: dict[str, Severity] = {
    cls.code: cls.severity
    for cls in (
        Dropped,
        DroppedBehaviourLost,
        Approximate,
        TranslatedWithNote,
        Untranslatable,
        AddressWithoutCounterpart,
        ToolNotOnPrinter,
        AfterEndOfProgram,
        CommentBecomesAction,
    )
}
TR_NAME: dict[str, str] = {
    cls.code: cls.name
    for cls in (
        Dropped,
        DroppedBehaviourLost,
        Approximate,
        TranslatedWithNote,
        Untranslatable,
        AddressWithoutCounterpart,
        ToolNotOnPrinter,
        AfterEndOfProgram,
        CommentBecomesAction,
    )
}
