"""The Marlin codes with no Hyrel counterpart, by what dropping them costs (the Marlin G-code reference,
marlinfw.org/meta/gcode; docs/translation.md): TR001 no effect on the job, TR002 the firmware did something, TR005 the
toolpath or the job's flow would change.  Klipper-style host commands found in Marlin-flavour files are listed apart.
"""

from __future__ import annotations

from gclint.translate.findings import TR_DROPPED, TR_LOST, TR_UNTRANSLATABLE
from gclint.translate.findings import codes as _codes

# Codes with no Hyrel counterpart (Marlin G-code reference; docs/translation.md).  TR001: no effect on the job.
NO_EFFECT = {
    **_codes("M73 M73.2", TR_DROPPED, "print progress display"),
    **_codes("M117 M118", TR_DROPPED, "display or host message"),
    **_codes(
        "M105 M114 M115 M119 M27 M31 M155 M154 M503 M122 M123 M43 M100 M111 M113 M430 M876",
        TR_DROPPED,
        "host report or diagnostic",
    ),
    **_codes("M400", TR_DROPPED, "wait for the move queue (Hyrel runs commands in order)"),
    **_codes("M486 M555", TR_DROPPED, "object labels and print area for the host"),
    **_codes("M75 M76 M77 M78", TR_DROPPED, "print job timer and statistics"),
    **_codes("M108 M110", TR_DROPPED, "host protocol"),
    **_codes("M20 M21 M22 M23 M24 M26 M28 M29 M32 M33 M34 M524 M928", TR_DROPPED, "SD card operation"),
    **_codes(
        "M500 M501 M502 M504 M510 M511 M512 M575 M993 M994 M995 M997 M999",
        TR_DROPPED,
        "settings storage or firmware maintenance",
    ),
    **_codes("M862.1 M862.2 M862.3 M862.4 M862.5 M862.6 M16", TR_DROPPED, "printer, nozzle or firmware check"),
    **_codes("M150 M250 M256 M355 M7219 M960", TR_DROPPED, "lights or display"),
    **_codes("M80 M81 M85 M86 M87", TR_DROPPED, "power supply or idle timeout"),
    **_codes("M120 M121 M540 M302 M412 M413 M591 M603 M217 M145 M149", TR_DROPPED, "firmware safety or preset setting"),
    **_codes("M301 M303 M304 M305 M307 M308 M143 M142", TR_DROPPED, "heater configuration"),
    **_codes(
        "M92 M350 M351 M569 M906 M907 M908 M909 M910 M911 M912 M913 M914 M915 M916 M917 M919",
        TR_DROPPED,
        "stepper driver configuration (Repetrel configures the Hyrel machine)",
    ),
    **_codes(
        "M260 M261 M42 M281 M282 M672 M860 M861 M862 M863 M864 M865 M866 M867 M868 M869 M871",
        TR_DROPPED,
        "pin, bus or sensor configuration",
    ),
    **_codes("M710", TR_DROPPED, "controller fan (the number is Hyrel's RTD enable)"),
    **_codes(
        "M971 M991 M1002 M975 M981 M982 M983 M1003 M1006 M1007 M973 M970 M970.3 M974 M976 M977 M972 M980.3"
        " M963 M964 M969 M1002 M708 M709",
        TR_DROPPED,
        "vendor-specific (Bambu, Prusa) notification or calibration",
    ),
    **_codes("G81 G162 G392", TR_DROPPED, "vendor-specific report or check"),
}

# TR002: the source firmware did something here that Hyrel cannot do from G-code.
LOST = {
    **_codes(
        "M201 M201.2 M204 M205 M566",
        TR_LOST,
        "acceleration and jerk limits have no Hyrel G-code (M204 and M205 "
        "mean no-ramp speed and homing speed in Hyrel firmware)",
    ),
    **_codes("M900 M572 M593 M592", TR_LOST, "pressure/linear advance and input shaping have no Hyrel counterpart"),
    **_codes(
        "G29 G29.1 G29.2 G30 G31 G32 G33 G34 G35 G80 G26 G425 G39 G380 G383 M420 M421 M422 M423 M425 M851 M48 "
        "M290 M401 M402 G76 M192",
        TR_LOST,
        "bed levelling and probing calibration; Hyrel has none in G-code",
    ),
    **_codes(
        "M207 M208 M209",
        TR_LOST,
        "firmware retraction settings (Hyrel heads carry their own unprime/prime settings, M721/M722)",
    ),
    **_codes("M206 M428 M218", TR_LOST, "home and hotend offsets (Repetrel declares head offsets with M6)"),
    **_codes("M163 M164 M165 M166 M567", TR_LOST, "colour mixing"),
    **_codes("M605", TR_LOST, "duplication mode (Hyrel clone squads need M702/M703 set up by hand)"),
    **_codes("M701 M702", TR_LOST, "filament load/unload (the numbers are Hyrel head reporting and clone squads)"),
    **_codes("M10 M11 M380 M381 M126 M127 M128 M129 M240", TR_LOST, "auxiliary output (valve, solenoid, camera)"),
    **_codes("M665 M666 M951", TR_LOST, "kinematics configuration"),
    **_codes("M404 M405 M406 M407", TR_LOST, "filament width sensor"),
    **_codes("M280", TR_LOST, "servo position"),
    **_codes("G12 G27 G60 M125", TR_LOST, "nozzle cleaning or parking moves"),
    **_codes("M410", TR_LOST, "quick stop"),
    **_codes("M193", TR_LOST, "laser cooler temperature"),
    **_codes("M403", TR_LOST, "MMU filament type"),
}

UNTRANSLATABLE = {
    **_codes(
        "G5 G6 G42 G61 G150 G38.2 G38.3 G38.4 G38.5",
        TR_UNTRANSLATABLE,
        "a move or probing move Hyrel has no command for (the toolpath changes)",
    ),
    **_codes("M808", TR_UNTRANSLATABLE, "repeat markers (a loop over part of the job)"),
    **_codes("M112", TR_UNTRANSLATABLE, "emergency stop: Hyrel documents no e-stop code"),
    # Bambu's AMS filament change: the numbers are Hyrel's laser and UV codes (M620-M623).
    **_codes(
        "M620 M620.1 M620.3 M620.10 M620.11 M621 M622 M622.1 M623 M624 M625",
        TR_UNTRANSLATABLE,
        "vendor filament-change sequence (the number is a Hyrel laser/UV code)",
    ),
}

HOST_NO_EFFECT = frozenset(
    {
        "EXCLUDE_OBJECT_DEFINE",
        "EXCLUDE_OBJECT_START",
        "EXCLUDE_OBJECT_END",
        "EXCLUDE_OBJECT",
        "SET_PRINT_STATS_INFO",
        "RESPOND",
        "SET_DISPLAY_TEXT",
        "UPDATE_DELAYED_GCODE",
        "SAVE_VARIABLE",
        "M117",
    }
)
HOST_LOST = frozenset(
    {
        "SET_VELOCITY_LIMIT",
        "SET_PRESSURE_ADVANCE",
        "SET_RETRACTION",
        "SET_GCODE_OFFSET",
        "SET_INPUT_SHAPER",
        "SET_FAN_SPEED",
        "SET_LED",
        "SET_HEATER_TEMPERATURE",
        "TEMPERATURE_WAIT",
        "SET_TEMPERATURE_FAN_TARGET",
        "BED_MESH_PROFILE",
        "BED_MESH_CLEAR",
        "BED_MESH_CALIBRATE",
        "SET_KINEMATIC_POSITION",
        "SET_EXTRUDER_ROTATION_DISTANCE",
    }
)
