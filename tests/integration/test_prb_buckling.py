"""The PRB bristle with the buckling link (exubrush.models.buckling) in Exudyn: pushed along
its axis it follows the exact post-buckled elastica, and brushing it leaves each reversal as
the DFM bristle does (the paper's rigid link stays pushed on the parallel case)."""

import numpy as np
import pytest

from exubrush.models.buckling import CLAMPED_PINNED_BETA
from exubrush.models.prb import axial_spring_constants
from exubrush.output.experiment import ForceSeries, stroke_flat_means
from exubrush.parameters.io import load_case
from exubrush.reference.buckled_column import clamped_pinned_load_index
from exubrush.reference.sliding import sliding_normal_force
from exubrush.run.prepared import prepare
from exubrush.simulation import simulate
from exubrush.statics import pinned_prb_push

ONE_BRISTLE = ["head.rows=1", "head.columns=1"]
REDUCED = ["solver.step_size='5 ms'"]  # the fast preset's step; flat zones agree with 2 ms
PERIODS = {"orthogonal": 2, "parallel": 1.5}  # three and two whole strokes


@pytest.fixture(scope="module")
def default_bristle():
    case = load_case("parallel", [*ONE_BRISTLE, "model.kind='prb'", "head.root_tilt='0 deg'"])
    return prepare(case).bristles[0], case.head.material


def test_a_pushed_link_is_stiff_below_buckling_and_follows_the_elastica_beyond(
        default_bristle):
    bristle, material = default_bristle
    stiffness, load = axial_spring_constants(bristle, material)
    # below buckling: the bristle's axial compliance, within the smooth minimum's shift
    shortening = pinned_prb_push(bristle, material, 0.5 * load)
    assert shortening == pytest.approx(0.5 * load / stiffness, rel=1e-2)
    for ratio in (1.05, 1.1, 1.13):  # on the buckled branch, below its peak of 1.1396
        shortening = pinned_prb_push(bristle, material, ratio * load)
        past_onset = (shortening - load / stiffness) / bristle.length
        exact = clamped_pinned_load_index(past_onset) / CLAMPED_PINNED_BETA**2 * load
        # 0.5 %: the law's fit is within 0.2 % of the exact branch, the smooth join adds
        # < 0.1 % this far past the onset, Newton's tolerance the rest
        assert ratio * load == pytest.approx(exact, rel=5e-3)
    assert past_onset > 0.3  # the link passed the shortening a snap-through needs (0.24 l)


def _later_strokes(case_name, seed, *overrides):
    case = load_case(case_name, [*ONE_BRISTLE, *REDUCED, f"motion.periods={PERIODS[case_name]}",
                                 f"head.seed={seed}", *overrides])
    results = simulate(case, progress=False, workers=1)
    means = stroke_flat_means(ForceSeries.from_results(results), 0.8)
    return np.array([m["normal_force"] for m in means[1:]])  # from the second whole stroke


@pytest.mark.slow
@pytest.mark.parametrize("case_name", ["orthogonal", "parallel"])
@pytest.mark.parametrize("seed", [1, 5, 12])
def test_prb_agrees_with_dfm_stroke_by_stroke(case_name, seed):
    dfm = _later_strokes(case_name, seed, "model.kind='dfm'", "model.segments=6")
    prb = _later_strokes(case_name, seed, "model.kind='prb'")
    assert len(prb) == len(dfm) >= 1
    # 6 %: a regression guard set above what was measured, +5.1 % to +5.2 % over these
    # seeds (orthogonal: -1.4 % to +3.1 %), not an accuracy: on the parallel case PRB's
    # dragged state is 2-4 % above the exact elastica (the fixed γ, K_Θ of Howell's table
    # at n = 1/μ_d) and DFM N = 6 1-3 % below it. The accuracy check is against the exact
    # sliding elastica below
    np.testing.assert_allclose(prb, dfm, rtol=0.06)
    if case_name == "parallel":  # bending about the weaker axis in the slide plane
        case = load_case(case_name, ONE_BRISTLE)
        bristle = prepare(case).bristles[0]
        exact = sliding_normal_force(
            case.motion.interaction_distance - bristle.tip_radius,  # root to tip centre
            case.contact.dynamic_friction, bristle.length,
            case.head.material.youngs_modulus * bristle.section.second_moment_z,
            bristle.tip_radius)
        np.testing.assert_allclose(prb, exact, rtol=0.05)


@pytest.mark.slow
def test_the_papers_rigid_link_stays_pushed_after_a_parallel_reversal():
    rigid = _later_strokes("parallel", 12, "model.kind='prb'", "model.prb_link='rigid'")
    dfm = _later_strokes("parallel", 12, "model.kind='dfm'", "model.segments=6")
    assert np.all(rigid > 3.0 * dfm)  # measured 11.6x: the jam the buckling link removes


@pytest.mark.slow
@pytest.mark.parametrize("case_name", ["orthogonal", "parallel"])
def test_the_pivot_spring_gives_the_joints_forces(case_name):
    spring = _later_strokes(case_name, 1, "model.kind='prb'", "model.prb_pivot='spring'")
    joint = _later_strokes(case_name, 1, "model.kind='prb'", "model.prb_pivot='joint'")
    assert len(spring) == len(joint) >= 1
    # 0.1 %: the spring's lateral compliance (10 EA/l) moves these strokes by 0.03-0.04 %
    # (0.01-0.02 % on four bristles at 2 ms steps; 100 EA/l: 0.003 %); without the torque
    # that puts the force on the pivot, 0.4-0.85 %; at 0.3 EA/l, 1.2 %
    np.testing.assert_allclose(spring, joint, rtol=1e-3)
