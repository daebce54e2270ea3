"""Each tuft's force on the surface (exubrush.output.tufts) and tufts.csv."""

import numpy as np

from exubrush.output.tufts import tuft_columns, tuft_forces


def test_a_tufts_force_is_minus_the_surfaces_force_on_its_tips():
    rng = np.random.default_rng(2)
    tip_force = rng.normal(size=(5, 6, 3))
    forces = tuft_forces(tip_force, [0, 1, 0, None, 1, 1], 2)
    np.testing.assert_array_equal(forces[:, 0], -(tip_force[:, 0] + tip_force[:, 2]))
    np.testing.assert_array_equal(forces[:, 1],
                                  -(tip_force[:, 1] + tip_force[:, 4] + tip_force[:, 5]))


def test_tufts_csv_names_each_tufts_components():
    columns = tuft_columns(["centre", "tufts[1]"], np.arange(3.0), np.ones((3, 2, 3)))
    assert list(columns) == ["time [s]", "centre.force_x [N]", "centre.force_y [N]",
                             "centre.force_z [N]", "tufts[1].force_x [N]",
                             "tufts[1].force_y [N]", "tufts[1].force_z [N]"]
