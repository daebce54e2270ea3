"""Small helpers every layer uses: units, unit-labelled tables, whole-or-nothing files,
provenance, float helpers, Exudyn's build choice, references.
"""
