"""Which build of Exudyn's C++ core exubrush runs on: the fast one unless asked otherwise.

Exudyn ships two builds of its core: ``exudynCPP``, which checks the range of every vector
and matrix index, and ``exudynCPPfast``, without those checks and built for AVX2. A process
picks one when it first imports ``exudyn``, from ``sys.exudynFast``. The fast build solves
exubrush's bristles 13-17 % faster with the same flat-zone forces (within their rounding and
the stick-slip that follows; measured in docs/decisions/0007).

``import exubrush`` asks for the fast build in every process that imports it before
``exudyn`` (the command line, its worker processes, Dask workers), unless

- the environment sets ``EXUBRUSH_EXUDYN_CHECKS=1`` (for hunting a crash: an index error
  then raises instead of reading past an array),
- the program set ``sys.exudynFast`` itself, or imported ``exudyn`` before exubrush.

Exudyn announces the fast build on standard output at every import; exubrush drops that
one line and passes on anything else Exudyn prints (e.g. that a CPU without AVX2 falls
back to the checked build). Exudyn itself is not imported here.
"""

from __future__ import annotations

import contextlib
import importlib.abc
import importlib.util
import io
import os
import sys

CHECKS_VARIABLE = "EXUBRUSH_EXUDYN_CHECKS"
_ANNOUNCEMENT = "Imported exudyn fast version without range checks"


def wants_checked_build(environ=os.environ) -> bool:
    """True if ``environ`` asks for Exudyn's range-checked build."""
    return environ.get(CHECKS_VARIABLE, "").strip().lower() in {"1", "true", "yes"}


def choose_exudyn_build() -> None:
    """Ask for the fast build unless the process decided already (see the module text)."""
    if "exudyn" in sys.modules or hasattr(sys, "exudynFast"):
        return
    sys.exudynFast = not wants_checked_build()
    if sys.exudynFast:
        sys.meta_path.insert(0, _QuietAnnouncement())


def build_in_use() -> str:
    """``"fast"`` or ``"checked"`` for run records: the core this process loaded if it has
    imported Exudyn (a CPU without AVX2 falls back to the checked one), else the one it will
    ask for (the workers, which solve, decide as this process does)."""
    exudyn = sys.modules.get("exudyn")
    if exudyn is not None and hasattr(exudyn, "_compiledModuleName"):
        return "fast" if exudyn._compiledModuleName == "exudynCPPfast" else "checked"
    return "fast" if getattr(sys, "exudynFast", False) else "checked"


class _QuietAnnouncement(importlib.abc.MetaPathFinder):
    """Finds ``exudyn`` once, through the normal finders, and runs its package code with
    the announcement line filtered out of standard output."""

    def find_spec(self, name, path=None, target=None):
        if name != "exudyn":
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.loader is not None:
            execute = spec.loader.exec_module

            def exec_module(module):
                captured = io.StringIO()
                try:
                    with contextlib.redirect_stdout(captured):
                        execute(module)
                finally:
                    lines = captured.getvalue().splitlines(keepends=True)
                    kept = "".join(line for line in lines if line.strip() != _ANNOUNCEMENT)
                    if kept and sys.stdout is not None:  # None: no console (pythonw)
                        sys.stdout.write(kept)

            spec.loader.exec_module = exec_module
        return spec
