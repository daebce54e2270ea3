"""The imperfections of a real head (docs/model.md, "Imperfections of a real head"): drawn
per bristle from head.seed, zero by default (the ideal head), recorded in run.json, and the
approach and force bound of a misaligned head worked out by hand."""

import math

import numpy as np
import pytest

from exubrush.models.geometry import UPRIGHT_FRAME, head_bristles, imperfections, rotation_about
from exubrush.output.assemble import imperfection_record
from exubrush.parameters.head import Head, Tuft
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare

IMPERFECT = dict(tilt_spread_x=math.radians(2.0), tilt_spread_y=math.radians(1.0),
                 length_spread=0.04, root_jitter=0.1, misalign_x=math.radians(0.5),
                 misalign_y=math.radians(-1.0))


def _arrays(bristles):
    return (np.array([b.root for b in bristles]), np.array([b.frame for b in bristles]),
            np.array([b.length for b in bristles]))


def test_the_same_seed_draws_the_same_head_and_another_seed_another():
    head = Head().replace(**IMPERFECT)
    first, again = _arrays(head_bristles(head)), _arrays(head_bristles(head))
    other = _arrays(head_bristles(head.replace(seed=2)))
    for a, b, c in zip(first, again, other, strict=True):
        assert np.array_equal(a, b)
        assert not np.allclose(a, c)


def test_zero_spreads_are_todays_head():
    # the head of 0.17.0 written out by hand: grid roots on Z = 0, upright frames turned by
    # root_tilt about a horizontal axis at the seed's uniform directions, one per bristle
    head = Head()
    assert not head.imperfect
    directions = np.random.default_rng(head.seed).uniform(0.0, 2.0 * np.pi, head.count)
    roots, frames, lengths = _arrays(head_bristles(head))
    k = 0
    for i in range(head.rows):
        for j in range(head.columns):
            x = (j - (head.columns - 1) / 2.0) * head.pitch_along
            y = (i - (head.rows - 1) / 2.0) * head.pitch_across
            assert np.array_equal(roots[k], [x, y, 0.0])
            axis = [np.cos(directions[k]), np.sin(directions[k]), 0.0]
            # the entry's own tilts (0) turn by exact identities first, as the code does
            assert np.array_equal(frames[k], rotation_about(axis, head.root_tilt)
                                  @ rotation_about([1.0, 0.0, 0.0], 0.0)
                                  @ rotation_about([0.0, 1.0, 0.0], 0.0) @ UPRIGHT_FRAME)
            k += 1
    assert np.array_equal(lengths, np.full(head.count, head.bristle.length))


def test_one_imperfection_leaves_the_others_draws_alone():
    # each quantity has its own stream: a length spread changes no frame or root, and the
    # root tilts' directions stay those of the ideal head
    ideal = _arrays(head_bristles(Head()))
    longer = _arrays(head_bristles(Head(length_spread=0.05)))
    assert np.array_equal(ideal[0], longer[0]) and np.array_equal(ideal[1], longer[1])
    assert not np.array_equal(ideal[2], longer[2])
    # twice the spread, twice the deviations (the same unit draws)
    once = imperfections(Head(length_spread=0.01), [None] * 48).length_factor - 1.0
    twice = imperfections(Head(length_spread=0.02), [None] * 48).length_factor - 1.0
    assert np.allclose(twice, 2.0 * once, rtol=1e-12, atol=0.0)


def test_the_draws_are_uniform_within_the_spreads():
    # n = 10,000 draws of U(-a, a): mean 0 with standard error a/√(3n) = 0.0058 a, variance
    # a²/3 with standard error a² √(4/45)/√n = 0.0089 of a²/3 relative; 5 standard errors
    # each (a false alarm once in 1.7 million runs); the largest |u| is within 0.1 % of a
    # unless all 10,000 fall short (0.999^10000 = 4.5e-5 per quantity)
    n = 10_000
    head = Head(**{**IMPERFECT, "misalign_x": 0.0, "misalign_y": 0.0})
    drawn = imperfections(head, [None] * n)
    samples = {
        "tilt_x": (drawn.tilt_x, head.tilt_spread_x),
        "tilt_y": (drawn.tilt_y, head.tilt_spread_y),
        "length": (drawn.length_factor - 1.0, head.length_spread),
        "x": (drawn.offset[:, 0], head.root_jitter),
        "y": (drawn.offset[:, 1], head.root_jitter),
    }
    for name, (values, a) in samples.items():
        assert abs(values.mean()) < 5.0 * a / math.sqrt(3.0 * n), name
        variance = values.var()
        assert abs(variance / (a * a / 3.0) - 1.0) < 5.0 * math.sqrt(4.0 / 45.0) * 3.0 / math.sqrt(
            n), name
        assert 0.999 * a < np.abs(values).max() <= a, name
    # the streams are independent: correlations within 5/√n
    stacked = np.array([values for values, _ in samples.values()])
    correlations = np.corrcoef(stacked)[np.triu_indices(len(samples), 1)]
    assert np.abs(correlations).max() < 5.0 / math.sqrt(n)


