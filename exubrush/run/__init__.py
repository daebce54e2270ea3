"""One run from a case to its results: preparation and budget, the Exudyn scene of a group,
solver settings and step policy, the solve, its assembly and the run directory.
"""
