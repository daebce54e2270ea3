"""Small vibrations of a clamped-free Euler-Bernoulli beam (pure, mm-s-N-t units).

A powered toothbrush shakes the head near 260 Hz, close to a nylon filament's first bending
frequency (~350 Hz for 0.2 mm x 10.5 mm): the bristle's inertia matters there. This module
gives the references the discrete flexible model is checked against
(tests/integration/test_filament_vibration.py).

Clamped-free modes (Rao, Vibration of Continuous Systems, 2nd ed., 2019, §11.5.3;
Blevins, Formulas for Natural Frequency and Mode Shape, 1979, table 8-1): with β_n the
roots of 1 + cos(β L) cosh(β L) = 0,

    ω_n = (β_n L)² / L² · √(EI / (ρA)),
    φ_n(x) = cosh β_n x − cos β_n x − σ_n (sinh β_n x − sin β_n x),
    σ_n = (cosh β_n L + cos β_n L) / (sinh β_n L + sin β_n L),

normalised so that ∫₀ᴸ φ_n² dx = L and φ_n(L) = ±2.

Base translation u_b(t) = U e^{iωt} normal to the beam (Clough & Penzien, Dynamics of
Structures, 2nd ed., 1993, §18-5, support excitation of a distributed system): the
relative deflection w = Σ φ_n q_n obeys q̈_n + 2ζ_n ω_n q̇_n + ω_n² q_n = −Γ_n ü_b with
the participation factor Γ_n = ∫φ_n dx / ∫φ_n² dx, so that the tip's absolute amplitude is

    |u_b + w(L)| / U = |1 + Σ Γ_n φ_n(L) r_n² / (1 − r_n² + 2iζ_n r_n)|,  r_n = ω/ω_n.

Σ Γ_n φ_n(x) = 1 (the expansion of a unit deflection), Γ_1 φ_1(L) = 1.566 and
Γ_2 φ_2(L) = −0.868. The force and the moment about the root that the base spends on the
beam are that expansion integrated along it, ∫ρA ü dx and ∫x ρA ü dx
(:func:`base_force_response`, :func:`base_moment_response`): what the head of a free
shaken filament carries.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

# β₁L, the first root of 1 + cos x cosh x = 0 (Blevins 1979, table 8-1); the unit tests
# check that it is the root
FIRST_ROOT = 1.8751040687119611
# β₂L: the second mode's frequency is (β₂/β₁)² = 6.267 times the first's
SECOND_ROOT = 4.6940911329741745


def characteristic(x: float) -> float:
    """1 + cos x cosh x, whose roots x = β_n L give the clamped-free modes [-]."""
    return 1.0 + math.cos(x) * math.cosh(x)


def mode_constant(root: float) -> float:
    """σ_n = (cosh β_nL + cos β_nL) / (sinh β_nL + sin β_nL) of the mode with β_n L = ``root``."""
    return (math.cosh(root) + math.cos(root)) / (math.sinh(root) + math.sin(root))


def mode_shape(s: ArrayLike, root: float = FIRST_ROOT) -> np.ndarray:
    """φ(s) of a clamped-free mode at the relative position s = x/L in [0, 1] [-].

    Normalised so that ∫₀¹ φ² ds = 1 and the tip value is φ(1) = ±2 (+2 for the first mode).
    """
    x = root * np.asarray(s, dtype=float)
    sigma = mode_constant(root)
    return np.cosh(x) - np.cos(x) - sigma * (np.sinh(x) - np.sin(x))


def mode_slope(s: ArrayLike, root: float = FIRST_ROOT) -> np.ndarray:
    """dφ/ds of :func:`mode_shape` at s = x/L [-]; divide by L for the slope [1/mm]."""
    x = root * np.asarray(s, dtype=float)
    sigma = mode_constant(root)
    return root * (np.sinh(x) + np.sin(x) - sigma * (np.cosh(x) - np.cos(x)))


def participation_factor(root: float = FIRST_ROOT) -> float:
    """Γ_n = ∫φ_n / ∫φ_n² of a clamped-free mode [-], in closed form 2σ_n / (β_n L).

    ∫₀ᴸ φ_n dx = 2σ_n L / (β_n L) follows from integrating the shape and using
    1 + cos β_nL cosh β_nL = 0; ∫₀ᴸ φ_n² dx = L. The unit tests check both by quadrature.
    """
    return 2.0 * mode_constant(root) / root


def first_bending_frequency(length: float, youngs_modulus: float, second_moment: float,
                            density: float, area: float) -> float:
    """First bending frequency of a clamped-free Euler-Bernoulli beam [Hz].

    f₁ = (β₁L)² / (2π L²) · √(EI / (ρA)), β₁L = 1.8751 (Blevins 1979, table 8-1). Shear and
    rotary inertia are neglected: Timoshenko's correction lowers f₁ by about
    ½ (β₁ r_g / L)² (1 + E/(κG)), r_g the section's radius of gyration, which is 2e-4 for a
    round 0.2 mm x 10.5 mm nylon filament (r_g = d/4, E/G = 2.8, κ = 0.9).

    Parameters
    ----------
    length : float
        L [mm].
    youngs_modulus : float
        E [MPa].
    second_moment : float
        I about the bending axis [mm⁴].
    density : float
        ρ [t/mm³].
    area : float
        A [mm²].
    """
    omega = FIRST_ROOT**2 / length**2 * math.sqrt(youngs_modulus * second_moment
                                                  / (density * area))
    return omega / (2.0 * math.pi)


def tip_amplification(frequency_ratio: ArrayLike, damping_ratio: float) -> np.ndarray:
    """Steady amplitude of the tip's absolute displacement over the base's amplitude [-]
    under harmonic base translation, first mode only.

    |1 + Γ₁φ₁(L) r² / (1 − r² + 2iζr)| with r = ω/ω₁, Γ₁φ₁(L) = 1.566 and ζ the first
    mode's damping ratio (Clough & Penzien 1993, §18-5; module docstring). Static limit
    (r → 0): 1, the beam moves with the base. At r = 1: √(1 + (Γ₁φ₁(L)/(2ζ))²).

    Where it holds: the modes left out respond almost statically below their own
    resonance; the second adds Γ₂φ₂(L) (r/6.267)² / (1 − (r/6.267)²), which is −0.014 at
    r = 0.8 (0.4 % of the amplification 3.7 at ζ = 0.055) and −0.024 at r = 1, but grows
    without bound as r nears the second mode's ratio 6.267 (β₂L/β₁L)². Keep r below about 2
    (:func:`stiffness_damped_tip_amplification` sums more modes). Small deflections (linear
    beam), no shear, no rotary inertia.

    Parameters
    ----------
    frequency_ratio : float or array
        r = ω/ω₁ [-], ≥ 0.
    damping_ratio : float
        ζ of the first mode [-].
    """
    r = np.asarray(frequency_ratio, dtype=float)
    gain = participation_factor() * 2.0  # Γ₁ φ₁(L), φ₁(L) = 2
    relative = gain * r**2 / (1.0 - r**2 + 2j * damping_ratio * r)
    return np.abs(1.0 + relative)


def mode_roots(modes: int) -> np.ndarray:
    """β_n L of the first ``modes`` clamped-free modes [-]: the roots of
    1 + cos x cosh x = 0, each within 0.5 of (n − ½)π (it tends to (n − ½)π as e^{-x})."""
    return np.array([brentq(characteristic, (n - 0.5) * math.pi - 0.5,
                            (n - 0.5) * math.pi + 0.5, xtol=1e-14)
                     for n in range(1, modes + 1)])


def stiffness_damped_tip_amplification(frequency_ratio: ArrayLike, damping_ratio: float,
                                       modes: int = 5) -> np.ndarray:
    """:func:`tip_amplification` summed over the first ``modes`` modes, each damped as
    stiffness-proportional damping C = τK damps it: ζ_n = ζ₁ ω_n/ω₁ [-].

    The model the DFM's base-excitation test is held to beyond the one-mode reference:
    Γ_nφ_n(L) = ±4σ_n/(β_nL) (φ_n(L) = ±2, alternating), so that the n-th term is exact
    without the cancellation of cosh and sinh in :func:`mode_shape` at high modes. Five
    modes leave out Σ_{n>5} Γ_nφ_n(L) r_n², below 1e-4 of the base amplitude for r ≤ 1.

    Parameters
    ----------
    frequency_ratio : float or array
        r = ω/ω₁ [-].
    damping_ratio : float
        ζ₁ of the first mode [-].
    modes : int
        Number of modes summed (1 gives :func:`tip_amplification`).
    """
    # Γ_n φ_n(L)
    return np.abs(_base_response(frequency_ratio, damping_ratio, modes,
                                 lambda n, root: (-1.0) ** n * 4.0 * mode_constant(root) / root))


def _base_response(frequency_ratio: ArrayLike, damping_ratio: float, modes: int,
                   gain) -> np.ndarray:
    """1 + Σ_n gain(n, β_nL) r_n² / (1 − r_n² + 2iζ_n r_n) over the first ``modes``
    stiffness-damped modes (ζ_n = ζ₁ ω_n/ω₁, r_n = r ω₁/ω_n), complex [-]: a quantity's
    response to base translation over its rigid-body value, the n-th mode weighted by its
    ``gain`` (n from 0)."""
    r = np.asarray(frequency_ratio, dtype=float)
    response = np.ones_like(r, dtype=complex)
    for n, root in enumerate(mode_roots(modes)):
        stretch = (root / FIRST_ROOT) ** 2  # ω_n / ω₁
        r_n = r / stretch
        response = response + gain(n, root) * r_n**2 / (1.0 - r_n**2
                                                        + 2j * damping_ratio * stretch * r_n)
    return response


def base_force_response(frequency_ratio: ArrayLike, damping_ratio: float,
                        modes: int = 5) -> np.ndarray:
    """The force the base spends on the beam under harmonic base translation u_b, over the
    rigid beam's m ü_b, complex [-] (its phase is the force's lead on m ü_b).

    The force is ∫₀ᴸ ρA ü dx, ü the absolute acceleration, = m ü_b (1 + Σ Γ_n² r_n² /
    (1 − r_n² + 2iζ_n r_n)): the mean of the modal expansion, as ∫φ_n dx = Γ_n L
    (:func:`participation_factor`), so it is the acceleration of the beam's centre of mass
    over the base's. Static limit 1 (Σ Γ_n² = 1). The modes are damped as
    :func:`stiffness_damped_tip_amplification` damps them, with its assumptions.

    Parameters
    ----------
    frequency_ratio : float or array
        r = ω/ω₁ [-].
    damping_ratio : float
        ζ₁ of the first mode [-].
    modes : int
        Number of modes summed.
    """
    return _base_response(frequency_ratio, damping_ratio, modes,
                          lambda n, root: participation_factor(root) ** 2)


def base_moment_response(frequency_ratio: ArrayLike, damping_ratio: float,
                         modes: int = 5) -> np.ndarray:
    """The moment about the clamped root that the base spends on the beam under harmonic
    base translation normal to it, over the rigid beam's m ü_b L/2, complex [-].

    The moment is ∫₀ᴸ x ρA ü dx = m ü_b L/2 (1 + Σ Γ_n (4/(β_nL)²) r_n² / (1 − r_n² +
    2iζ_n r_n)), as ∫₀ᴸ x φ_n dx = 2L²/(β_nL)²: the beam equation φ⁗ = β_n⁴ φ integrated
    by parts twice, with φ″ = φ‴ = 0 at the free end and φ″ = 2β_n² at the root. Static
    limit 1. Parameters and assumptions as :func:`base_force_response`.
    """
    return _base_response(frequency_ratio, damping_ratio, modes,
                          lambda n, root: participation_factor(root) * 4.0 / root**2)


def stiffness_proportional_damping_ratio(damping_time: float, frequency: float) -> float:
    """Damping ratio ζ = τω/2 of a mode of ``frequency`` [Hz] under C = τK [-].

    With C = τK, a mode of ω² = k/m has c = τk and ζ = c/(2mω) = τω/2 (Rayleigh damping
    with no mass term: Clough & Penzien 1993, §12-4). exubrush's DFM damps every
    spring-damper so (Material.damping_time), so this holds exactly for its modes.
    """
    return 0.5 * damping_time * 2.0 * math.pi * frequency
