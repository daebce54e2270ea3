"""exubrush: toothbrush bristle deflection and contact forces, simulated with Exudyn.

Units inside the package are mm, N, s and tonne (so stresses are MPa and densities t/mm^3);
every public input and output names its unit.

>>> import exubrush
>>> case = exubrush.load_case("orthogonal", ["head.rows=1"])
>>> results = exubrush.simulate(case)            # doctest: +SKIP

The names below are imported on first use, so that ``import exubrush`` stays light (no
Exudyn, no matplotlib) for a script that only reads parameters or results.
"""

from exubrush.util.exudyn_build import choose_exudyn_build
from exubrush.util.provenance import package_version

__version__ = package_version()
choose_exudyn_build()  # Exudyn's fast build in every process that imports exubrush first

_API = {
    "load_case": "exubrush.parameters.io",
    "Case": "exubrush.parameters.case",
    "ParameterError": "exubrush.parameters.fields",
    "prepare": "exubrush.run.prepared",
    "PreparedCase": "exubrush.run.prepared",
    "simulate": "exubrush.simulation",
    "Results": "exubrush.output.results",
    "read_results": "exubrush.output.results",
}
__all__ = ["__version__", *_API]


def __getattr__(name: str):
    if name in _API:
        import importlib

        return getattr(importlib.import_module(_API[name]), name)
    raise AttributeError(f"module 'exubrush' has no attribute {name!r}")
