"""Heads built from tufts: parameters, the CSV tuft table, the filaments' geometry and what
prepare() refuses or warns about. Messages are checked in full where a user reads them."""

import math

import numpy as np
import pytest

from exubrush.models.geometry import head_bristles
from exubrush.parameters.catalogue import tuft_case
from exubrush.parameters.fields import ParameterError
from exubrush.parameters.head import BUILT_IN_MATERIALS
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare

TABLE = """# a two-tuft head, a comment line
name,x [mm],y [mm],diameter [mm],filaments,material,length [cm]
front,-2,0,1.6,37,nylon,1.04
back,2,0.5,1.2,7,pbt,
"""


def _case_with_table(tmp_path, table=TABLE, extra=""):
    (tmp_path / "tufts.csv").write_text(table)
    (tmp_path / "head.toml").write_text(
        f'name = "t"\n[head]\nlayout = "tufts"\ntuft_table = "tufts.csv"\n{extra}')
    return tmp_path / "head.toml"


def test_a_tuft_table_is_read_relative_to_its_case_file_with_units_and_defaults(tmp_path):
    case = load_case(str(_case_with_table(tmp_path)))
    front, back = case.head.tufts
    assert case.head.tuft_table == ""  # replaced by its tufts, so the saved case stands alone
    assert (front.name, front.x, front.length, front.filaments) == ("front", -2.0, 10.4, 37)
    assert (back.name, back.y, back.material, back.length) == ("back", 0.5, "pbt", 10.4)
    assert case.head.count == 44


def test_filaments_take_their_tuft_material_position_and_index(tmp_path):
    case = load_case(str(_case_with_table(tmp_path)))
    bristles = head_bristles(case.head)
    assert [b.tuft for b in bristles] == [0] * 37 + [1] * 7
    assert bristles[0].material == BUILT_IN_MATERIALS["nylon"]
    assert bristles[-1].material == BUILT_IN_MATERIALS["pbt"]
    roots = np.array([b.root[:2] for b in bristles[37:]])
    # seven filaments of 0.2 mm, hexagonal: one on the tuft's centre, six 0.2 mm around it
    assert sorted(np.hypot(*(roots - [2.0, 0.5]).T)) == pytest.approx(
        [0.0] + [0.2] * 6, abs=1e-12)
    assert bristles[0].section.area == pytest.approx(math.pi * 0.01, rel=1e-12)


def test_a_named_material_of_the_case_file_is_used(tmp_path):
    extra = ('[[head.materials]]\nname = "soft-nylon"\nyoungs_modulus = "1.5 GPa"\n'
             '[[head.tufts]]\nx = "0 mm"\nmaterial = "soft-nylon"\n')
    (tmp_path / "c.toml").write_text(f'name = "t"\n[head]\nlayout = "tufts"\n{extra}')
    bristle = head_bristles(load_case(str(tmp_path / "c.toml")).head)[0]
    assert bristle.material.youngs_modulus == 1500.0
    assert bristle.material.density == BUILT_IN_MATERIALS["silicone"].density  # unset: default


def test_the_paper_head_is_unchanged_by_tufts_in_the_code():
    head = load_case("orthogonal").head
    bristles = head_bristles(head)
    assert len(bristles) == 48
    assert all(b.tuft is None and b.material == head.material for b in bristles)


def test_the_tuft_case_is_37_nylon_filaments_bending_far():
    case = tuft_case()
    bristles = head_bristles(case.head)
    assert len(bristles) == 37
    reach = bristles[0].length + bristles[0].tip_radius
    interference = reach - case.motion.interaction_distance
    assert interference / reach == pytest.approx(0.2, abs=0.005)


TABLE_FAULTS = [
    ("x,y [mm]\n0,0\n", "head.tuft_table '{path}': column 'x' has no unit; write 'x [mm]'"),
    ("x [mm],y [mm],colour\n0,0,red\n", "head.tuft_table '{path}': unknown column 'colour'"),
    ("x [mm],diameter [mm]\n0,1.6\n", "head.tuft_table '{path}' has no column 'y'; every "
     "tuft needs its position"),
    ("x [mm],y [mm],diameter [mm]\n0,0,wide\n", "head.tuft_table '{path}', line 2, column "
     "'diameter': 'wide' is not a number"),
    ("x [mm],y [mm],diameter [mm]\n0,0,-1\n", "head.tuft_table '{path}', line 2: "
     "tuft.diameter: -1 mm must be > 0 mm"),
    ("x [mm],y [mm],diameter [s]\n0,0,1\n", "head.tuft_table '{path}', line 2: "
     "tuft.diameter: '1 s' has unit 's', which cannot be converted to 'mm'"),
    ("x [mm],y [mm],filaments\n0,0,3.5\n", "line 2, column 'filaments': '3.5' is not a whole "
     "number"),
    ("x [mm],y [mm],material [kg]\n0,0,nylon\n", "column 'material' holds text and takes no "
     "unit, got [kg]"),
    ("x [mm],y [mm]\n0,0\n1,0\n", "head: tuft 't.csv line 2' and tuft 't.csv line 3' "
     "overlap by 0.6 mm"),
    ("x [mm],y [mm],material\n0,0,steel\n", "head: tuft 't.csv line 2': material 'steel' is "
     "not defined"),
    ("x [mm],y [mm]\n", "needs a header and at least one tuft row, found 1 lines"),
    ("x [mm],y [mm]\n0,0,1\n", "line 2: 3 cells for 2 columns"),
]


