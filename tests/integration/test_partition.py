"""Per-bristle solves summed equal one coupled solve of the head (bristles do not touch)."""

import numpy as np

from exubrush.parameters.io import load_case
from exubrush.simulation import simulate


def test_per_bristle_and_coupled_solves_agree_in_steady_sliding():
    overrides = ["head.rows=1", "head.columns=2", "motion.periods=0.12"]
    split = simulate(load_case("orthogonal", overrides), progress=False, workers=2)
    coupled = simulate(load_case("orthogonal", [*overrides, "solver.partition='coupled'"]),
                       progress=False)
    assert split.metadata["derived"]["systems_solved"] == 2
    assert coupled.metadata["derived"]["systems_solved"] == 1
    np.testing.assert_array_equal(split.time, coupled.time)
    # away from stick-slip transitions the state is smooth and both solves take the same
    # physics; step sequences differ (a coupled system's step is set by all its bristles),
    # so agreement is to the Newton tolerance amplified by the contact stiffness: 0.2 %
    late = split.time > split.time[-1] - 0.5
    scale = np.abs(coupled.normal_force[late]).max()
    np.testing.assert_allclose(split.normal_force[late], coupled.normal_force[late],
                               atol=2e-3 * scale)
    np.testing.assert_allclose(split.tangential_force[late], coupled.tangential_force[late],
                               atol=2e-3 * scale)


def test_two_threads_solve_a_coupled_head_with_builtin_contact_as_one_does():
    overrides = ["head.rows=2", "head.columns=2", "motion.periods=0.12",
                 "solver.partition='coupled'", "contact.backend='exudyn-builtin'"]
    one = simulate(load_case("orthogonal", overrides), progress=False)
    two = simulate(load_case("orthogonal", [*overrides, "solver.threads=2"]), progress=False)
    assert two.metadata["status"] == "completed", two.metadata["message"]
    # same steps; threads only change the order of summation in the residual: round-off
    # amplified by Newton's tolerance, far below 1e-4 of the force
    scale = np.abs(one.normal_force).max()
    np.testing.assert_allclose(two.normal_force, one.normal_force, atol=1e-4 * scale)
    np.testing.assert_allclose(two.tangential_force, one.tangential_force, atol=1e-4 * scale)
