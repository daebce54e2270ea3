"""Contact between bristles in Exudyn (exubrush.contact.exudyn_between): a bristle pushed
against its neighbour against beam theory, and a tuft solved as one group."""

import json

import numpy as np
import pytest

from exubrush.models.geometry import BristleGeometry
from exubrush.models.sections import section_properties
from exubrush.parameters.case import BristleContactLaw
from exubrush.parameters.head import BUILT_IN_MATERIALS
from exubrush.statics import pushed_pair
from exubrush.util.references import BRISTLE_CONTACT, FLORES, FRICTION, PAPER

D, L, GAP = 0.2, 10.0, 0.01  # mm: nylon filaments 10 mm long, 10 µm apart
NYLON = BUILT_IN_MATERIALS["nylon"]
UPRIGHT = np.eye(3)[:, [2, 0, 1]]  # bristle x along z


def _pair():
    section = section_properties("circle", D, D)
    return tuple(BristleGeometry(root=np.array([x, 0.0, 0.0]), frame=UPRIGHT, length=L,
                                 tip_radius=D / 2, section=section, width=D, height=D,
                                 shape="circle", material=NYLON)
                 for x in (0.0, D + GAP))


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_a_pushed_filament_shares_its_load_with_its_neighbour_as_beam_theory_says():
    # small deflections (2 % of L): once the gap is closed at the tips, the contact force F
    # bends the second, P − F the first: (P − F) L³/3EI − F L³/3EI = gap
    bristles = _pair()
    load = 2e-4  # N
    pushed = pushed_pair(bristles, np.array([load, 0.0, 0.0]), BristleContactLaw(),
                         segments=12)
    assert pushed.completed
    tips = pushed.tips
    flexibility = L**3 / (3.0 * NYLON.youngs_modulus * bristles[0].section.second_moment_y)
    contact = (load - GAP / flexibility) / 2.0
    second = tips[1, 0] - (D + GAP)
    first = tips[0, 0]
    # 1 %: the accuracy asked of contact between bristles (docs/tufts.md); beam theory
    # neglects the 2 % deflection's geometric effect
    assert second == pytest.approx(contact * flexibility, rel=0.01)
    assert first == pytest.approx((load - contact) * flexibility, rel=0.01)
    assert pushed.contact_force[0] == pytest.approx(contact, rel=0.01)
    assert pushed.deepest < 0.05 * D


@pytest.mark.parametrize("load", [1e-3, 4e-3])
@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_a_filament_pushed_far_shares_its_load_as_the_elastica_says(load):
    # tip 1 moves 10 % and 36 % of L; frictionless, held in the x-z plane as the planar
    # reference is (statics.pushed_pair says why)
    from exubrush.reference.touching_cantilevers import touching_cantilevers

    bristles = _pair()
    law = BristleContactLaw().replace(friction=0.0)
    pushed = pushed_pair(bristles, np.array([load, 0.0, 0.0]), law, segments=12,
                         in_plane=True)
    assert pushed.completed
    bending = NYLON.youngs_modulus * bristles[0].section.second_moment_y
    exact = touching_cantilevers(L, GAP, D / 2, bending, load, segments=50, load_steps=5)
    # 1 %: the accuracy asked of contact between bristles (measured: tips within 0.1 %,
    # contact force 0.9 % at 4 mN, where the beams touch along their length; the
    # reference's 50 springs add 0.1 %)
    assert pushed.tips[0, 0] == pytest.approx(exact.tips[0, 0], rel=0.01)
    assert pushed.tips[1, 0] - (D + GAP) == pytest.approx(exact.tips[1, 0] - (D + GAP),
                                                          rel=0.01)
    assert np.linalg.norm(pushed.contact_force) == pytest.approx(
        np.linalg.norm(exact.contact_force), rel=0.01)


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_a_filament_pushed_far_never_overlaps_its_neighbour_by_more_than_5_percent():
    pushed = pushed_pair(_pair(), np.array([2e-3, 0.0, 0.0]), BristleContactLaw(),
                         segments=6)
    assert pushed.completed
    assert pushed.tips[0, 0] > 0.2 * L  # bent well beyond the linear range
    assert pushed.deepest < 0.05 * D


@pytest.mark.slow  # about 12 s: a 7-filament tuft's run
def test_a_tuft_with_contact_is_one_group_and_reports_its_contacts(cli, tmp_path):
    case = tmp_path / "tuft7.toml"
    case.write_text('name = "tuft7"\n[head]\nlayout = "tufts"\n[[head.tufts]]\n'
                    'filaments = 7\ndiameter = "0.8 mm"\n[motion]\n'
                    'interaction_distance = "8.4 mm"\napproach_duration = "0.3 s"\n'
                    'hold_duration = "0.05 s"\n[contact]\nbetween_bristles = true\n')
    done = cli("run", str(case), "--periods", "0.02", "--quiet", "--out", str(tmp_path / "r"))
    assert done.returncode == 0, done.stderr
    record = json.loads((tmp_path / "r" / "run.json").read_text())
    assert [r["key"] for r in record["references"]] == [
        r.key for r in (PAPER, FLORES, FRICTION, BRISTLE_CONTACT)]
    derived = record["derived"]
    assert derived["bristle_groups"] == [list(range(7))]
    assert derived["systems_solved"] == 1
    # seven hexagonal filaments touching all along: 12 neighbour pairs, several segment
    # pairs each
    assert derived["bristle_contacts_max"] >= 12
    assert derived["bristle_overlap_max_mm"] < 0.05 * D
    # the group's line search counts the Newton attempts it gave up (a count, maybe 0 here)
    assert isinstance(record["solver_statistics"]["given_up_attempts"], int)


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_touching_filaments_take_larger_steps_mid_stroke_and_miss_no_contact(tmp_path):
    # three filaments pressed together, into the slide: the step grows past
    # solver.step_size where the head slides fast (the mid-stroke cap, 5x), and the broad
    # phase, sized for the coming step, still finds every pair that touches at its end
    import exudyn as exu

    from exubrush.parameters.io import load_case
    from exubrush.run.prepared import prepare
    from exubrush.run.scene import build_scene
    from exubrush.run.solve import group_settings

    case_file = tmp_path / "tuft3.toml"
    case_file.write_text('name = "tuft3"\n[head]\nlayout = "tufts"\n[[head.tufts]]\n'
                         'filaments = 3\ndiameter = "0.6 mm"\n[motion]\n'
                         'interaction_distance = "8.4 mm"\napproach_duration = "0.3 s"\n'
                         'hold_duration = "0.05 s"\n[contact]\nbetween_bristles = true\n')
    case = load_case(str(case_file), ["motion.periods=0.15"])
    prepared = prepare(case)
    scene = build_scene(prepared, prepared.groups[0])
    contact = scene.bristle_contact
    start = exu.ConfigurationType.StartOfStep
    steps, missed = [], []

    def before_step(mbs, t):
        if contact.candidate_corners is not None:  # the last step's end against its refresh
            candidates = set(map(tuple, contact.candidate_corners[0].tolist()))
            missed.extend(c for c in map(tuple, contact._contacts(mbs).corners.tolist())
                          if c not in candidates)
        steps.append(t - mbs.systemData.GetTime(start))
        return scene.run_step_hooks(mbs, t)

    scene.mbs.SetPreStepUserFunction(before_step)
    assert scene.mbs.SolveDynamic(group_settings(prepared, scene, prepared.groups[0]),
                                  storeSolver=True)
    assert max(contact.counts) > 0
    assert max(steps) > 2.0 * case.solver.step_size
    assert missed == []
