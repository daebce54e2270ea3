"""Each contact law against every back end it is made in, over a sweep of its inputs.

The tip's law (exubrush.contact.laws) is one definition run on floats (contact.backend
"paper-python") and on Exudyn's symbolic expressions ("paper-symbolic"), and written by
hand in numba ("paper-compiled", exubrush.contact.surface_kernel), which reads the law's
fields by name (surface_kernel.LAW_FIELDS). The law between filaments exists only in numba
(exubrush.contact.between_kernel), in a force kernel and a derivative kernel. One test per
law holds every back end to the same values and derivatives, at the band edges of the
friction (v_s, v_d; the soft depth and v_r between filaments), at zero slip and at zero
depth. A new back end or law is one more entry here (docs/architecture.md, "Contact laws:
one definition each, and adding one").
"""

import itertools

import exudyn as exu
import numpy as np
import pytest

import exubrush.contact.between_kernel as between
import exubrush.contact.surface_kernel as kernel
from exubrush.contact.between import law_vector, pair_corner_forces
from exubrush.contact.between_kernel import LAW_FIELDS as BETWEEN_FIELDS
from exubrush.contact.between_kernel import SOFT_DEPTH, pairs_derivatives
from exubrush.contact.exudyn_contact import SYMBOLIC_MATH
from exubrush.contact.laws import sphere_plane_force, sphere_surface_force
from exubrush.contact.surface_kernel import (
    LAW_FIELDS,
    MAX_FEATURES,
    law_numbers,
    surface_load,
    surface_numbers,
)
from exubrush.parameters.case import BristleContactLaw, ContactLaw, Surface
from exubrush.util.float_math import FLOAT_MATH
from exubrush.world.surfaces import features

RADIUS = 0.4  # tip sphere [mm]
PLANE = Surface(kind="plane")
TIP_LAWS = [
    ContactLaw(),  # the paper's table 2: friction falls from mu_s to mu_d
    ContactLaw(stiffness_exponent=1.5, damping_rate_exponent=0.8, damping_depth_exponent=1.0,
               static_friction=0.5, dynamic_friction=0.7),  # rising friction, other exponents
]


def _slip_speeds(law):
    """Zero slip, inside the rise, the band edges v_s and v_d, between them, beyond [mm/s]."""
    vs, vd = law.static_velocity, law.dynamic_velocity
    return [0.0, 0.5 * vs, vs, 0.5 * (vs + vd), vd, 3.0 * vd]


class _Symbolic:
    """A back end recorded once into Exudyn expressions of variables, evaluated per state."""

    def __init__(self, load):
        real = exu.symbolic.Real
        self.names = ("z", "vx", "vy", "vz", "scale", "drop")
        self.variables = {name: real(name, 0.0) for name in self.names}
        v = self.variables
        self.expressions = load([0.0, 0.0, v["z"]], [v["vx"], v["vy"], v["vz"]], v["scale"],
                                v["drop"])

    def __call__(self, **values):
        for name in self.names:
            self.variables[name].SetValue(values[name])
        return np.array([e if isinstance(e, float) else e.Evaluate() for e in self.expressions])


def _tip_back_ends(law, lagged):
    """The tip law's back ends, each a function of the state (plane frame, omega = 0) to the
    force [N] and moment [N·mm] on the sphere."""

    def surface_law(m):
        def load(centre, velocity, scale, drop):
            return sphere_surface_force(law, RADIUS, features(PLANE, centre, RADIUS, m),
                                        velocity, [0.0, 0.0, 0.0], m, scale,
                                        [drop] if lagged else None)
        return load

    def plane_law(m):
        def load(centre, velocity, scale, drop):
            return sphere_plane_force(law, RADIUS, centre, velocity, [0.0, 0.0, 0.0], m, scale,
                                      drop if lagged else None)
        return load

    def floats(load):
        return lambda z, vx, vy, vz, scale, drop: np.array(
            load([0.0, 0.0, z], [vx, vy, vz], scale, drop), float)

    kind, params = surface_numbers(PLANE)
    numbers = law_numbers(law)

    def compiled(z, vx, vy, vz, scale, drop):
        drops = np.full(MAX_FEATURES, drop if lagged else -1.0)
        out = np.zeros(6)
        surface_load(kind, params, numbers, RADIUS, np.array([0.0, 0.0, z]),
                     np.array([vx, vy, vz]), np.zeros(3), scale, drops, out)
        return out

    return {
        "features-python": floats(surface_law(FLOAT_MATH)),
        "features-symbolic": _Symbolic(surface_law(SYMBOLIC_MATH)),
        "features-compiled": compiled,
        "plane-python": floats(plane_law(FLOAT_MATH)),
        "plane-symbolic": _Symbolic(plane_law(SYMBOLIC_MATH)),
    }


