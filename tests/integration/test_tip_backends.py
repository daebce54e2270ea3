"""The tip contact's back ends (exubrush.contact.tip_backends): one per contact.backend,
each applying where it says, and the sensor each records its force with."""

from types import SimpleNamespace

import exudyn as exu
import pytest

from exubrush.contact.tip_backends import BACKENDS, TipSite, tip_backend
from exubrush.parameters.choices import CONTACT_BACKENDS
from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run import scene as scenes
from exubrush.run.prepared import prepare

ONE = ["head.rows=1", "head.columns=1"]


def test_every_backend_a_case_can_name_has_one():
    assert tuple(BACKENDS) == CONTACT_BACKENDS
    assert all(BACKENDS[name].name == name for name in CONTACT_BACKENDS)


def _site(case, overrides):
    """The site of the first bristle's tip of ``case`` with ``overrides``, in a new scene."""
    prepared = prepare(load_case(case, [*ONE, *overrides]))
    scene, handle = scenes.add_handle(prepared, prepared.bristles[:1], drawn=False)
    items = scenes.add_bristle(scene, prepared, scene.bristles[0], handle.body, drawn=False)
    surface = scenes.surface_marker(scene.mbs, scene.ground, prepared.case.surface)
    site = TipSite(scene.mbs, scene.ground, surface, items.tip_body, items.nodes[-1],
                   scene.bristles[0])
    return prepared.case, site


@pytest.mark.parametrize(("case", "overrides", "expected"), [
    ("orthogonal", [], "paper-symbolic"),
    ("orthogonal", ["contact.backend='paper-python'"], "paper-python"),
    ("orthogonal", ["contact.backend='exudyn-builtin'"], "exudyn-builtin"),
    # compiled over a curved analytic surface on a tip with Euler parameters (DFM's) ...
    ("interdental", [], "paper-compiled"),
    ("orthogonal", ["surface.kind='sphere'", "contact.backend='paper-compiled'"],
     "paper-compiled"),
    # ... and the symbolic law in its stead elsewhere: the plane, PRB's rotation vector
    ("orthogonal", ["contact.backend='paper-compiled'"], "paper-symbolic"),
    ("interdental", ["model.kind='prb'"], "paper-symbolic"),
])
def test_a_tip_gets_its_backend_where_that_applies(case, overrides, expected):
    assert tip_backend(*_site(case, overrides)).name == expected


def test_the_builtin_contact_refuses_a_surface_it_cannot_brush():
    # a case refuses this when it is read (exubrush.parameters.case); this is the back
    # end's own check, met by a stand-in for such a case
    _, site = _site("orthogonal", [])
    crown = SimpleNamespace(contact=SimpleNamespace(backend="exudyn-builtin"),
                            surface=SimpleNamespace(kind="cylinder"))
    with pytest.raises(ValueError, match="'exudyn-builtin' does not apply to surface.kind "
                                         "'cylinder'"):
        tip_backend(crown, site)
    with pytest.raises(ParameterError, match="brushes a plane only"):
        load_case("orthogonal", ["surface.kind='cylinder'", "contact.backend='exudyn-builtin'"])


@pytest.mark.parametrize(("overrides", "output", "body"), [
    ([], exu.OutputVariableType.ForceLocal, False),  # the connector's, surface frame
    (["contact.backend='exudyn-builtin'"], exu.OutputVariableType.Force, False),
])
def test_each_backend_records_its_force(overrides, output, body):
    case, site = _site("orthogonal", overrides)
    backend = tip_backend(case, site)
    contact = backend.add(site, case, None, {})
    sensor = backend.force_sensor(contact)
    assert sensor.outputVariableType == output
    assert int(sensor.objectNumber) == int(contact.connector)
