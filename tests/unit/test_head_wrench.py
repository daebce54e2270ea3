"""The head's force and moment in forces.csv: written after the older columns, read back,
absent from runs of exubrush 0.13.0 (read as before), refused when only some are there."""

import numpy as np
import pytest

from exubrush.output.results import (
    CSV_COLUMNS,
    WRENCH_COLUMNS,
    HeadWrench,
    Results,
    ResultsError,
    read_results,
)
from exubrush.world.kinematics import in_head_frame
from exubrush.world.pose import rotation_matrix


def _results(wrench=None):
    t = np.linspace(0.0, 1.0, 11)
    return Results(t, np.sin(t), np.ones_like(t), 0.5 * np.ones_like(t), np.zeros_like(t),
                   np.zeros(0), np.zeros((0, 0, 0, 3)),
                   metadata={"case": "made-up", "model": "dfm", "status": "completed"},
                   wrench=wrench)


def _wrench():
    rng = np.random.default_rng(4)
    force, moment = rng.normal(size=(11, 3)), rng.normal(size=(11, 3))
    angles = rng.uniform(-0.5, 0.5, (11, 3))
    return HeadWrench(force, moment, in_head_frame(force, angles),
                      in_head_frame(moment, angles))


def test_the_wrench_is_written_after_the_old_columns_and_read_back(tmp_path):
    wrench = _wrench()
    _results(wrench).save(tmp_path)
    header = (tmp_path / "forces.csv").read_text().splitlines()[0].split(",")
    assert header == [f"{n} [{u}]" for n, u in (*CSV_COLUMNS, *WRENCH_COLUMNS)]
    back = read_results(tmp_path).wrench
    for name in ("force", "moment", "head_force", "head_moment"):
        # written with 9 significant digits (util.files.write_csv)
        np.testing.assert_allclose(getattr(back, name), getattr(wrench, name), rtol=1e-8,
                                   atol=1e-12)


def test_a_run_without_the_wrench_reads_as_before(tmp_path):
    _results().save(tmp_path)
    assert read_results(tmp_path).wrench is None


def test_some_wrench_columns_without_the_others_are_refused(tmp_path):
    _results(_wrench()).save(tmp_path)
    path = tmp_path / "forces.csv"
    rows = [line.split(",") for line in path.read_text().splitlines()]
    path.write_text("\n".join(",".join(row[:-1]) for row in rows) + "\n")
    with pytest.raises(ResultsError, match="some of the head's force and moment columns"):
        read_results(tmp_path)


def test_the_head_frame_turns_with_the_head():
    angles = np.array([[0.0, 0.0, np.pi / 2], [0.3, -0.2, 0.1]])
    vectors = np.array([[1.0, 0.0, 0.0], [0.0, 2.0, -1.0]])
    turned = in_head_frame(vectors, angles)
    # a quarter turn about z: the surface's x axis is the head's -y axis
    np.testing.assert_allclose(turned[0], [0.0, -1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(rotation_matrix(angles[1]) @ turned[1], vectors[1], atol=1e-15)
