"""Contact force laws of a tip sphere on a rigid surface (pure, mm-N-s units).

Each law is written once against a small "math back end" (exubrush.util.float_math) so that
the same code runs on floats (``FLOAT_MATH``) and on Exudyn's symbolic expressions
(``exudyn.symbolic``), which the Exudyn adapter records into a C++ user function.

Sources: the paper's eqs. 14 and 15 (Cellupica et al. 2024, exubrush.util.references), after
its refs. [35-37] (Hertz, extended by Flores) and [39-42] (velocity-based friction).

Normal force, Hertz-type penalty with Flores-type damping (the paper's eq. 14)::

    F_n = k δ^m1 + c sign(δ') |δ'|^m2 δ^m3,   δ > 0,   F_n clamped at >= 0

Decision: the surface never pulls. When the damping term outweighs the
elastic one while the sphere leaves the surface, F_n is clamped to zero rather than
allowed to become adhesive.

Friction coefficient μ(v) of the paper's eq. 15 (F_t = -μ(v_t) F_n v_t / |v_t|),
v = |v_t| >= 0: from 0 at v = 0 to μ_s at v_s along the odd cubic step that runs from -μ_s
at -v_s to +μ_s at +v_s (so μ grows linearly from zero, slope 1.5 μ_s / v_s, as in the
step-function friction of common multibody codes), then a cubic step from μ_s at v_s to
μ_d at v_d, and μ_d above. Value and slope are continuous.
No stiction state: the law is regularised.

Where μ_s > 0 the coefficient is a product μ(v) = μ_rise(v) · r(v): the rise from 0 to μ_s
(constant μ_s above v_s) and the drop ratio from 1 to μ_d / μ_s between v_s and v_d
(:func:`friction_rise`, :func:`friction_drop`). The force functions take the drop ratio
as a number where a time step evaluates it at the slip speed of the step's start
(``drop``; ``solver.friction_drop = "lagged"``, docs/model.md).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from exubrush.parameters.surface_kinds import PLANE
from exubrush.util.float_math import FLOAT_MATH
from exubrush.world.surfaces import Choice, features, taken

if TYPE_CHECKING:  # the laws read the parameters' attributes only: no import at run time
    from exubrush.parameters.case import ContactLaw, Surface


def cubic_step(x, x0, h0, x1, h1, m=FLOAT_MATH):
    """Smooth step from h0 at x <= x0 to h1 at x >= x1 (cubic 3ξ² - 2ξ³, zero end slopes)."""
    xi = m.min(m.max((x - x0) / (x1 - x0), 0.0), 1.0)
    return h0 + (h1 - h0) * xi * xi * (3.0 - 2.0 * xi)


def normal_force(law: ContactLaw, penetration, penetration_rate, m=FLOAT_MATH):
    """Normal contact force F_n >= 0 [N] for penetration δ [mm] and its rate δ' [mm/s]."""
    depth = m.max(penetration, 0.0)
    rate = penetration_rate
    elastic = law.stiffness * depth**law.stiffness_exponent
    dissipative = (
        law.damping
        * m.sign(rate)
        * m.abs(rate) ** law.damping_rate_exponent
        * depth**law.damping_depth_exponent
    )
    return m.max(elastic + dissipative, 0.0)


def friction_coefficient(law: ContactLaw, slip_speed, m=FLOAT_MATH):
    """Velocity-dependent friction coefficient μ(|v_t|) [-]; ``slip_speed`` in mm/s."""
    to_static = cubic_step(
        slip_speed, -law.static_velocity, -law.static_friction,
        law.static_velocity, law.static_friction, m,
    )
    to_dynamic = cubic_step(
        slip_speed, law.static_velocity, law.static_friction,
        law.dynamic_velocity, law.dynamic_friction, m,
    )
    return m.IfThenElse(slip_speed < law.static_velocity, to_static, to_dynamic)


def friction_rise(law: ContactLaw, slip_speed, m=FLOAT_MATH):
    """μ_rise(v): the odd cubic step from 0 at v = 0 to μ_s at v_s, μ_s above [-]."""
    return cubic_step(slip_speed, -law.static_velocity, -law.static_friction,
                      law.static_velocity, law.static_friction, m)


def friction_drop(law: ContactLaw, slip_speed, m=FLOAT_MATH):
    """r(v) = μ(v) / μ_rise(v): 1 up to v_s, a cubic step to μ_d / μ_s at v_d, μ_d / μ_s
    above [-] (needs μ_s > 0)."""
    return cubic_step(slip_speed, law.static_velocity, 1.0, law.dynamic_velocity,
                      law.dynamic_friction / law.static_friction, m)


