"""Pairs of points near each other, found with a k-d tree.

The tuft overlap check (parameters/case.py), the touching bristle groups
(models/geometry.py) and the contact between bristles (contact/between.py) first find the
candidate pairs this way and then test each one exactly. SciPy's spatial module takes
0.4 s to import, so it is imported where a search runs, not with this module.
"""

from __future__ import annotations

import numpy as np


def pairs_within(points, distance: float) -> np.ndarray:
    """Index pairs (k, 2) of the points (n, dims) at most ``distance`` apart (Euclidean,
    same unit as the points), each pair with i < j, in the k-d tree's order: the same for
    the same points, but sort the rows where a caller's result must not depend on the tree
    (the contact between bristles keeps it: its forces add up in this order).
    """
    from scipy.spatial import cKDTree  # 0.4 s of import: only where a search runs

    points = np.asarray(points, dtype=float)
    if len(points) < 2:
        return np.zeros((0, 2), dtype=np.intp)
    return cKDTree(points).query_pairs(distance, output_type="ndarray")
