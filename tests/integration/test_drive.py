"""The drive: the handle follows the prescribed motion, also for a measured slide.

The offsets are set before every step (scene.add_drive), not by an offset user function
called in every Newton iteration; the solver imposes them at the step's end. Here the
handle's solved coordinates are read back and compared with the slide and descent
prescribed for the same instants, within what recording them costs. Against the former
offset user function, this run's coordinates and the default orthogonal, parallel, PRB and
viewer runs are byte-identical (forces, shapes, solver statistics; CHANGELOG 0.4.0).
"""

import numpy as np
import pytest

from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.run.solve import solve_group

# an irregular measured-like slide: uneven samples, both directions, a rest; it starts at
# rest (two equal samples: PCHIP's slope is 0 there), as a slide with a velocity jump at its
# start would put a kink into the motion that no recording interval resolves
SLIDE = ("time [s],slider_position [mm]\n0,0\n0.2,0\n0.5,1.2\n0.75,1.5\n1.1,-0.8\n"
         "1.4,-0.8\n1.8,2.0\n2.2,0.4\n")


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_the_handle_follows_a_csv_slide_and_the_descent(tmp_path):
    path = tmp_path / "slide.csv"
    path.write_text(SLIDE)
    step = 2e-3  # s: the default step, also the recording interval here
    prepared = prepare(load_case("orthogonal", [
        "motion.profile='csv'", f"motion.csv_file='{path}'", "head.rows=1", "head.columns=1",
        "output.solution_file=true", f"output.interval='{step} s'",
        f"output.shape_interval='{10 * step} s'"]))
    solution = solve_group(prepared, prepared.groups[0])
    assert solution.completed
    time, handle = solution.coordinates[:, 0], solution.coordinates[:, 1:7]
    motion, axis = prepared.motion, prepared.slide_axis
    expected = np.array([axis * motion.sliding(t)[0] - [0.0, 0.0, motion.descent(t)[0]]
                         for t in time])
    assert time[-1] > motion.slide_start + 1.5  # the whole slide was driven
    # The coordinates are recorded at the solver's step ends and put on the shape grid by
    # linear interpolation between records `step` apart: that alone may differ from the
    # exact motion by max|acceleration| * step^2 / 8. A drive one step late would be off by
    # speed * step, 10-1000x more.
    fine = np.linspace(0.0, time[-1], 20001)
    acceleration = max(max(abs(motion.sliding(t)[2]), abs(motion.descent(t)[2])) for t in fine)
    bound = acceleration * step**2 / 8 + 1e-9
    speed = max(max(abs(motion.sliding(t)[1]), abs(motion.descent(t)[1])) for t in fine)
    assert bound < speed * step / 10
    np.testing.assert_allclose(handle[:, :3], expected, rtol=0, atol=bound)
    np.testing.assert_allclose(handle[:, 3:], 0.0, rtol=0, atol=1e-9)  # no rotation