def drop_can_lag(law: ContactLaw) -> bool:
    """Whether the law's friction falls from μ_s to μ_d (μ_s > μ_d): only then has
    :func:`friction_drop` anything to lag (with μ_d >= μ_s, μ(v) never falls)."""
    return law.static_friction > law.dynamic_friction


def friction_per_speed(law: ContactLaw, slip_square, m=FLOAT_MATH, drop=None):
    """μ(v) / v [s/mm] as a function of v² = |v_t|² [mm²/s²]: :func:`friction_coefficient`
    over the slip speed, written so that Exudyn's expression tree uses its argument as few
    times as possible (it evaluates a subexpression again at every use).

    Below v_s the odd cubic step is μ_s (3/2 ξ − 1/2 ξ³), ξ = v / v_s, so μ/v =
    μ_s / v_s (3/2 − 1/2 v²/v_s²): no square root, and finite at v = 0 (the viscous-like
    limit 1.5 μ_s / v_s). Above, the cubic step to μ_d is μ_s + (μ_d − μ_s) η²(3 − 2η),
    η = min((v − v_s)/(v_d − v_s), 1). With ``drop`` (the drop ratio r, a number), the
    coefficient is μ_rise(v) · r: μ_s r / v above v_s.
    """
    vs, vd = law.static_velocity, law.dynamic_velocity
    mu_s, mu_d = law.static_friction, law.dynamic_friction
    creeping = mu_s / vs * (1.5 - 0.5 / (vs * vs) * slip_square)
    speed = m.sqrt(m.max(slip_square, vs * vs))
    if drop is not None:
        return drop * m.IfThenElse(slip_square < vs * vs, creeping, mu_s / speed)
    eta = m.min((speed - vs) / (vd - vs), 1.0)
    sliding = (mu_s + (mu_d - mu_s) * m.square(eta) * (3.0 - 2.0 * eta)) / speed
    return m.IfThenElse(slip_square < vs * vs, creeping, sliding)


def plane_slip(radius: float, velocity, omega):
    """Slip (x, y) [mm/s] of a sphere of ``radius`` [mm] on the plane z = 0: the velocity
    of its material point at the contact point, v + ω × (−r e_z)."""
    return velocity[0] - radius * omega[1], velocity[1] + radius * omega[0]


def sphere_plane_force(
    law: ContactLaw, radius: float, centre, velocity, omega, m=FLOAT_MATH, friction_scale=1.0,
    drop=None,
):
    """Force and moment of a plane z = 0 (normal +z) on a sphere.

    Parameters
    ----------
    radius : float
        Sphere radius r [mm].
    centre, velocity, omega : sequence of 3
        Centre position [mm], centre velocity [mm/s] and angular velocity [rad/s] of the
        sphere, in the plane's frame.
    friction_scale : float or expression
        Factor on the friction force (1 = the law as it is; used to switch friction on
        smoothly after the approach).
    drop : float or expression, optional
        The drop ratio r to use instead of r(v) (:func:`friction_drop`); None: the law's
        own μ(v).

    Returns
    -------
    list of 6
        Force on the sphere [N] and moment about its centre [N·mm], plane frame. The
        friction force acts at the contact point (0, 0, -r) from the centre, so its moment
        is (-r e_z) × F_t = (r F_ty, -r F_tx, 0).
    """
    penetration = radius - centre[2]
    slip_x, slip_y = plane_slip(radius, velocity, omega)
    force_n = normal_force(law, penetration, -velocity[2], m)
    slip_speed = m.sqrt(slip_x * slip_x + slip_y * slip_y + 1e-12)
    # μ(v)/v -> 1.5 μ_s / v_s as v -> 0, so the force is a smooth viscous-like function of
    # slip; the 1e-12 mm²/s² floor only keeps the division defined at exactly zero slip.
    mu = (friction_coefficient(law, slip_speed, m) if drop is None
          else friction_rise(law, slip_speed, m) * drop)
    scale = -friction_scale * mu * force_n / slip_speed
    force_tx = scale * slip_x
    force_ty = scale * slip_y
    return [force_tx, force_ty, force_n, radius * force_ty, -radius * force_tx, 0.0]


