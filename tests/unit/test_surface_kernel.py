"""The compiled tip-surface contact (exubrush.contact.surface_kernel) against the generic
law over the surface's features (exubrush.contact.laws.sphere_surface_force)."""

import numpy as np
import pytest

from exubrush.contact.laws import sphere_surface_force
from exubrush.contact.surface_kernel import (
    MAX_FEATURES,
    law_numbers,
    surface_load,
    surface_numbers,
)
from exubrush.parameters.case import ContactLaw, Surface
from exubrush.surfaces import features

LAW = ContactLaw()
SURFACES = [
    Surface(kind="plane"),
    Surface(kind="cylinder", radius=4.0),
    Surface(kind="sphere", radius=4.0),
    Surface(kind="tooth-row"),
    Surface(kind="tooth-row", gap_width=0.5),  # narrower than the sphere: both teeth
]


def _kernel(surface, radius, centre, velocity, omega, scale, drops):
    kind, params = surface_numbers(surface)
    lagged = np.full(MAX_FEATURES, -1.0)
    if drops is not None:
        lagged[:len(drops)] = drops
    out = np.zeros(6)
    surface_load(kind, params, law_numbers(LAW), radius, np.asarray(centre, float),
                 np.asarray(velocity, float), np.asarray(omega, float), scale, lagged, out)
    return out


@pytest.mark.parametrize("surface", SURFACES, ids=lambda s: f"{s.kind}-{s.gap_width}")
@pytest.mark.parametrize("lagged", [False, True])
def test_the_kernel_is_the_generic_law(surface, lagged):
    rng = np.random.default_rng(3)
    radius = 0.4
    touched = 0
    for _ in range(400):
        # centres around the surface's top and, on a tooth row, inside a gap
        centre = [rng.uniform(-5.0, 5.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.6, 0.5)]
        velocity = rng.normal(scale=rng.choice([0.5, 3.0, 40.0]), size=3)
        omega = rng.normal(scale=20.0, size=3)
        scale = rng.choice([1.0, 0.37])
        found = features(surface, centre, radius)
        drops = rng.uniform(0.9, 1.0, size=len(found)).tolist() if lagged else None
        expected = sphere_surface_force(LAW, radius, found, velocity.tolist(), omega.tolist(),
                                        friction_scale=scale, drops=drops)
        got = _kernel(surface, radius, centre, velocity, omega, scale, drops)
        # rounding: the same operations, summed in the same order
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-15)
        touched += bool(np.any(np.asarray(expected) != 0.0))
    assert touched > 40  # the states reach the surface often enough to test the law
