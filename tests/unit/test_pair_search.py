"""The k-d tree pair search (exubrush.util.pair_search) against a search of every pair."""

import itertools
import math

import numpy as np
import pytest

from exubrush.util.pair_search import pairs_within


def _every_pair_within(points, distance):
    """O(n²): every pair i < j at most ``distance`` apart, in itertools' (i, j) order."""
    return [(i, j) for i, j in itertools.combinations(range(len(points)), 2)
            if math.dist(points[i], points[j]) <= distance]


@pytest.mark.parametrize("dims", [2, 3])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_tree_finds_every_close_pair_once(dims, seed):
    # 300 points in a unit box, a radius that catches a few percent of the 44,850 pairs;
    # random doubles do not fall within rounding of the radius, so both searches agree
    # exactly on which pairs are in
    points = np.random.default_rng(seed).random((300, dims))
    found = pairs_within(points, 0.12)
    expected = _every_pair_within(points.tolist(), 0.12)
    assert len(expected) > 100  # the comparison has pairs to compare
    assert found.shape == (len(expected), 2)
    assert sorted(tuple(pair) for pair in found.tolist()) == expected


def test_points_exactly_the_distance_apart_are_a_pair():
    # a unit grid: neighbours at exactly 1 are in, diagonals (√2) are not
    grid = [(x, y) for x in range(3) for y in range(3)]
    assert sorted(tuple(pair) for pair in pairs_within(grid, 1.0).tolist()) == (
        _every_pair_within(grid, 1.0))
    assert len(pairs_within(grid, 1.0)) == 12


@pytest.mark.parametrize("points", [np.zeros((0, 3)), np.zeros((1, 3)), [(0.0, 0.0), (5.0, 0.0)]])
def test_fewer_than_two_points_or_none_close_give_no_pairs(points):
    found = pairs_within(points, 1.0)
    assert found.shape == (0, 2)
    assert found.dtype.kind == "i"  # usable as indices
