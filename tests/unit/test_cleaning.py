"""Cleaning metrics on synthetic tip histories whose answers are known in closed form."""

import math

import numpy as np
import pytest

from exubrush.output.cleaning import (
    cleaning_summary,
    contact_geometry,
    gap_depths,
    part_names,
    patch_radius,
    stroke_spans,
    wiped_cells,
)
from exubrush.parameters.case import Surface

TEETH = Surface(kind="tooth-row")  # w = 7, g = 1, h = 2, ρ = 0.5 mm


def test_strokes_are_cut_at_reversals_and_the_partial_ones_flagged():
    time = np.linspace(0.0, 13.0, 1301)
    slide = np.where(time < 1.0, 0.0, 15.0 * np.sin(np.pi * (time - 1.0) / 6.0))
    spans = stroke_spans(time, slide)
    # from rest to +15 (partial), +15 -> -15 (whole), -15 -> 0 cut off by the end (partial)
    assert [whole for _, _, whole in spans] == [False, True, False]
    assert time[spans[0][0]] == pytest.approx(1.0, abs=0.02)
    assert time[spans[1][0]] == pytest.approx(4.0, abs=0.02)
    assert time[spans[2][0]] == pytest.approx(10.0, abs=0.02)
    assert time[spans[1][1]] == pytest.approx(10.0, abs=0.02)


def test_patch_radius_is_the_chord_of_the_cut_sphere():
    assert patch_radius(0.4, 0.4) == 0.0
    assert patch_radius(0.4, 0.5) == 0.0
    assert patch_radius(0.4, 0.39) == pytest.approx(math.sqrt(0.8 * 0.01 - 0.0001))
    assert patch_radius(0.4, 0.0) == pytest.approx(0.4)


@pytest.mark.parametrize("grid", [0.01, 0.005])
def test_a_straight_swipe_wipes_a_stadium(grid):
    # a patch of radius a dragged a length L wipes 2aL + πa² (a stadium)
    a, length = 0.05, 3.0
    steps = 301
    points = np.zeros((steps, 1, 3))
    points[:, 0, 0] = np.linspace(0.0, length, steps) + 0.0123
    points[:, 0, 1] = 0.0371
    cells = wiped_cells(points, np.ones((steps, 1), bool), np.full((steps, 1), a), grid)
    exact = 2 * a * length + math.pi * a * a
    # cells counted by their centres: along the perimeter P cells are gained and lost at
    # random, a net error far below a quarter of a cell row (P·grid/4)
    perimeter = 2 * length + 2 * math.pi * a
    assert len(cells) * grid**2 == pytest.approx(exact, abs=0.25 * perimeter * grid)


def test_no_contact_wipes_nothing_and_separate_contacts_are_not_joined():
    points = np.zeros((3, 1, 3))
    points[:, 0, 0] = [0.0, 1.0, 2.0]
    touching = np.array([[True], [False], [True]])
    cells = wiped_cells(points, touching, np.full((3, 1), 0.001), 0.1)
    assert len(cells) == 2  # the two contact points' own cells, no path between them
    assert len(wiped_cells(points, np.zeros((3, 1), bool), np.zeros((3, 1)), 0.1)) == 0


def test_parts_of_a_tooth_row():
    # sphere centres just touching the top, the rounding, the wall and the floor
    r = 0.3
    centres = np.array([[[0.0, 0.0, r],
                         [3.0 + 0.8 * math.sin(0.7), 1.0, -0.5 + 0.8 * math.cos(0.7)],
                         [3.5 + r, 0.0, -1.2],
                         [4.0, 2.0, -2.0 + r]]])
    points, normals, distances, parts = contact_geometry(TEETH, centres, np.full(4, r))
    names = part_names(TEETH)
    assert [names[k] for k in parts[0]] == ["top", "edge", "wall", "floor"]
    np.testing.assert_allclose(distances[0], r, atol=1e-12)
    np.testing.assert_allclose(points[0, :, 2], [0.0, -0.5 + 0.5 * math.cos(0.7), -1.2, -2.0],
                               atol=1e-12)


