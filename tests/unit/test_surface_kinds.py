"""The one list of surface kinds (exubrush.parameters.surface_kinds) against the code that
implements each kind's properties."""

import pytest

from exubrush.contact.surface_kernel import surface_numbers
from exubrush.parameters.case import Surface
from exubrush.parameters.surface_kinds import KINDS, SURFACE_KIND, SURFACE_KINDS
from exubrush.world.surfaces import features, height


def test_every_kind_is_named_once_and_a_case_accepts_exactly_these():
    assert len(SURFACE_KINDS) == len(KINDS) == len(SURFACE_KIND)
    for name in SURFACE_KINDS:
        if name != "mesh":  # a mesh also needs its file
            assert Surface().replace(kind=name).kind == name
    with pytest.raises(ValueError, match="ellipsoid"):
        Surface().replace(kind="ellipsoid")


@pytest.mark.parametrize("name", [k.name for k in KINDS if not k.plane_law])
def test_a_kind_with_its_own_law_has_analytic_features(name):
    surface = Surface(kind=name)
    assert features(surface, (0.0, 0.0, 0.1), 0.4)
    assert float(height(surface, 0.0, 0.0)) == 0.0  # its top at the frame's origin


def test_every_compiled_kind_has_its_own_kernel_code():
    codes = [surface_numbers(Surface(kind=k.name))[0] for k in KINDS if k.compiled]
    assert len(set(codes)) == len(codes) > 0
