"""Slicer profiles: PrusaSlicer, SuperSlicer and OrcaSlicer configurations and bundles (``.ini``), OrcaSlicer and
Bambu Studio printer profiles (``.json``), Cura machine definitions (``.def.json``).

``gclint check profile.ini`` checks the custom G-code a profile puts into every job sliced with it (start, end,
tool change, layer change, pauses...), with its placeholders filled, in the profile's flavour, and reports each
finding where it is written in the profile.

* ``ini``: PrusaSlicer's INI files read with positions, string values decoded as the slicer decodes them;
* ``jsontext``: JSON read with the position of every string;
* ``bundle``: configuration bundles and their ``inherits`` chains, flattened as PrusaSlicer flattens them (also
  what the slicer tests use to slice with the vendor profiles PrusaSlicer ships);
* ``reader``: which file is a profile, and its custom G-code settings and values;
* ``placeholders``: the slicers' placeholder and macro language, filled;
* ``check``: the G-code put together as a job carries it, checked, each finding mapped back to the profile.
"""