def test_gap_depth_counts_only_tips_over_a_gap_below_the_tops():
    r = np.full(3, 0.4)
    centres = np.array([[[4.0, 0.0, -0.6],     # in gap 0, lowest point 1.0 below the tops
                         [-4.0, 0.0, 0.2],     # over gap -1 but its lowest point is 0.2 deep
                         [0.0, 0.0, 0.3]]])    # on a tooth: not in a gap
    depth, gap, inside = gap_depths(TEETH, centres, r)
    np.testing.assert_allclose(depth[0], [1.0, 0.2, 0.0])
    assert list(gap[0, :2]) == [0, -1] and list(inside[0]) == [True, True, False]


def test_summary_shares_the_force_and_measures_the_gaps():
    # two tips on the plane pressed with 2 N and 1 N along a whole stroke
    time = np.linspace(0.0, 12.0, 1201)
    slide = 10.0 * np.sin(np.pi * time / 4.0)
    n_t = len(time)
    position = np.zeros((n_t, 2, 3))
    position[:, :, 1] = slide[:, None]
    position[:, 1, 0] = 2.0
    position[:, :, 2] = 0.39
    force = np.zeros((n_t, 2, 3))
    force[:, 0, 2], force[:, 1, 2] = 2.0, 1.0
    summary = cleaning_summary(Surface(), time, slide, position, force, [0.4, 0.4], grid=0.01)
    whole = [s for s in summary["strokes"] if s["whole"]]
    assert len(whole) == 2
    for stroke in whole:
        assert stroke["force_share"] == pytest.approx([2 / 3, 1 / 3], rel=1e-9)
        assert stroke["force_share_spread"] == pytest.approx(np.std([2, 1]) / 1.5, rel=1e-9)
        assert stroke["tips_in_contact_max"] == 2
        # two 20 mm swipes of a patch of radius √(0.8·0.01 − 1e-4), to a quarter of a cell
        # row on the perimeter (as in the stadium test)
        a = math.sqrt(0.8 * 0.01 - 1e-4)
        perimeter = 2 * (2 * 20 + 2 * math.pi * a)
        assert stroke["wiped_area_mm2"] == pytest.approx(2 * (2 * a * 20 + math.pi * a * a),
                                                         abs=0.25 * perimeter * 0.01)
    assert "interdental" not in whole[0]
    assert summary["contact_time_per_part_tip_s"]["surface"] == pytest.approx(24.0, rel=1e-3)


def test_summary_refuses_a_grid_that_is_not_positive():
    with pytest.raises(ValueError, match="grid must be positive"):
        cleaning_summary(Surface(), np.zeros(2), np.zeros(2), np.zeros((2, 1, 3)),
                         np.zeros((2, 1, 3)), [0.4], grid=0.0)


def test_wiped_cells_match_a_cell_by_cell_search():
    """Isolated contacts (no two in a row, so no joining path): every cell whose centre lies
    in a patch, or that holds a patch's centre, found by testing each cell near each patch."""
    rng = np.random.default_rng(7)
    grid, steps, bristles = 0.02, 40, 3
    points = rng.uniform(-0.3, 0.3, (steps, bristles, 3))
    touching = np.zeros((steps, bristles), bool)
    touching[::2] = rng.random((steps // 2, bristles)) < 0.8
    half_width = rng.uniform(0.0, 0.09, (steps, bristles))
    expected = set()
    for t, b in zip(*np.nonzero(touching), strict=True):
        x, y, r = points[t, b, 0], points[t, b, 1], half_width[t, b]
        i0, j0 = int(np.floor(x / grid)), int(np.floor(y / grid))
        expected.add((i0, j0))
        for i in range(i0 - 8, i0 + 9):
            for j in range(j0 - 8, j0 + 9):
                if np.hypot((i + 0.5) * grid - x, (j + 0.5) * grid - y) <= r:
                    expected.add((i, j))
    found = {tuple(cell) for cell in wiped_cells(points, touching, half_width, grid).tolist()}
    assert found == expected
