"""``gclint explain``: decode each command in the printer's own terms.

Modelled on the "This command is decoded and executed by the printer as follows" sections of the Hyrel
Gcode page (https://hyrel3d.com/wiki/index.php/Gcode):

    M109 T0 S240 L10 U5
    * M109 (wait for head temperature)
    ** T0 (head T0: yoke 1, position 1)
    ** S240 (and set the temperature to 240°C)
    ** L10 (but end the wait once the temperature reaches 10°C below the set point)
    ** U5 (or end the wait once the temperature reaches 5°C above the set point)
    ** note: the wait ends when the temperature is anywhere between 230°C and 245°C

What a code and its words mean is read from one place, the dialect's code table (``Code.summary``,
``Code.does``/``notes``, ``Param.meaning``/``says``/``values``/``absent``, each with the section it comes
from).  The modules here add what depends on numbers or on the job so far, one topic each:

* ``explainer``: the walker (line by line through the machine ``Interpreter``) and the decoder table;
* ``job``: what a decoder sees besides the command (the dialect, the job's state); ``Decoder``;
* ``model``: ``Explanation`` and ``Item``, the output;
* ``generic``: what the table alone says (titles, meanings, unknown codes);
* ``addressing``: T variables (v5, v4), T command lines, clone squads (M702-M704);
* ``temperature``: M104/M140/M141, the M109/M190/M191 wait windows (H C L U R, W0), M116;
* ``fans``: M106 and its C range, M107;
* ``motion``: G0/G1 (with H), modal axis words, G4, G90/G91, M82/M83;
* ``arcs``: G2/G3, the G2.x spirals, G2.3;
* ``flow``: M229, M721/M722;
* ``offsets``: G28, G92, M6 (Hyrel), M660;
* ``lasers_spindles``: M620/M621/M623, M3/M4/M5, M6 (CNC), G81;
* ``jobflow``: M0 and its actions.
"""

from gclint.explain.explainer import Explainer, explain_lines, explain_source, explain_text
from gclint.explain.model import Explanation, Item

__all__ = ["Explainer", "Explanation", "Item", "explain_lines", "explain_source", "explain_text"]