def feature_slip(radius: float, normal, velocity, omega):
    """Normal speed v·n [mm/s] of a sphere's centre and slip (3 components) [mm/s] of its
    material point at the contact point −r n: v_c = v + ω × (−r n) less its normal part
    ((ω × n)·n = 0, so the contact point's normal speed is the centre's)."""
    nx, ny, nz = normal
    contact_velocity = (
        _sum(velocity[0], _product(-radius, _difference(_product(omega[1], nz),
                                                        _product(omega[2], ny)))),
        _sum(velocity[1], _product(-radius, _difference(_product(omega[2], nx),
                                                        _product(omega[0], nz)))),
        _sum(velocity[2], _product(-radius, _difference(_product(omega[0], ny),
                                                        _product(omega[1], nx)))),
    )
    normal_speed = _sum(*(_product(velocity[i], normal[i]) for i in range(3)))
    return normal_speed, _tangential(contact_velocity, normal, normal_speed)


def sphere_feature_force(
    law: ContactLaw, radius: float, normal, distance, velocity, omega, m=FLOAT_MATH,
    friction_scale=1.0, drop=None,
):
    """Force and moment of one convex surface feature on a sphere (exubrush.world.surfaces).

    The sphere (radius r [mm]) penetrates the feature by δ = r − d along the feature's
    outward unit normal n at the closest point, d the signed distance of its centre
    [mm]. The material point of the sphere at the contact point −r n from the centre moves
    with v_c = v + ω × (−r n); its normal part v·n gives the penetration rate −v·n, its
    tangential part v_c − (v_c·n) n the slip. The law is :func:`sphere_plane_force`'s
    along n: F = F_n n + F_t, moment (−r n) × F_t about the centre. The surface is at rest.

    A normal given as plain numbers (a flat face) drops the terms it multiplies by zero, so
    that Exudyn's expression tree of a face costs about as much as the plane's. ``drop``:
    as in :func:`sphere_plane_force`.

    Returns
    -------
    list of 6
        Force on the sphere [N] and moment about its centre [N·mm], in the frame of
        ``normal``, ``velocity`` and ``omega``.
    """
    nx, ny, nz = normal
    normal_speed, slip = feature_slip(radius, normal, velocity, omega)
    force_n = normal_force(law, radius - distance, -normal_speed, m)
    slip_square = _sum(*(0.0 if _is_number(c) and c == 0.0 else m.square(c) for c in slip))
    scale = -friction_scale * force_n * friction_per_speed(law, slip_square, m, drop)
    force = [_sum(_product(force_n, normal[i]), _product(scale, slip[i])) for i in range(3)]
    # (−r n) × F_t, F_t = scale · slip
    arm = -radius * scale
    return force + [
        _product(arm, _difference(_product(ny, slip[2]), _product(nz, slip[1]))),
        _product(arm, _difference(_product(nz, slip[0]), _product(nx, slip[2]))),
        _product(arm, _difference(_product(nx, slip[1]), _product(ny, slip[0]))),
    ]


def sphere_surface_force(
    law: ContactLaw, radius: float, surface_features, velocity, omega, m=FLOAT_MATH,
    friction_scale=1.0, drops=None,
):
    """The sum of :func:`sphere_feature_force` over ``surface_features``
    (exubrush.world.surfaces.features): every feature the sphere penetrates acts on it. A
    feature's load is only evaluated where the sphere reaches it (d < r), a Choice's only
    in the region the point is in (Exudyn's IfThenElse evaluates one branch). ``drops``:
    one drop ratio per feature (:func:`sphere_plane_force`'s ``drop``), or None."""

    def load(feature, drop):
        if isinstance(feature, Choice):
            yes, no = load(feature.if_true, drop), load(feature.if_false, drop)
            return [m.IfThenElse(feature.condition, a, b) for a, b in zip(yes, no, strict=True)]
        pushed = sphere_feature_force(law, radius, feature.normal, feature.distance, velocity,
                                      omega, m, friction_scale, drop)
        touching = feature.distance < radius
        return [m.IfThenElse(touching, component, 0.0) for component in pushed]

    total = None
    for index, feature in enumerate(surface_features):
        part = load(feature, None if drops is None else drops[index])
        total = part if total is None else [a + b for a, b in zip(total, part, strict=True)]
    return total


