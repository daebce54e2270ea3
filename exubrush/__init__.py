"""exubrush: toothbrush bristle deflection and contact forces, simulated with Exudyn.

Units inside the package are mm, N, s and tonne (so stresses are MPa and densities t/mm^3);
every public input and output names its unit.
"""

__version__ = "0.1.0"
