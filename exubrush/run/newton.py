"""A backtracking line search inside Exudyn's Newton iterations.

Exudyn's implicit solver takes Newton's full update at every iteration. Where a stiff
contact or the steep stretch of a regularised friction law lies between an iterate and the
solution, the full update overshoots: a light tip's slip swings across the friction's band
and back, a filament jumps through its neighbour, and the iterations stall or diverge until
the step is cut (docs/decisions/0001-newton-line-search.md). A line search keeps Newton's
direction and shortens the update until the residual falls.

How it sits in Exudyn. After each update Exudyn calls the system's pre-Newton-residual user
function, then evaluates the residual. There, :class:`LineSearch` evaluates the residual
at the updated state itself (``ComputeNewtonResidual``) and, where it has not fallen below
(1 − c·α) of the last iterate's (Armijo's condition on the residual norm), moves the state
back along the update: α = 1/2, 1/4, ... down to :data:`SHORTEST`, keeping the best it
found where none is sufficient. With Euler-parameter and Tait-Bryan nodes, generalized-α's
update is linear in Newton's increment Δ (q −= Δ, q_t −= γ'Δ, q_tt −= β'Δ, λ −= Δλ·s), so
the state at α·Δ is exactly the last iterate plus α times (full update − last iterate);
Exudyn's next update starts from whatever state it finds. Lie-group nodes (rotation
vectors) keep their own copy of the update and compose rotations: the blend would not be
what Exudyn continues from, so the search is not run on them (:func:`has_lie_group_nodes`).

Exudyn restarts a modified Newton that diverges: it resets the state to the predictor with
a zero increment and calls the same function; a zero increment marks that call, which then
only records the state.

Giving up a hopeless attempt. In a group of touching filaments, an attempt whose residual
is still above a tenth of its first after two updates seldom converges within Exudyn's
iterations. Replayed on a 19-filament tuft's window, that rule would have stopped 121 of
the 4,775 attempts that converged, and saved 2,056 of the 4,620 iterations spent by the
385 that failed, each after all 12 iterations and 9 Jacobians (docs/decisions/0026).
:class:`LineSearch` with ``give_up`` > 0 stops Newton there (Exudyn's ``conv.stopNewton``),
so that the step is cut at once, unless it is at its minimum already (Exudyn cuts
no further there: the run would stop). Exudyn restarts an attempt from its predictor
after a diverged iterate, which puts its residual back at its first: from the third
iteration on, such an attempt is given up at the restart.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import exudyn as exu
import numpy as np

# Armijo's sufficient decrease: the residual must fall by this share of α times its size
SUFFICIENT_DECREASE = 1e-4
# the shortest update tried (six halvings); below it the best trial is kept
SHORTEST = 1.0 / 64.0
# the Newton iteration from which an attempt may be given up (LineSearch.give_up): its
# residual is then the one after two updates
GIVE_UP_FROM = 3


def backtrack(residual_at, last: float, full: float,
              sufficient: float = SUFFICIENT_DECREASE, shortest: float = SHORTEST):
    """Step length α of a backtracking line search on a residual norm.

    Parameters
    ----------
    residual_at : callable
        α -> residual norm at the last iterate plus α times the full update; called for
        α = 1/2, 1/4, ... only (the full update's is ``full``). It must leave the state at
        the α it was last called with.
    last, full : float
        Residual norms at the last iterate and after the full update.

    Returns
    -------
    alpha : float
        1 if the full update is sufficient, else the first halving that is, else the one
        with the smallest residual (1 included).
    best_residual : float
        The residual at the returned α.
    trials : int
        How many shorter updates were evaluated.
    """
    alpha, residual = 1.0, full
    best = (full if not math.isnan(full) else math.inf, 1.0)  # a nan is never the best
    trials = 0
    while not residual <= (1.0 - sufficient * alpha) * last and alpha > shortest:
        alpha *= 0.5
        residual = residual_at(alpha)
        trials += 1
        if residual < best[0]:
            best = (residual, alpha)
    if residual <= (1.0 - sufficient * alpha) * last:
        return alpha, residual, trials
    return best[1], best[0], trials


@dataclass
class LineSearchCounts:
    """What a line search did in a solve: iterations checked, iterations whose update was
    shortened, residuals evaluated for shorter updates, checks where no shorter update
    was sufficient (the best was kept), and step attempts given up."""

    checked: int = 0
    shortened: int = 0
    trials: int = 0
    insufficient: int = 0
    given_up: int = 0


class LineSearch:
    """Exudyn pre-Newton-residual user function (mbs, t, newton_iteration,
    discontinuous_iteration) that shortens Newton's updates (module docstring).

    It reads the solver from ``mbs.sys["dynamicSolver"]`` and its settings from
    ``mbs.sys["simulationSettings"]``, which ``SolveDynamic(..., storeSolver=True)`` sets.
    ``give_up`` > 0: from iteration :data:`GIVE_UP_FROM` on, an attempt whose residual is
    above this share of its first is given up (module docstring); 0: never.
    """

    def __init__(self, sufficient: float = SUFFICIENT_DECREASE, shortest: float = SHORTEST,
                 give_up: float = 0.0):
        self.sufficient = sufficient
        self.shortest = shortest
        self.give_up = give_up
        self.counts = LineSearchCounts()
        self._last = None  # the state of the last iterate (q, q_t, q_tt, λ)
        self._first = math.inf  # the attempt's first residual (after its predictor)

    @staticmethod
    def _state(data) -> tuple[np.ndarray, ...]:
        current = exu.ConfigurationType.Current
        return (np.array(data.GetODE2Coordinates(current)),
                np.array(data.GetODE2Coordinates_t(current)),
                np.array(data.GetODE2Coordinates_tt(current)),
                np.array(data.GetAECoordinates(current)))

    @staticmethod
    def _set_state(data, state) -> None:
        current = exu.ConfigurationType.Current
        data.SetODE2Coordinates(state[0], current)
        data.SetODE2Coordinates_t(state[1], current)
        data.SetODE2Coordinates_tt(state[2], current)
        data.SetAECoordinates(state[3], current)

    def __call__(self, mbs, t, newton_iteration, discontinuous_iteration) -> None:
        data = mbs.systemData
        solver = mbs.sys["dynamicSolver"]
        if newton_iteration == 1:  # Exudyn's residual is still the predictor's
            self._first = solver.conv.residual
        elif (self.give_up > 0.0 and newton_iteration >= GIVE_UP_FROM
              and solver.conv.residual > self.give_up * self._first
              and solver.it.currentStepSize > solver.it.minStepSize):
            solver.conv.stopNewton = True
            self.counts.given_up += 1
            return
        # the predictor, also after a restart (a zero increment)
        if newton_iteration == 0 or self._last is None or not solver.GetNewtonSolution().any():
            self._last = self._state(data)
            return
        settings = mbs.sys["simulationSettings"]
        last, full = self._last, self._state(data)
        last_residual = solver.conv.residual
        self.counts.checked += 1
        full_residual = solver.ComputeNewtonResidual(mbs, settings)

        at = [1.0]  # the α whose state the system holds

        def residual_at(alpha):
            self._set_state(data, tuple(a + alpha * (b - a) for a, b in zip(last, full,
                                                                            strict=True)))
            at[0] = alpha
            return solver.ComputeNewtonResidual(mbs, settings)

        alpha, residual, trials = backtrack(residual_at, last_residual, full_residual,
                                            self.sufficient, self.shortest)
        self.counts.trials += trials
        if alpha < 1.0:
            self.counts.shortened += 1
            if not residual <= (1.0 - self.sufficient * alpha) * last_residual:
                self.counts.insufficient += 1
            if at[0] != alpha:  # the best of the trials was not the last
                residual_at(alpha)
            self._last = self._state(data)
        else:
            if at[0] != 1.0:  # a shorter trial was evaluated last: back to the full update
                self._set_state(data, full)
            self._last = full


def has_lie_group_nodes(mbs) -> bool:
    """Whether the assembled system ``mbs`` has a node whose rotation Exudyn updates on the
    Lie group (e.g. RigidBodyRotVecLG), where a shortened update is not what it continues
    from."""
    return any(mbs.GetNode(number)["nodeType"].endswith("LG")
               for number in range(mbs.systemData.NumberOfNodes()))


def after_step_cut(search: LineSearch, margin: float = 0.99):
    """Pre-step hook (mbs, t) that runs ``search`` in Newton only while the step is below
    the solver's largest step (after a cut, until it has grown back), where Newton had
    failed; elsewhere a step's one or two iterations are left without its Python cost.

    The step is read from the solver's iteration record, kept between calls (a live view:
    reading it through the solver each time cost as much as the rest of the hook)."""
    active = [False]
    solver_record = [None, None]  # the solver and its iteration record

    def switch(mbs, t):
        solver = mbs.sys.get("dynamicSolver")
        if solver is None:
            return
        if solver is not solver_record[0]:
            solver_record[:] = [solver, solver.it]
        record = solver_record[1]
        on = record.currentStepSize < margin * record.maxStepSize
        if on != active[0]:
            mbs.SetPreNewtonResidualUserFunction(search if on else 0)
            active[0] = on

    return switch
