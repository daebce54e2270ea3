"""contact.backend "paper-compiled": the compiled law on the tip node
(exubrush.contact.surface_kernel) gives the symbolic connector's forces; where it is not
built, the backend is the symbolic law."""

import numpy as np
import pytest

from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.run.scene import build_scene
from exubrush.simulation import simulate

ONE_BRISTLE = ["head.rows=1", "head.columns=1", "motion.periods=0.1"]


def _run(case_name, backend):
    case = load_case(case_name, [*ONE_BRISTLE, f"contact.backend='{backend}'"])
    return simulate(case, progress=False, workers=1)


@pytest.mark.parametrize("case_name", ["crown", "interdental"])
@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_the_compiled_contact_gives_the_symbolic_forces(case_name):
    symbolic = _run(case_name, "paper-symbolic")
    compiled = _run(case_name, "paper-compiled")
    assert compiled.metadata["status"] == "completed"
    # the approach and the hold (no snap yet): the same law, Newton to its tolerance
    # (measured: 4e-6 N of a 0.1 N peak on the crown, 5e-8 N on the tooth row)
    calm = compiled.time < 1.15  # the slide starts at 1.2 s
    difference = np.abs(compiled.normal_force - symbolic.normal_force)[calm]
    tip_difference = np.abs(compiled.tip_force - symbolic.tip_force)[calm].max(axis=(1, 2))
    # 2e-5 N: Newton's tolerance (measured: 4e-6 N of a 0.1 N peak on the crown, 6e-6 N
    # on the tooth row), except at the sample where the tip first strikes the tooth,
    # whose impact the two take in different steps (0.9 mN there): at most one sample,
    # and within 2 % of the peak
    for differences in (difference, tip_difference):
        assert np.count_nonzero(differences > 2e-5) <= 1
        assert differences.max() < 2e-3
    # the tip force the compiled contact reports is the one the handle feels
    assert np.abs(compiled.tip_force[calm, 0, 2] - compiled.normal_force[calm]).max() < 2e-5
    assert compiled.normal_force[calm].max() > 0.05  # the tip pressed on the surface
    if case_name == "crown":  # sliding with friction, past the bristle's snap at 1.58 s
        sliding = compiled.time > 1.7
        for quantity in ("normal_force", "tangential_force"):
            a, b = getattr(compiled, quantity)[sliding], getattr(symbolic, quantity)[sliding]
            # 2e-6 N: Newton's tolerance again (measured 3e-7 N of 12-16 mN)
            np.testing.assert_allclose(a, b, rtol=0, atol=2e-6)
            assert np.abs(b).max() > 5e-3


@pytest.mark.parametrize("model, compiled", [("dfm", True), ("prb", False)])
def test_the_compiled_contact_is_built_on_euler_parameter_tips(model, compiled):
    prepared = prepare(load_case("interdental", [*ONE_BRISTLE, f"model.kind='{model}'"]))
    scene = build_scene(prepared, (0,))
    assert any(contact.compiled is not None for contact in scene.contacts) is compiled


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_where_it_is_not_built_the_compiled_backend_is_the_symbolic_law():
    # PRB's link turns on a rotation vector: its tip keeps the symbolic connector
    symbolic = load_case("interdental", [*ONE_BRISTLE, "model.kind='prb'",
                                         "contact.backend='paper-symbolic'"])
    compiled = load_case("interdental", [*ONE_BRISTLE, "model.kind='prb'"])
    assert compiled.contact.backend == "paper-compiled"  # the case's default
    a = simulate(symbolic, progress=False, workers=1)
    b = simulate(compiled, progress=False, workers=1)
    np.testing.assert_array_equal(a.normal_force, b.normal_force)
    np.testing.assert_array_equal(a.tip_force, b.tip_force)
