"""The [sweep] and [execution] tables of a sweep file, declared as parameters.

They use the case parameters' machinery (:func:`~exubrush.parameters.fields.param`,
:func:`~exubrush.parameters.fields.build`): unknown keys, whole numbers, units and ranges
are checked there, and ``exubrush sweep --example`` writes these tables with each field's
help text (exubrush.sweep.example). What varies ([grid], [sample]) is read in
exubrush.sweep.plan.
"""

from __future__ import annotations

from dataclasses import dataclass

from exubrush.parameters.catalogue import BUILT_IN_CASES
from exubrush.parameters.fields import Parameters, param

MAX_RUNS = 1000  # default bound on the runs of one sweep (sweep.max_runs raises it)
MAX_TIMEOUT = 600.0  # s: a longer wait for a scheduler is a hang, not a setting


@dataclass(frozen=True)
class SweepSettings(Parameters):
    """[sweep]: the base case, overrides for every run, seeds, a bound on the run count."""

    name: str = param("", "names the sweep folder (empty: the sweep file's name)", "text")
    base: str = param("", f"a built-in case ({', '.join(BUILT_IN_CASES)}) or a TOML case "
                      "file, relative to the sweep file", "text")
    set: tuple[str, ...] = param((), "--set overrides (KEY=VALUE) applied to every run",
                                 "text")
    seeds: tuple[int, ...] = param((), "repeat every run once per head.seed (root-tilt "
                                   "directions)", minimum=0)
    max_runs: int = param(MAX_RUNS, "refuse a sweep that expands to more runs than this",
                          above=0)

    def check(self) -> None:
        """Each seed once (a repeated seed repeats a run); a name that is not blank."""
        if len(set(self.seeds)) != len(self.seeds):
            raise ValueError("seeds repeats a seed; each seed gives the same run: list it "
                             "once")
        if self.name and not self.name.strip():
            raise ValueError("name must be non-empty text (or left out: the file's name)")


@dataclass(frozen=True)
class Execution(Parameters):
    """[execution]: where the runs are solved; the command line's --scheduler and
    --workers win."""

    scheduler: str = param("local", "a Dask cluster on this machine (local), or the "
                           "address tcp://HOST:PORT of a scheduler", "text")
    workers: int = param(0, "processes of a local cluster (0: every core)", minimum=0)
    timeout: float = param(10.0, "to reach a scheduler", "s", above=0.0)

    def check(self) -> None:
        """A scheduler named; a timeout that is a wait, not a hang."""
        if not self.scheduler:
            raise ValueError('scheduler must be "local" or an address tcp://HOST:PORT')
        if self.timeout > MAX_TIMEOUT:
            raise ValueError(f"timeout {self.timeout:g} s is longer than {MAX_TIMEOUT:g} s "
                             'a wait for a scheduler may take; write e.g. "30 s"')