@pytest.mark.parametrize("table, message", TABLE_FAULTS)
def test_a_bad_tuft_table_is_refused_in_one_line_naming_file_line_and_column(
        tmp_path, table, message):
    (tmp_path / "t.csv").write_text(table)
    (tmp_path / "c.toml").write_text('name = "t"\n[head]\nlayout = "tufts"\n'
                                     'tuft_table = "t.csv"\n')
    with pytest.raises(ParameterError) as caught:
        load_case(str(tmp_path / "c.toml"))
    text = str(caught.value)
    assert message.format(path=tmp_path / "t.csv") in text
    assert "\n" not in text


def test_a_tuft_table_longer_than_the_bristle_limit_is_refused_before_it_is_parsed(tmp_path):
    rows = "".join(f"{2 * i},0\n" for i in range(12))
    path = _case_with_table(tmp_path, "x [mm],y [mm]\n" + rows, "")
    with pytest.raises(ParameterError, match="has 12 tufts, more than limits.bristles = 10; to "
                       "read it anyway, --set limits.bristles=12"):
        load_case(str(path), ["limits.bristles=10"])


@pytest.mark.parametrize("overrides, message", [
    (['head.tuft_table="x.csv"'], "head: tuft_table is read for layout 'tufts' only (layout "
     "is 'grid'): set head.layout = 'tufts'"),
    (['head.layout="tufts"'], "head: layout 'tufts' needs [[head.tufts]] entries or a "
     "tuft_table"),
])
def test_tuft_settings_that_cannot_work_are_refused(overrides, message):
    with pytest.raises(ParameterError, match=message.replace("[", r"\[").replace("(", r"\(")
                       .replace(")", r"\)")):
        load_case("orthogonal", overrides)


def test_filaments_that_do_not_fit_their_tuft_are_refused_naming_the_tuft():
    case = tuft_case()
    narrow = case.replace(head=case.head.replace(tufts=(case.head.tufts[0].replace(
        diameter=1.2),)))
    with pytest.raises(ParameterError, match=r"head: tuft 'tuft': 37 filaments of 0.2 mm need "
                       r"a tuft of 1.4 mm in hexagonal packing, the tuft is 1.2 mm"):
        prepare(narrow)


def test_a_tuft_out_of_reach_is_a_warning_not_an_error(tmp_path):
    table = "x [mm],y [mm],length [mm]\n0,0,10.4\n3,0,5\n"
    prepared = prepare(load_case(str(_case_with_table(tmp_path, table)),
                                 ["motion.interaction_distance='8.4 mm'"]))
    assert prepared.warnings == ("head: tuft 'tufts.csv line 3' cannot reach the surface at "
                                 "motion.interaction_distance = 8.4 mm: its filaments never "
                                 "touch it",)
    assert prepared.reaching == (True,) * 37 + (False,) * 37


def test_bristles_that_can_touch_are_grouped_and_far_tufts_apart(tmp_path):
    # two tufts 10.4 mm long: roots 25 mm apart can never touch (2 x (10.4 + 0.1) < 25), the
    # third tuft 20 mm from the second can (21 mm of reach together)
    table = "x [mm],y [mm],filaments\n0,0,7\n25,0,7\n45,0,1\n"
    case = load_case(str(_case_with_table(tmp_path, table)), ["contact.between_bristles=true"])
    assert prepare(case).groups == (tuple(range(7)), tuple(range(7, 15)))


def test_groups_that_interleave_keep_ascending_indices():
    from dataclasses import replace

    from exubrush.models.geometry import touching_groups
    bristles = head_bristles(load_case("orthogonal").head)
    far = [replace(b, root=b.root + [60.0 * (i % 2), 0, 0]) for i, b in enumerate(bristles[:4])]
    assert touching_groups(far) == ((0, 2), (1, 3))


def test_a_run_with_contact_between_bristles_is_warned_of_its_cost():
    prepared = prepare(load_case("tuft", ["contact.between_bristles=true"]))
    assert prepared.groups == (tuple(range(37)),)
    # one warning naming the one system and its size (the measured times in it change with
    # each release)
    (warning,) = prepared.warnings
    assert warning.startswith("contact.between_bristles: 1 system(s), the largest of 37 "
                              "bristles that can touch, each solved on one core")


def test_the_manual_brush_is_40_tufts_of_37_filaments_that_reach_each_other():
    from exubrush.models.geometry import touching_groups

    case = load_case("manual-brush")
    bristles = head_bristles(case.head)
    assert len(case.head.tufts) == 40 and len(bristles) == 40 * 37
    # the typical ranges of docs/tufts.md: 20-50 tufts of 20-50 filaments, 0.15-0.25 mm, trim length
    # 10-11 mm, holes 1.5-2 mm
    tuft = case.head.tufts[0]
    assert 0.15 <= tuft.width <= 0.25 and 10.0 <= tuft.length + tuft.tip_radius <= 11.0
    assert 1.5 <= tuft.diameter <= 2.0
    # neighbouring tufts are within reach of each other: with contact the head is one group
    assert touching_groups(bristles) == (tuple(range(len(bristles))),)
    assert prepare(case).groups == tuple((i,) for i in range(len(bristles)))


def test_without_contact_between_bristles_each_bristle_is_its_own_group():
    assert prepare(load_case("tuft")).groups == tuple((i,) for i in range(37))