def _call(back_end, depth, rate, slip, scale, drop):
    """The back end at penetration ``depth`` [mm], its rate [mm/s] and the slip [mm/s]
    along a direction 30° off x."""
    return back_end(z=RADIUS - depth, vx=slip * np.cos(np.pi / 6), vy=slip * np.sin(np.pi / 6),
                    vz=-rate, scale=scale, drop=drop)


# central-difference steps of depth [mm], rate and slip [mm/s]
STEPS = (1e-7, 1e-5, 1e-6)


@pytest.mark.parametrize("law", TIP_LAWS, ids=["falling", "rising"])
@pytest.mark.parametrize("lagged", [False, True], ids=["implicit", "lagged"])
def test_every_back_end_of_the_tip_law_gives_its_values_and_derivatives(law, lagged):
    back_ends = _tip_back_ends(law, lagged)
    depths = [-0.01, 0.0, 1e-4, 0.02, 0.08]
    rates = [-20.0, 0.0, 20.0]
    touched = 0
    for depth, rate, slip, scale in itertools.product(depths, rates, _slip_speeds(law),
                                                      [1.0, 0.4]):
        state = (depth, rate, slip, scale, 0.93)
        values = {name: _call(f, *state) for name, f in back_ends.items()}
        reference = values["features-python"]
        touched += bool(np.any(reference != 0.0))
        for name, got in values.items():
            # the plane's own form (sphere_plane_force) divides by sqrt(v² + 1e-12 mm²/s²)
            # rather than v: 1e-12 / v² relative at most; the others the same operations
            rtol = 1e-9 if name.startswith("plane") else 1e-12
            np.testing.assert_allclose(got, reference, rtol=rtol, atol=1e-14,
                                       err_msg=f"{name} at {state}")
        for k, step in enumerate(STEPS):  # ∂/∂depth, ∂/∂rate, ∂/∂slip of each back end
            ahead, behind = list(state), list(state)
            ahead[k] += step
            behind[k] -= step
            slopes = {name: (_call(f, *ahead) - _call(f, *behind)) / (2.0 * step)
                      for name, f in back_ends.items()}
            reference = slopes["features-python"]
            for name, got in slopes.items():
                # the values' rounding (1e-15 N) over the step, and the plane's floor
                np.testing.assert_allclose(got, reference, rtol=1e-7,
                                           atol=1e-15 / step + 1e-9 * np.abs(reference).max(),
                                           err_msg=f"d/d{('depth', 'rate', 'slip')[k]} of "
                                                   f"{name} at {state}")
    assert touched > 50  # most states press the sphere in


def test_the_compiled_laws_read_each_field_by_its_name():
    # every field of the law, and only those, each where its name says
    law = ContactLaw(stiffness=101.0, stiffness_exponent=1.31, damping=0.21,
                     damping_rate_exponent=1.01, damping_depth_exponent=2.01,
                     static_friction=0.81, dynamic_friction=0.77, static_velocity=1.21,
                     dynamic_velocity=1.51)
    numbers = law_numbers(law)
    for name in LAW_FIELDS:
        assert numbers[getattr(kernel, name.upper())] == getattr(law, name)
    assert len(set(numbers)) == len(LAW_FIELDS) == len(numbers)
    filaments = BristleContactLaw(stiffness=51.0, damping=3e-4, friction=0.21,
                                  friction_velocity=0.011)
    vector = law_vector(filaments)
    for name in BETWEEN_FIELDS:
        assert vector[getattr(between, name.upper())] == getattr(filaments, name)
    assert len(vector) == len(BETWEEN_FIELDS)


