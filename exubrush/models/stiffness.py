"""Lumped stiffness of the bristle models (pure functions, mm-N units).

Discrete flexible model (DFM)
    The Timoshenko matrix of a cantilever segment of length L (the paper's eq. 9 with its
    two I_xy misprints corrected) relates the end's displacement and rotation,
    measured in the frame of the clamped start, to the end force and moment. exubrush puts
    the spring of each segment at the segment's *midpoint*, with both connector frames there,
    so the connector is symmetric in its two bodies. Moving the matrix to the midpoint
    (a congruence transform with the rigid lever L/2) removes the shear-bending coupling
    exactly: what remains is diagonal, with a bending-plus-shear translational stiffness
    12EI/(L³(1+Φ)) and a rotational stiffness EI/L. Both forms hold the same strain energy
    for any small relative motion; ``midpoint_stiffness`` is tested against that transform.

Pseudo-rigid-body model (PRB)
    Three torsional springs at the characteristic pivot (Howell 2001, ch. 5): k_x = GJ/(γl),
    k_y = γK_Θ·EI_y/l, k_z = γK_Θ·EI_z/l.
"""

from __future__ import annotations

import numpy as np

from exubrush.models.sections import SectionProperties


def shear_parameters(
    section: SectionProperties, youngs_modulus: float, shear_modulus: float, length: float
) -> tuple[float, float]:
    """Timoshenko shear parameters (Φ_y, Φ_z) of a segment [-].

    Φ_y = 12·E·I_z / (κ·G·A·L²) governs bending in the x-y plane, Φ_z = 12·E·I_y / (κ·G·A·L²)
    bending in the x-z plane (Timoshenko beam theory).
    """
    shear_stiffness = section.shear_coefficient * shear_modulus * section.area
    phi_y = 12.0 * youngs_modulus * section.second_moment_z / (shear_stiffness * length**2)
    phi_z = 12.0 * youngs_modulus * section.second_moment_y / (shear_stiffness * length**2)
    return phi_y, phi_z


def timoshenko_cantilever_matrix(
    section: SectionProperties, youngs_modulus: float, shear_modulus: float, length: float
) -> np.ndarray:
    """6x6 Timoshenko stiffness of a cantilever segment of length ``length`` [N/mm, N, N·mm].

    Order of the generalised coordinates: (u_x, u_y, u_z, θ_x, θ_y, θ_z) of the free end in
    the frame of the clamped end; forces (F_x, F_y, F_z, M_x, M_y, M_z) at the free end.
    """
    E, G, L = youngs_modulus, shear_modulus, length
    phi_y, phi_z = shear_parameters(section, E, G, L)
    Iy, Iz = section.second_moment_y, section.second_moment_z
    K = np.zeros((6, 6))
    K[0, 0] = E * section.area / L
    K[1, 1] = 12.0 * E * Iz / (L**3 * (1.0 + phi_y))
    K[2, 2] = 12.0 * E * Iy / (L**3 * (1.0 + phi_z))
    K[3, 3] = G * section.torsion_constant / L
    K[4, 4] = (4.0 + phi_z) * E * Iy / (L * (1.0 + phi_z))
    K[5, 5] = (4.0 + phi_y) * E * Iz / (L * (1.0 + phi_y))
    K[1, 5] = K[5, 1] = -6.0 * E * Iz / (L**2 * (1.0 + phi_y))
    K[2, 4] = K[4, 2] = 6.0 * E * Iy / (L**2 * (1.0 + phi_z))
    return K


def lever_transform(lever: float) -> np.ndarray:
    """Map (Δu, Δθ) at a point ``lever`` back along x to (u, θ) at the segment end.

    A rigid rotation θ about the point at x = -lever moves the end by θ × (lever, 0, 0):
    u_y gains +lever·θ_z and u_z gains -lever·θ_y.
    """
    T = np.eye(6)
    T[1, 5] = lever
    T[2, 4] = -lever
    return T


def midpoint_stiffness(
    section: SectionProperties, youngs_modulus: float, shear_modulus: float, length: float
) -> np.ndarray:
    """Diagonal 6x6 stiffness of a segment with its spring frames at the segment midpoint.

    Equal to Tᵀ·K·T with K the cantilever matrix and T = ``lever_transform(length / 2)``;
    computed here from the closed form: diag(EA/L, 12EI_z/(L³(1+Φ_y)), 12EI_y/(L³(1+Φ_z)),
    GJ/L, EI_y/L, EI_z/L).
    """
    E, G, L = youngs_modulus, shear_modulus, length
    phi_y, phi_z = shear_parameters(section, E, G, L)
    return np.diag(
        [
            E * section.area / L,
            12.0 * E * section.second_moment_z / (L**3 * (1.0 + phi_y)),
            12.0 * E * section.second_moment_y / (L**3 * (1.0 + phi_z)),
            G * section.torsion_constant / L,
            E * section.second_moment_y / L,
            E * section.second_moment_z / L,
        ]
    )


def prb_torsional_stiffness(
    section: SectionProperties,
    youngs_modulus: float,
    shear_modulus: float,
    length: float,
    gamma: float,
    stiffness_coefficient: float,
) -> np.ndarray:
    """Torsional spring constants (k_x, k_y, k_z) of the PRB pivot [N·mm/rad].

    Parameters
    ----------
    length : float
        Free bristle length l [mm].
    gamma, stiffness_coefficient : float
        Howell's characteristic radius factor γ and stiffness coefficient K_Θ [-].
    """
    E, G, length_ = youngs_modulus, shear_modulus, length
    return np.array(
        [
            G * section.torsion_constant / (gamma * length_),
            gamma * stiffness_coefficient * E * section.second_moment_y / length_,
            gamma * stiffness_coefficient * E * section.second_moment_z / length_,
        ]
    )


def buckling_load(section: SectionProperties, youngs_modulus: float, length: float) -> float:
    """Euler buckling load of a clamped-free column, π²·E·I_min / (4·l²) [N].

    The largest axial load a straight bristle carries before it bows out; beyond it the
    tip force barely grows, which makes it the tip's representative contact force.
    """
    second_moment = min(section.second_moment_y, section.second_moment_z)
    return float(np.pi**2 * youngs_modulus * second_moment / (4.0 * length**2))
