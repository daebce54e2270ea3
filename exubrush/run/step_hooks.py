"""The hooks a scene calls before every step attempt, in named phases run in a declared order.

Exudyn calls the pre-step function before every step attempt (retries included) with t at
the end of the step it is about to try and the state at the step's start. A hook is a
callable ``(mbs, t)``; the scene (exubrush.run.scene) registers each under its phase, and
:class:`StepHooks` calls them phase by phase in the order of :data:`PHASES`, within a
phase in the order they were added. Pure: imports nothing of exubrush.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

# the phases, each with what must come before it
AFTER_CUT = "after a cut"
"""Newton's line search switched on while the step is below the largest after a cut
(exubrush.run.newton.after_step_cut): first, as it compares the step with the cap the
last step's :data:`STEP_SIZE` hooks set."""
DRIVE = "drive"
"""The handle's prescribed coordinates at the step's end (exubrush.run.scene.add_drive)."""
SURFACES = "surfaces"
"""A mesh's tangent planes under the tips, at the state the step starts from."""
FRICTION = "friction"
"""The friction's lagged drop (which reads the contacts' frames: after :data:`SURFACES`),
or the built-in contact's friction blended in."""
SAMPLING = "sampling"
"""The contacts between bristles recorded at the last converged state, with the candidate
pairs they were found with (before :data:`CANDIDATES` renews those)."""
JACOBIAN = "jacobian"
"""The step's Jacobian policy: a new one after the step size changed or while a sine pose
term acts (exubrush.run.solver)."""
STEP_SIZE = "step size"
"""The largest step for the steps to come (exubrush.run.step_policy)."""
CANDIDATES = "candidate pairs"
"""The candidate pairs of contact between bristles for the coming step attempt, sized by
its step (last: the attempt is set by then)."""

PHASES = (AFTER_CUT, DRIVE, SURFACES, FRICTION, SAMPLING, JACOBIAN, STEP_SIZE, CANDIDATES)

Hook = Callable[..., object]  # (mbs, t), its return value unused


class StepHooks:
    """The step hooks of a scene by phase; calling it calls them all in order."""

    def __init__(self) -> None:
        self._hooks: dict[str, list[Hook]] = {phase: [] for phase in PHASES}
        self._order: tuple[Hook, ...] = ()

    def add(self, phase: str, hook: Hook) -> None:
        """Run ``hook`` in ``phase`` (one of :data:`PHASES`), after the hooks already there."""
        if phase not in self._hooks:
            raise ValueError(f"step hook phase {phase!r} is none of {PHASES}")
        self._hooks[phase].append(hook)
        self._order = tuple(h for p in PHASES for h in self._hooks[p])

    def of(self, phase: str) -> tuple[Hook, ...]:
        """The hooks of ``phase``, in the order they run."""
        return tuple(self._hooks[phase])

    def __iter__(self) -> Iterator[Hook]:
        return iter(self._order)

    def __len__(self) -> int:
        return len(self._order)

    def __call__(self, mbs, t) -> bool:
        """Call every hook in order; True (go on): fit for Exudyn's pre-step user function."""
        for hook in self._order:
            hook(mbs, t)
        return True
