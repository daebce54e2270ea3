"""``exubrush frames``: DFM and PRB runs drawn side by side, PNG frames and a GIF."""

import json

import numpy as np
import pytest
from PIL import Image

from exubrush.output.frames import load_shapes


@pytest.mark.slow
def test_frames_and_gif_of_two_models(two_model_runs, cli, tmp_path):
    runs = two_model_runs
    done = cli("frames", str(runs / "dfm"), str(runs / "prb"), "--times", "0,1.5",
               "--gif-frames", "5", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    pngs = sorted(tmp_path.glob("frame_*.png"))
    assert [p.name for p in pngs] == ["frame_000_t0000.000.png", "frame_001_t0001.500.png"]
    with Image.open(pngs[0]) as image:
        assert image.size[0] > image.size[1]  # two runs side by side
    with Image.open(tmp_path / "bristles.gif") as gif:
        assert gif.n_frames == 5


@pytest.mark.slow
def test_prb_drawing_puts_the_pivot_on_the_stub(two_model_runs):
    runs = two_model_runs
    shapes = load_shapes(runs / "prb")
    gamma = json.loads((runs / "prb" / "run.json").read_text())["derived"]["prb_gamma"]
    stub = np.linalg.norm(shapes.lines[:, :, 1] - shapes.lines[:, :, 0], axis=-1)
    link = np.linalg.norm(shapes.lines[:, :, 2] - shapes.lines[:, :, 1], axis=-1)
    # stub (1 - γ) l fixed to the handle; the link γ l long when unloaded, shorter where the
    # bristle is pushed (its sliding link, exubrush.models.buckling), never longer. 3e-4 mm
    # (7e-5 of the link; a misplaced pivot would be off by millimetres): the joint holds the
    # pivot on the link's axis only to the Newton tolerance, and shapes are linearly
    # interpolated onto the output grid between step ends (simulation.on_output_grid),
    # where the chord of the tip's arc over one step of at most 2 ms is up to ~6e-5 mm
    # shorter. In this short run the bristles are pressed, not buckled: < 2 % shorter.
    np.testing.assert_allclose(stub, (1.0 - gamma) * 5.0, rtol=1e-12)
    assert np.all(link <= gamma * 5.0 + 3e-4)
    assert np.all(link >= 0.98 * gamma * 5.0)


@pytest.mark.slow
def test_frames_refuse_times_outside_the_run(two_model_runs, cli, tmp_path):
    runs = two_model_runs
    done = cli("frames", str(runs / "dfm"), "--times", "99", "--out", str(tmp_path))
    assert done.returncode == 2
    assert "--times 99 s lie outside the stored shapes" in done.stderr
    assert "Traceback" not in done.stderr


def test_frames_refuse_a_directory_without_results(cli_here, tmp_path):
    done = cli_here("frames", str(tmp_path))
    assert done.returncode == 2 and "holds no run.json" in done.stderr
