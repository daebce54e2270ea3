"""Filament packing inside a tuft (exubrush.models.packing) against lattice geometry."""

import math

import numpy as np
import pytest

from exubrush.models.packing import (
    PackingError,
    filament_offsets,
    hexagonal_diameter,
    hexagonal_offsets,
    random_offsets,
)

PITCH = 0.2  # mm, a typical filament diameter


def _nearest_neighbour_distances(points):
    gaps = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=2)
    np.fill_diagonal(gaps, np.inf)
    return gaps.min(axis=1)


@pytest.mark.parametrize("rings", [0, 1, 2, 3, 4])
def test_whole_hexagonal_rings_fill_a_circle_of_2k_plus_1_pitches(rings):
    # k rings around a centre filament: 3k(k+1) + 1 filaments, the outermost k pitches out
    count = 3 * rings * (rings + 1) + 1
    offsets = hexagonal_offsets(count, PITCH)
    assert len(offsets) == count
    assert np.hypot(*offsets.T).max() == pytest.approx(rings * PITCH, rel=1e-12)
    assert hexagonal_diameter(count, PITCH) == pytest.approx((2 * rings + 1) * PITCH, rel=1e-12)


@pytest.mark.parametrize("count", [2, 7, 12, 37, 50])
def test_hexagonal_filaments_touch_and_never_overlap(count):
    offsets = hexagonal_offsets(count, PITCH)
    nearest = _nearest_neighbour_distances(offsets)
    assert nearest.min() == pytest.approx(PITCH, rel=1e-12)  # touching neighbours
    assert len(np.unique(np.round(offsets, 9), axis=0)) == count  # no filament twice


def test_hexagonal_offsets_of_a_partial_ring_are_the_points_nearest_the_centre():
    offsets = hexagonal_offsets(10, PITCH)
    radii = np.hypot(*offsets.T)
    # 1 + 6 at one pitch, then 3 of the 6 next-nearest lattice points at √3 pitches
    assert np.sort(radii)[-3:] == pytest.approx([math.sqrt(3) * PITCH] * 3, rel=1e-12)


def test_random_packing_is_seeded_inside_the_tuft_and_without_overlap():
    first = random_offsets(25, PITCH, 1.6, np.random.default_rng(4))
    again = random_offsets(25, PITCH, 1.6, np.random.default_rng(4))
    np.testing.assert_array_equal(first, again)
    assert _nearest_neighbour_distances(first).min() >= PITCH - 1e-9
    assert np.hypot(*first.T).max() + PITCH / 2 <= 0.8 + 1e-9


@pytest.mark.parametrize("count, diameter, packing, message", [
    (37, 1.3, "hexagonal", "37 filaments of 0.2 mm need a tuft of 1.4 mm in hexagonal "
     "packing, the tuft is 1.3 mm"),
    (37, 1.6, "random", "would cover 58% of a 1.6 mm tuft"),
    (1, 0.1, "random", "a filament of 0.2 mm does not fit in a tuft of 0.1 mm"),
])
def test_filaments_that_do_not_fit_are_refused_with_the_numbers(count, diameter, packing,
                                                                  message):
    with pytest.raises(PackingError, match=message):
        filament_offsets(count, PITCH, diameter, packing, np.random.default_rng(1))


def test_a_full_hexagonal_tuft_fits_exactly():
    offsets = filament_offsets(37, PITCH, 1.4, "hexagonal", np.random.default_rng(1))
    assert len(offsets) == 37
