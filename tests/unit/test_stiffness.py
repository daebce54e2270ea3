"""Timoshenko and PRB stiffness against their formulas (paper eq. 9; Howell's PRB springs)."""

import numpy as np
import pytest

from exubrush.models.sections import section_properties
from exubrush.models.stiffness import (
    buckling_load,
    lever_transform,
    midpoint_stiffness,
    prb_torsional_stiffness,
    shear_parameters,
    timoshenko_cantilever_matrix,
)

E, NU, L = 7.5, 0.48, 5.0 / 6
G = E / (2 * (1 + NU))
SECTION = section_properties("rectangle", 0.6, 0.9)


def test_cantilever_matrix_entries_follow_the_formulas():
    A, Iy, Iz, J = 0.54, 0.6 * 0.9**3 / 12, 0.9 * 0.6**3 / 12, SECTION.torsion_constant
    phi_y = 12 * E * Iz / (5 / 6 * G * A * L**2)
    phi_z = 12 * E * Iy / (5 / 6 * G * A * L**2)
    K = timoshenko_cantilever_matrix(SECTION, E, G, L)
    expected = {
        (0, 0): E * A / L,
        (1, 1): 12 * E * Iz / (L**3 * (1 + phi_y)),
        (2, 2): 12 * E * Iy / (L**3 * (1 + phi_z)),
        (3, 3): G * J / L,
        (4, 4): (4 + phi_z) * E * Iy / (L * (1 + phi_z)),
        (5, 5): (4 + phi_y) * E * Iz / (L * (1 + phi_y)),
        (1, 5): -6 * E * Iz / (L**2 * (1 + phi_y)),
        (2, 4): 6 * E * Iy / (L**2 * (1 + phi_z)),
    }
    for (i, j), value in expected.items():
        assert K[i, j] == pytest.approx(value, rel=1e-13)
        assert K[j, i] == pytest.approx(value, rel=1e-13)
    others = np.ones((6, 6), bool)
    for i, j in expected:
        others[i, j] = others[j, i] = False
    assert np.all(K[others] == 0.0)
    assert np.all(np.linalg.eigvalsh(K) > 0)


def test_without_shear_the_matrix_is_euler_bernoulli():
    stiff_shear = section_properties("rectangle", 0.6, 0.9)
    phi_y, phi_z = shear_parameters(stiff_shear, E, G * 1e9, L)
    assert phi_y < 1e-8 and phi_z < 1e-8
    K = timoshenko_cantilever_matrix(stiff_shear, E, G * 1e9, L)
    Iz = stiff_shear.second_moment_z
    # Euler-Bernoulli cantilever: 12EI/L³, -6EI/L², 4EI/L (rel 1e-7: Φ ~ 1e-9 remains)
    assert K[1, 1] == pytest.approx(12 * E * Iz / L**3, rel=1e-7)
    assert K[1, 5] == pytest.approx(-6 * E * Iz / L**2, rel=1e-7)
    assert K[5, 5] == pytest.approx(4 * E * Iz / L, rel=1e-7)


def test_cantilever_matrix_reproduces_tip_deflection_under_a_tip_force():
    # Timoshenko cantilever, tip force P: v = PL³/3EI + PL/(κGA), θ = PL²/2EI
    K = timoshenko_cantilever_matrix(SECTION, E, G, L)
    P = 1e-3
    u = np.linalg.solve(K, [0, P, 0, 0, 0, 0])
    Iz = SECTION.second_moment_z
    assert u[1] == pytest.approx(P * L**3 / (3 * E * Iz) + P * L / (5 / 6 * G * 0.54), rel=1e-12)
    assert u[5] == pytest.approx(P * L**2 / (2 * E * Iz), rel=1e-12)


def test_midpoint_stiffness_is_the_congruence_transform_of_the_cantilever_matrix():
    K = timoshenko_cantilever_matrix(SECTION, E, G, L)
    T = lever_transform(L / 2)
    transformed = T.T @ K @ T
    Km = midpoint_stiffness(SECTION, E, G, L)
    np.testing.assert_allclose(transformed, Km, rtol=1e-12, atol=1e-12 * np.abs(K).max())


def test_prb_springs():
    gamma, k_theta, length = 0.8329, 2.6001, 5.0
    k = prb_torsional_stiffness(SECTION, E, G, length, gamma, k_theta)
    assert k[0] == pytest.approx(G * SECTION.torsion_constant / (gamma * length), rel=1e-14)
    assert k[1] == pytest.approx(gamma * k_theta * E * SECTION.second_moment_y / length, rel=1e-14)
    assert k[2] == pytest.approx(gamma * k_theta * E * SECTION.second_moment_z / length, rel=1e-14)


def test_buckling_load_is_eulers_clamped_free_column_about_the_weak_axis():
    # π² E I_min / (4 L²) with I_min = 0.9 · 0.6³ / 12 (bending across the 0.6 mm side)
    expected = np.pi**2 * E * (0.9 * 0.6**3 / 12) / (4 * L**2)
    assert buckling_load(SECTION, E, L) == pytest.approx(expected, rel=1e-12)
