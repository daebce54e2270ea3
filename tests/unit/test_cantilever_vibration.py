"""The clamped-free beam's vibration references (exubrush.reference.cantilever_vibration)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from exubrush.models.sections import section_properties
from exubrush.parameters.head import BUILT_IN_MATERIALS
from exubrush.reference.cantilever_vibration import (
    FIRST_ROOT,
    SECOND_ROOT,
    base_force_response,
    base_moment_response,
    characteristic,
    first_bending_frequency,
    mode_constant,
    mode_roots,
    mode_shape,
    mode_slope,
    participation_factor,
    stiffness_damped_tip_amplification,
    stiffness_proportional_damping_ratio,
    tip_amplification,
)


@pytest.mark.parametrize(("root", "bracket"), [(FIRST_ROOT, (1.0, 3.0)),
                                               (SECOND_ROOT, (4.0, 5.0))])
def test_roots_solve_the_frequency_equation(root, bracket):
    # brentq's xtol 1e-14 against constants given to 17 digits
    assert brentq(characteristic, *bracket, xtol=1e-14) == pytest.approx(root, abs=1e-12)


@pytest.mark.parametrize("root", [FIRST_ROOT, SECOND_ROOT])
def test_mode_shape_normalisation_and_boundary_conditions(root):
    # quadrature and finite differences: errors near 1e-8 on an O(1) shape
    norm, _ = quad(lambda s: mode_shape(s, root) ** 2, 0.0, 1.0, epsabs=1e-12)
    assert norm == pytest.approx(1.0, rel=1e-9)
    assert abs(float(mode_shape(1.0, root))) == pytest.approx(2.0, rel=1e-9)
    assert float(mode_shape(0.0, root)) == 0.0  # clamped: no deflection...
    assert float(mode_slope(0.0, root)) == pytest.approx(0.0, abs=1e-12)  # ... and no slope
    h = 1e-4  # free tip: no moment (φ'' = 0); central differences of the slope
    curvature = (mode_slope(1.0, root) - mode_slope(1.0 - h, root)) / h
    assert abs(float(curvature)) < 1e-3 * root**2
    # the slope is the shape's derivative
    s = np.linspace(0.1, 0.9, 9)
    difference = (mode_shape(s + 1e-6, root) - mode_shape(s - 1e-6, root)) / 2e-6
    np.testing.assert_allclose(mode_slope(s, root), difference, rtol=1e-6, atol=1e-6)


@pytest.mark.parametrize(("root", "tip_gain"), [(FIRST_ROOT, 1.566), (SECOND_ROOT, -0.868)])
def test_participation_factor_by_quadrature(root, tip_gain):
    integral, _ = quad(lambda s: mode_shape(s, root), 0.0, 1.0, epsabs=1e-12)
    square, _ = quad(lambda s: mode_shape(s, root) ** 2, 0.0, 1.0, epsabs=1e-12)
    assert participation_factor(root) == pytest.approx(integral / square, rel=1e-9)
    # Γφ(L) as the literature rounds it (Clough & Penzien: 1.566 for the first mode)
    assert participation_factor(root) * float(mode_shape(1.0, root)) == pytest.approx(
        tip_gain, abs=5e-4)


def test_static_limit_moves_with_the_base():
    # r² terms: at r = 1e-3 the relative motion is 1.566e-6 of the base's
    assert tip_amplification(1e-3, 0.05) == pytest.approx(1.0, abs=2e-6)
    assert tip_amplification(0.0, 0.05) == 1.0


@pytest.mark.parametrize("damping_ratio", [0.01, 0.02])
def test_resonance_peak(damping_ratio):
    gain = participation_factor() * 2.0
    # at r = 1 exactly: |1 + Γφ/(2iζ)| = √(1 + (Γφ/2ζ)²) (the base's unit amplitude is in
    # quadrature with the relative motion there, so it does not add 1)
    assert tip_amplification(1.0, damping_ratio) == pytest.approx(
        math.hypot(1.0, gain / (2.0 * damping_ratio)), rel=1e-12)
    # the peak over r sits within O(ζ) of r = 1 and within O(ζ) of Γφ/(2ζ)
    r = np.linspace(0.9, 1.1, 20001)
    amplification = tip_amplification(r, damping_ratio)
    assert abs(r[np.argmax(amplification)] - 1.0) < 2.0 * damping_ratio
    assert amplification.max() == pytest.approx(gain / (2.0 * damping_ratio),
                                                rel=2.0 * damping_ratio)


def test_amplification_above_resonance_falls_towards_one_minus_gain():
    # r → ∞ (first mode only): 1 − Γφ(L) = −0.566 in magnitude; the remainder is
    # Γφ(L)/r², 3e-4 of it at r = 100
    assert tip_amplification(100.0, 0.05) == pytest.approx(participation_factor() * 2 - 1,
                                                          rel=1e-3)


def test_damping_ratio_of_stiffness_proportional_damping():
    assert stiffness_proportional_damping_ratio(5e-5, 350.0) == pytest.approx(
        5e-5 * math.pi * 350.0, rel=1e-15)


def test_nylon_filament_near_350_hz():
    nylon = BUILT_IN_MATERIALS["nylon"]
    section = section_properties("circle", 0.2, 0.2)
    frequency = first_bending_frequency(10.5, nylon.youngs_modulus, section.second_moment_z,
                                        nylon.density, section.area)
    # by hand: ω = 1.8751² / 10.5² · √(2000 · 7.854e-5 / (1.06e-9 · 0.031416)) rad/s
    by_hand = 1.8751040687**2 / 10.5**2 * math.sqrt(
        2000.0 * math.pi * 0.1**4 / 4.0 / (1.06e-9 * math.pi * 0.1**2)) / (2.0 * math.pi)
    assert frequency == pytest.approx(by_hand, rel=1e-9)
    assert 340.0 < frequency < 360.0  # the "near 350 Hz"


def test_mode_roots():
    roots = mode_roots(6)
    assert roots[:2] == pytest.approx([FIRST_ROOT, SECOND_ROOT], abs=1e-12)
    # each a root, and they tend to (n - 1/2)π (within 1e-4 from the fourth on)
    assert all(abs(characteristic(x)) < 1e-12 * math.cosh(x) for x in roots)
    assert roots[3:] == pytest.approx((np.arange(4, 7) - 0.5) * math.pi, abs=1e-4)


def test_participation_at_the_tip_by_quadrature_for_higher_modes():
    # the closed form ±4σ/βL that the sum uses, against quadrature of the shape (modes 1-4;
    # quadrature of the shape loses digits to cosh - sinh cancellation above that)
    for n, root in enumerate(mode_roots(4)):
        integral, _ = quad(lambda s, b=root: mode_shape(s, b), 0.0, 1.0, epsabs=1e-12)
        tip = float(mode_shape(1.0, root))
        assert tip == pytest.approx(2.0 * (-1.0) ** n, rel=1e-8)
        assert integral * tip == pytest.approx((-1.0) ** n * 4.0 * mode_constant(root) / root,
                                               rel=1e-8)


def test_mode_sum():
    r = np.array([0.0, 0.3, 0.8, 1.0, 2.0])
    # one mode: the one-mode reference exactly
    np.testing.assert_allclose(stiffness_damped_tip_amplification(r, 0.05, modes=1),
                               tip_amplification(r, 0.05), rtol=1e-14)
    # the mode sum's static limit: Σ Γ_n φ_n(L) → 1, so the slow part of the relative
    # motion, Σ Γ_n φ_n(L) r_n², has r² times Σ Γ_n φ_n(L)/(ω_n/ω₁)², and the amplification
    # approaches 1 from above as r → 0 (4e-6 at r = 1e-3)
    assert stiffness_damped_tip_amplification(1e-3, 0.05) == pytest.approx(1.0, abs=4e-6)
    # five against two modes: < 0.05 % for r <= 1 (modes 3-5 respond statically there)
    two = stiffness_damped_tip_amplification(r, 0.05, modes=2)
    five = stiffness_damped_tip_amplification(r, 0.05, modes=5)
    np.testing.assert_allclose(five[:4], two[:4], rtol=5e-4)
    # the second mode's share well below its resonance: quasi-static, Γ₂φ₂(L) r₂² with
    # Γ₂φ₂(L) = -0.868 and r₂ = r/6.267, added to the first mode's response (projected on
    # its phase): -0.17 % at r = 0.3, -0.37 % at r = 0.5; 2 % for the neglected r₂⁴ terms
    # and the second mode's damping
    low = np.array([0.3, 0.5])
    first = 1.0 + 1.566 * low**2 / (1.0 - low**2 + 0.1j * low)
    share = -0.868 * (low / 6.267) ** 2 * np.real(first) / np.abs(first) ** 2
    np.testing.assert_allclose(
        stiffness_damped_tip_amplification(low, 0.05, modes=2) / tip_amplification(low, 0.05)
        - 1.0, share, rtol=0.02)


def test_the_head_s_force_and_moment_are_the_deflection_integrated_along_the_beam():
    # base_force_response and base_moment_response in closed form (∫φ_n = Γ_n L,
    # ∫x φ_n = 2L²/(β_nL)²) against quadrature of the five-mode deflection field
    # 1 + Σ Γ_n φ_n(s) r_n² H_n (the field whose tip value the tip amplification is), with
    # and without the lever s; quadrature of the shapes keeps ~1e-9 up to the fifth mode
    zeta = 0.05
    roots = mode_roots(5)
    for r in (0.3, 0.8, 1.0, 2.0):
        terms = [participation_factor(b) * ((r / (b / FIRST_ROOT) ** 2) ** 2)
                 / (1.0 - (r / (b / FIRST_ROOT) ** 2) ** 2
                    + 2j * zeta * (b / FIRST_ROOT) ** 2 * r / (b / FIRST_ROOT) ** 2)
                 for b in roots]

        def field(s, lever, part, terms=terms):
            value = 1.0 + sum(t * mode_shape(s, b) for t, b in zip(terms, roots, strict=True))
            return float(getattr(value * s**lever, part))

        for lever, response, scale in ((0, base_force_response, 1.0),
                                       (1, base_moment_response, 0.5)):
            integral = complex(*(quad(field, 0.0, 1.0, args=(lever, part), epsabs=1e-12)[0]
                                 for part in ("real", "imag")))
            assert complex(response(r, zeta)) * scale == pytest.approx(integral, rel=1e-8)


def test_the_head_s_force_and_moment_are_the_rigid_beam_s_when_slow():
    # r → 0: the beam moves with the base, m ü_b and m ü_b L/2; the r² terms at r = 1e-3
    # are Σ Γ_n² / (ω_n/ω₁)² r² ~ 0.6e-6 (moment 0.9e-6)
    assert base_force_response(0.0, 0.05) == 1.0
    assert base_moment_response(0.0, 0.05) == 1.0
    assert abs(base_force_response(1e-3, 0.05) - 1.0) < 1e-6
    assert abs(base_moment_response(1e-3, 0.05) - 1.0) < 2e-6
    # and the modes' weights add up to the rigid beam's: Σ Γ_n² = 1 and Σ Γ_n 4/(β_nL)² = 1
    # (the series of a unit deflection and of s integrated); Γ_n → 2/β_nL, β_nL → (n - ½)π,
    # so the tails beyond 200 modes are 4/(π² 200) = 2e-3 and 8/(2π³ 200²) = 3.2e-6
    roots = mode_roots(200)
    gamma = 2.0 * np.array([mode_constant(b) for b in roots]) / roots
    assert 1.0 - np.sum(gamma**2) == pytest.approx(2e-3, rel=0.05)
    assert 1.0 - np.sum(gamma * 4.0 / roots**2) == pytest.approx(3.2e-6, rel=0.05)
