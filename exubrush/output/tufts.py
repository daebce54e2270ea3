"""Each tuft's force on the surface (pure; N): the sum over its filaments' tips of the
force they put on the surface, the negative of the surface's contact force on them
(tips.npz), in the surface frame. The filaments' own inertia is not in it, so the tufts
add up to the head's force less that (a few per mille in slow brushing)."""

from __future__ import annotations

import numpy as np


def tuft_forces(tip_force: np.ndarray, tuft_of_tip: list[int | None],
                tufts: int) -> np.ndarray:
    """Force of each tuft on the surface [N], (n, tufts, 3).

    Parameters
    ----------
    tip_force : (n, tips, 3) array
        The surface's contact force on each tip [N].
    tuft_of_tip : list
        The tuft index of each tip (None: not in a tuft, left out).
    tufts : int
        Number of tufts.
    """
    forces = np.zeros((tip_force.shape[0], tufts, 3))
    for tip, tuft in enumerate(tuft_of_tip):
        if tuft is not None:
            forces[:, tuft] -= tip_force[:, tip]
    return forces


def tuft_columns(names: list[str], time: np.ndarray, forces: np.ndarray) -> dict:
    """tufts.csv's columns by header: ``time [s]``, then ``NAME.force_x [N]``, ``_y``,
    ``_z`` for each tuft (its name, or ``tufts[i]``)."""
    columns = {"time [s]": time}
    for k, name in enumerate(names):
        for axis, label in enumerate("xyz"):
            columns[f"{name}.force_{label} [N]"] = forces[:, k, axis]
    return columns