def _filament_law_force(law, overlap, radii, approach, slip):
    """The law between filaments as docs/tufts.md states it, on the second segment [N]:
    along the normal n = +z, f_n = max(k g(overlap) − c h(overlap) (n·v_rel), 0), g =
    overlap²/(2δ) up to δ = SOFT_DEPTH (r_a + r_b) and overlap − δ/2 beyond, h =
    min(overlap/δ, 1); friction −μ f_n v_t / sqrt(|v_t|² + v_r²) along the slip (+x)."""
    soft = SOFT_DEPTH * sum(radii)
    g = overlap**2 / (2 * soft) if overlap < soft else overlap - soft / 2
    normal = max(law.stiffness * g - law.damping * min(overlap / soft, 1.0) * approach, 0.0)
    friction = -law.friction * normal * slip / np.hypot(slip, law.friction_velocity)
    return np.array([friction, 0.0, normal])


def test_the_law_between_filaments_gives_its_values_and_derivatives():
    # two crossing segments (along x and along y), the second above the first: the overlap,
    # its rate and the slip set by the second's height and velocity
    law = BristleContactLaw()
    radii = np.array([0.1, 0.1])
    soft = SOFT_DEPTH * radii.sum()
    vr = law.friction_velocity
    touched = 0
    for overlap, approach, slip in itertools.product(
            [-1e-3, 0.0, 0.5 * soft, soft, 3.0 * soft, 0.02],  # gap, first touch, soft edge
            [-50.0, 0.0, 50.0],  # the second leaving (n·v_rel > 0: damping never pulls)
            [0.0, 0.5 * vr, vr, 30.0 * vr]):  # zero slip, the regularisation speed
        x = np.array([[[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0],
                       [0.0, -1.0, radii.sum() - overlap],
                       [0.0, 1.0, radii.sum() - overlap]]])
        v = np.zeros((1, 4, 3))
        v[0, 2:, 0] = slip
        v[0, 2:, 2] = approach
        inner = np.zeros((1, 4), bool)
        forces, found = pair_corner_forces(x, v, radii[None, :], inner, law)
        np.testing.assert_allclose(found, [overlap], rtol=0, atol=1e-15)  # rounding of z
        expected = (_filament_law_force(law, overlap, radii, approach, slip) if overlap > 0.0
                    else np.zeros(3))
        # the second segment's two corners carry half each (the contact at their middle),
        # the first's the opposite; rounding of the overlap (1e-15 mm) times the stiffness
        np.testing.assert_allclose(forces[0, 2] + forces[0, 3], expected, rtol=1e-9,
                                   atol=1e-12)
        np.testing.assert_allclose(forces[0, 0] + forces[0, 1], -expected, rtol=1e-9,
                                   atol=1e-12)
        touched += bool(overlap > 0.0)
        # the derivative kernel against differences of the force kernel
        by_position, by_velocity = pairs_derivatives(x, v, radii[None, :], inner, x.copy(),
                                                     law_vector(law), 1e-8, 1e-5)
        for moved, derivative, step in ((x, by_position, 1e-6), (v, by_velocity, 1e-4)):
            ahead, behind = moved.copy(), moved.copy()
            ahead[0, 2, 2] += step
            behind[0, 2, 2] -= step
            pair = (ahead, v) if moved is x else (x, ahead)
            back = (behind, v) if moved is x else (x, behind)
            slope = (pair_corner_forces(*pair, radii[None, :], inner, law)[0]
                     - pair_corner_forces(*back, radii[None, :], inner, law)[0]) / (2 * step)
            # forward (kernel) against central (here) differences: the truncation, 1e-5
            # of the stiffness; at first touch and at the soft edge the damping's h(overlap)
            # has a kink, where the two differ by up to its jump in slope c |n·v_rel| / δ,
            # and the elastic term's curvature k / δ over the step (μ times both in the
            # friction)
            kink = ((1.0 + law.friction) * (law.damping * abs(approach) + law.stiffness * step)
                    / soft)
            np.testing.assert_allclose(derivative[0, :, :, 2, 2], slope[0], rtol=1e-5,
                                       atol=kink if overlap in (0.0, soft) else
                                       1e-5 * law.stiffness)
    assert touched == 4 * 3 * 4
