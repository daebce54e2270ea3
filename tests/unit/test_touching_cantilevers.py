"""The planar reference of two touching cantilevers (exubrush.reference.touching_cantilevers)
against beam theory, the single elastica and its own refinement."""

import numpy as np
import pytest

from exubrush.reference.elastica import solve_cantilever
from exubrush.reference.touching_cantilevers import _closest_on_chain, touching_cantilevers

L, R, GAP, EI = 10.0, 0.1, 0.01, 0.157  # mm, mm, mm, N·mm²: 0.2 mm nylon filaments
FLEXIBILITY = L**3 / (3.0 * EI)


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_below_the_closing_load_the_second_beam_carries_nothing():
    load = 0.5 * GAP / FLEXIBILITY
    pair = touching_cantilevers(L, GAP, R, EI, load, segments=50)
    np.testing.assert_array_equal(pair.contact_force, 0.0)
    # upright but for the optimiser's rounding (1e-9 mm against deflections of 0.1 mm)
    np.testing.assert_allclose(pair.second[:, 0], 2 * R + GAP, rtol=0, atol=1e-9)
    # the first bends as a single cantilever; the chain's midpoint rule errs by O(1/n²)
    assert pair.tips[0, 0] == pytest.approx(load * FLEXIBILITY, rel=1e-3)


@pytest.mark.parametrize("load", [1.5e-4, 3e-4])
@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_small_loads_follow_beam_theory(load):
    # (P − F) f − F f = gap; the deflections are 1.6-3 % of L, so beam theory's error is of
    # the order of their square (< 0.1 %): tolerance 0.5 %
    pair = touching_cantilevers(L, GAP, R, EI, load, segments=50)
    contact = (load - GAP / FLEXIBILITY) / 2.0
    assert pair.contact_force[0] == pytest.approx(contact, rel=5e-3)
    assert pair.tips[0, 0] == pytest.approx((load - contact) * FLEXIBILITY, rel=5e-3)
    assert pair.tips[1, 0] - (2 * R + GAP) == pytest.approx(contact * FLEXIBILITY, rel=5e-3)


@pytest.mark.slow  # about 20 s: fine chain and the elastica's shooting
def test_the_second_beam_is_the_exact_elastica_of_its_contact_force():
    # large deflection (10 % of L), touching at the first one's tip only: the second beam
    # up to the point the tip presses on is a cantilever under the contact force alone,
    # whose exact elastica (exubrush.reference.elastica, an ODE solution) must pass there
    pair = touching_cantilevers(L, GAP, R, EI, 1e-3)
    segment, u, contact = (found[0] for found in _closest_on_chain(pair.first[-1:],
                                                                    pair.second))
    assert np.linalg.norm(pair.first[-1] - contact) == pytest.approx(2 * R, rel=1e-9)
    bars = np.linalg.norm(np.diff(pair.second, axis=0), axis=1)
    free = bars[:segment].sum() + u * bars[segment]  # arc length to the contact [mm]
    force = pair.contact_force
    # elastica axis +x = the beam's upright axis (z); its +y = our +x
    exact = solve_cantilever(np.linalg.norm(force) * free**2 / EI,
                             np.arctan2(force[0], force[1]))
    tip = np.array([exact.tip_x, exact.tip_y]) * free  # (along the axis, across) [mm]
    # 0.2 % / 0.02 %: the chain's 100 springs against the exact ODE solution
    assert contact[0] - (2 * R + GAP) == pytest.approx(tip[1], rel=2e-3)
    assert contact[1] == pytest.approx(tip[0], rel=2e-4)


@pytest.mark.slow  # about 9 s: three chains
def test_refining_the_chain_changes_the_answer_by_its_order():
    # 4 mN: touching along the length; errors of order 1/n² in the shape (a quarter from
    # 50 to 100 springs), the distributed contact force converges more slowly (measured:
    # 0.1 % between 50 and 100)
    coarse, fine = (touching_cantilevers(L, GAP, R, EI, 4e-3, segments=n, load_steps=5)
                    for n in (50, 100))
    assert np.abs(coarse.tips - fine.tips).max() < 1e-4 * L
    np.testing.assert_allclose(coarse.contact_force, fine.contact_force, rtol=2e-3)