def drop_ratios(law: ContactLaw, radius: float, surface: Surface | None, centre, velocity,
                omega) -> list[float]:
    """The drop ratio r(v) (:func:`friction_drop`) at the slip of each feature of
    ``surface`` (None: the plane z = 0) that a sphere of ``radius`` [mm] at ``centre``
    [mm], moving with ``velocity`` [mm/s] and ``omega`` [rad/s] (surface frame), sees: the
    numbers the force functions take as ``drop`` / ``drops`` when a step lags the drop.
    The slip is the force law's own (:func:`plane_slip`, :func:`feature_slip`), whether
    the sphere touches or not; on the plane it does not depend on ``centre``."""
    if surface is None or surface.kind == PLANE:
        slip_x, slip_y = plane_slip(radius, velocity, omega)
        return [friction_drop(law, math.sqrt(slip_x * slip_x + slip_y * slip_y + 1e-12))]
    return [friction_drop(law, _slip_speed(radius, taken(feature).normal, velocity, omega))
            for feature in features(surface, centre, radius)]


def _slip_speed(radius: float, normal, velocity, omega) -> float:
    """|slip| [mm/s] of :func:`feature_slip` on floats, in plain arithmetic (a pre-step
    hook calls it for every tip and step: :func:`drop_ratios` took 40 µs a call on a tooth
    row with the generic helpers, 9 µs with this). The same operations in the same order,
    so the same numbers (tests/unit/test_contact_laws.py): the terms the generic code
    drops are exact zeros, except where a computed normal has a component of exactly ±1
    beside a tiny one, whose term (~1e-9 relative) the generic shortcut for a unit axis
    drops and this keeps."""
    nx, ny, nz = normal
    vx, vy, vz = velocity
    wx, wy, wz = omega
    cx = vx + -radius * (wy * nz - wz * ny)
    cy = vy + -radius * (wz * nx - wx * nz)
    cz = vz + -radius * (wx * ny - wy * nx)
    normal_speed = vx * nx + vy * ny + vz * nz
    sx, sy, sz = cx - normal_speed * nx, cy - normal_speed * ny, cz - normal_speed * nz
    return math.sqrt(sx * sx + sy * sy + sz * sz)


def _is_number(value) -> bool:
    return isinstance(value, int | float)


def _product(a, b):
    """a·b, exact for a plain factor 0 (0.0), 1 (the other) or −1 (its negative)."""
    for plain, other in ((a, b), (b, a)):
        if _is_number(plain):
            if plain == 0.0:
                return 0.0
            if plain == 1.0:
                return other
            if plain == -1.0:
                return -other
    return a * b


def _sum(*terms):
    """The sum of the terms that are not a plain 0."""
    kept = [t for t in terms if not (_is_number(t) and t == 0.0)]
    if not kept:
        return 0.0
    total = kept[0]
    for term in kept[1:]:
        total = total + term
    return total


def _difference(a, b):
    return _sum(a, _product(-1.0, b))


def _tangential(vector, normal, normal_part):
    """vector − normal_part · normal; a component along a plain unit axis is exactly 0."""
    axis = [i for i, n in enumerate(normal) if _is_number(n) and abs(n) == 1.0]
    if axis and all(_is_number(n) for n in normal):
        return tuple(0.0 if i == axis[0] else vector[i] for i in range(3))
    return tuple(_difference(vector[i], _product(normal_part, normal[i])) for i in range(3))


def builtin_contact_parameters(law: ContactLaw, reference_force: float) -> dict:
    """Parameters of Exudyn's built-in sphere-triangle contact closest to ``law`` (mm-N-s).

    Exudyn's ``ObjectContactSphereTriangle`` has the same elastic term k δ^m1, but a linear
    damping d δ' and a single friction coefficient μ, linear in the slip speed up to a
    regularisation speed v_r and constant above. The fit, an approximation:

    - d = c δ_ref^m3 (1 mm/s)^(m2-1): the paper's damping at the indentation δ_ref where
      the elastic force equals ``reference_force`` [N] (k δ_ref^m1 = F_ref);
    - μ = μ_d, the coefficient of steady sliding;
    - v_r = μ_d v_s / (1.5 μ_s): the same slope dμ/dv at zero slip as the paper's law
      (1.5 μ_s / v_s), so a sticking tip sees the same tangential stiffness. What is lost:
      the static peak μ_s between v_r and v_d.
    """
    reference_depth = (reference_force / law.stiffness) ** (1.0 / law.stiffness_exponent)
    if law.static_friction > 0.0 and law.dynamic_friction > 0.0:
        regularisation = law.dynamic_friction * law.static_velocity / (1.5 * law.static_friction)
    else:
        regularisation = law.static_velocity
    return {
        "contactStiffness": law.stiffness,
        "contactStiffnessExponent": law.stiffness_exponent,
        "contactDamping": law.damping * reference_depth**law.damping_depth_exponent,
        "dynamicFriction": law.dynamic_friction,
        "frictionProportionalZone": regularisation,
    }
