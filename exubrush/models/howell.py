"""Howell's pseudo-rigid-body parameters γ(n) and K_Θ(n) for a tip-loaded cantilever.

n = F_n / F_t is the ratio of the axial (compressive for n > 0) to the transverse part of
the tip load. The table is Howell's (Compliant Mechanisms, Wiley 2001, table 5.1), as
reproduced in the paper's table 1. For a tip sliding on a plane with Coulomb friction μ,
n = 1/μ.
"""

from __future__ import annotations

import numpy as np

# n, γ, K_Θ (Howell 2001, table 5.1; the paper's table 1)
HOWELL_TABLE = np.array(
    [
        [0.0, 0.8517, 2.67617],
        [0.5, 0.8430, 2.63744],
        [1.0, 0.8360, 2.61259],
        [1.5, 0.8311, 2.59289],
        [2.0, 0.8276, 2.59707],
        [3.0, 0.8232, 2.56737],
        [4.0, 0.8207, 2.56506],
        [5.0, 0.8192, 2.56251],
        [7.5, 0.8168, 2.55984],
        [10.0, 0.8156, 2.56597],
    ]
)


def howell_parameters(load_ratio: float) -> tuple[float, float]:
    """Interpolate (γ, K_Θ) linearly in Howell's table at n = ``load_ratio``.

    Raises
    ------
    ValueError
        If n lies outside the table's range [0, 10]: extrapolating a fitted table is not
        safe, so the caller must set γ and K_Θ explicitly there.
    """
    n_min, n_max = HOWELL_TABLE[0, 0], HOWELL_TABLE[-1, 0]
    if not n_min <= load_ratio <= n_max:
        raise ValueError(
            f"load ratio n = {load_ratio:g} is outside Howell's table [{n_min:g}, {n_max:g}]; "
            "set the PRB gamma and stiffness coefficient explicitly"
        )
    gamma = float(np.interp(load_ratio, HOWELL_TABLE[:, 0], HOWELL_TABLE[:, 1]))
    k_theta = float(np.interp(load_ratio, HOWELL_TABLE[:, 0], HOWELL_TABLE[:, 2]))
    return gamma, k_theta