def test_the_drawn_values_are_applied_to_the_bristles():
    head = Head(**{**IMPERFECT, "root_tilt": 0.0, "misalign_x": 0.0, "misalign_y": 0.0})
    drawn = imperfections(head, [None] * head.count)
    roots, frames, lengths = _arrays(head_bristles(head))
    ideal = _arrays(head_bristles(head.replace(tilt_spread_x=0.0, tilt_spread_y=0.0,
                                               length_spread=0.0, root_jitter=0.0)))
    assert np.allclose(roots[:, :2] - ideal[0][:, :2], drawn.offset, rtol=0.0, atol=1e-15)
    assert np.allclose(lengths / ideal[2], drawn.length_factor, rtol=1e-15, atol=0.0)
    # the bristle axis -Z turned about y by tilt_y, then about the head's x by tilt_x
    tx, ty = drawn.tilt_x, drawn.tilt_y
    axis = np.column_stack([-np.sin(ty), np.sin(tx) * np.cos(ty), -np.cos(tx) * np.cos(ty)])
    assert np.allclose(frames[:, :, 0], axis, rtol=0.0, atol=1e-15)


def test_a_tuft_tilts_as_one_and_its_filaments_vary_in_length():
    tufts = (Tuft(x=0.0, filaments=7), Tuft(x=3.0, filaments=7))
    head = Head(layout="tufts", tufts=tufts, root_tilt=0.0, tilt_spread_x=math.radians(3.0),
                length_spread=0.02)
    _, frames, lengths = _arrays(head_bristles(head))
    axes = frames[:, :, 0]
    assert np.array_equal(axes[:7], np.repeat(axes[:1], 7, axis=0))
    assert np.array_equal(axes[7:], np.repeat(axes[7:8], 7, axis=0))
    assert not np.array_equal(axes[0], axes[7])
    assert len(set(lengths.tolist())) == 14


def test_a_misaligned_head_starts_with_its_lowest_tip_at_the_clearance_and_bounds_by_hand():
    # two upright bristles at x = ±0.9 mm, the head turned 2° about y: a point (x, 0, z)
    # goes to (x cos θ + z sin θ, 0, -x sin θ + z cos θ); the root at +0.9 sinks by
    # 0.9 sin θ, the tip below it stands 0.9 sin θ + l cos θ + r under the roots' level
    theta = math.radians(2.0)
    case = load_case("orthogonal", ["head.rows=1", "head.columns=2", "head.root_tilt='0 deg'",
                                    "head.misalign_y='2 deg'", "motion.periods=0.1"])
    prepared = prepare(case)
    length, r = case.head.bristle.length, case.head.bristle.tip_radius
    lowest_tip = 0.9 * math.sin(theta) + length * math.cos(theta) + r
    assert prepared.start_height == pytest.approx(case.motion.approach_clearance + lowest_tip,
                                                  rel=1e-14)
    # each bristle straight and fully compressed: δ = l + r - (d + its root's height)
    d, area = case.motion.interaction_distance, 0.6 * 0.9
    heights = [0.9 * math.sin(theta), -0.9 * math.sin(theta)]  # roots at x = -0.9, +0.9
    expected = [7.5 * area * (length + r - d - h) / length for h in heights]
    assert prepared.force_limits == pytest.approx(expected, rel=1e-14)


def test_run_json_records_the_drawn_values():
    case = load_case("orthogonal", ["head.rows=2", "head.columns=3", "head.length_spread=0.03",
                                    "head.tilt_spread_x='1 deg'", "head.root_jitter='0.05 mm'",
                                    "head.misalign_x='0.5 deg'", "motion.periods=0.1"])
    prepared = prepare(case)
    record = imperfection_record(prepared)
    drawn = imperfections(case.head, [None] * 6)
    assert record["tilt_x_deg"] == pytest.approx(np.degrees(drawn.tilt_x), abs=5e-7)
    assert record["tilt_y_deg"] == [0.0] * 6
    assert record["length_mm"] == pytest.approx(5.0 * drawn.length_factor, abs=5e-7)
    assert np.asarray(record["root_offset_mm"]) == pytest.approx(drawn.offset, abs=5e-7)
    assert record["misalignment_deg"] == [0.5, 0.0]
    assert record["seed"] == 1


def test_each_root_is_as_far_from_the_plane_as_its_own_height_allows():
    # without pose terms the head only descends to d: a root at height z stands d + z above
    # the plane; with them, at most the roots' closest approach (any root may be turned
    # lowest), here 3 mm
    from types import SimpleNamespace

    from exubrush.world.clearance import root_distances

    case = load_case("orthogonal")
    d = case.motion.interaction_distance
    roots = np.array([[0.0, 0.0, 0.0], [9.9, 0.0, -0.3], [-9.9, 0.0, 0.3]])
    still = root_distances(case, roots, SimpleNamespace(pose=None), closest=d)
    assert still.tolist() == [d, d - 0.3, d + 0.3]
    posed = root_distances(case, roots, SimpleNamespace(pose=object()), closest=3.0)
    assert posed.tolist() == [3.0, 3.0, 3.0]
