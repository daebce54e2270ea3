"""Bristle frames drawn from a saved run (no solve: the shapes are made up here)."""

import numpy as np
import pytest
from PIL import Image

from exubrush.output.frames import load_shapes, tube_outline, write_animation, write_frames
from exubrush.output.results import Results
from exubrush.parameters.fields import to_plain
from exubrush.parameters.io import load_case


def _saved_run(directory, model):
    """A two-bristle run of ``model`` whose tips swing sideways (made-up shapes)."""
    # a shape at every force sample, three DFM segments: as the run.json says
    case = load_case("orthogonal", ["head.rows=1", "head.columns=2", f"model.kind={model}",
                                    "model.segments=3", "output.interval='0.1 s'"])
    time = np.linspace(0.0, 1.0, 11)
    nodes_per_bristle = 1 if model == "prb" else 3
    roots = np.array([[-0.9, 0.0, 4.0], [0.9, 0.0, 4.0]])
    nodes = np.zeros((len(time), 2, nodes_per_bristle + 1, 3))
    for k in range(nodes_per_bristle + 1):
        s = k / nodes_per_bristle  # 0 at the root, 1 at the tip
        nodes[:, :, k] = roots - s * np.array([0.0, 0.0, 3.5])
        nodes[:, :, k, 1] += s**2 * np.sin(np.pi * time)[:, None]
    zero = np.zeros(len(time))
    metadata = {"case": case.name, "model": model, "parameters": to_plain(case),
                "derived": {"prb_gamma": 0.85}, "status": "completed"}
    Results(time=time, slider_position=zero, normal_force=zero, tangential_force=zero,
            head_height=zero + 4.0, shape_time=time, shape_nodes=nodes,
            metadata=metadata).save(directory)
    return directory


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_frames_and_animation_of_two_saved_runs(tmp_path):
    runs = [load_shapes(_saved_run(tmp_path / model, model)) for model in ("dfm", "prb")]
    # the PRB line gains its pivot: root, pivot at (1 - γ) l along the bristle, tip
    assert runs[1].lines.shape[2] == 3
    stub = np.linalg.norm(runs[1].lines[:, :, 1] - runs[1].lines[:, :, 0], axis=-1)
    np.testing.assert_allclose(stub, 0.15 * 5.0, rtol=1e-12)
    names = write_frames(runs, [0.0, 0.5], tmp_path)
    assert names == ["frame_000_t0000.000.png", "frame_001_t0000.500.png"]
    with Image.open(tmp_path / names[0]) as image:
        assert image.size[0] > image.size[1]  # two runs side by side
    calls = []
    write_animation(runs, runs[0].time[:4], tmp_path / "bristles.gif",
                    progress=lambda i, n: calls.append(i))
    with Image.open(tmp_path / "bristles.gif") as gif:
        assert gif.n_frames == 4
    assert len(calls) == 4


def test_a_tube_is_its_centreline_offset_by_the_radius_on_both_sides():
    bent = np.array([[0.0, 0.0], [0.0, 1.0], [1.0, 2.0]])  # straight up, then 45 degrees
    outline = tube_outline(bent, 0.1)
    assert outline.shape == (6, 2)
    np.testing.assert_allclose(outline[0], [-0.1, 0.0], atol=1e-15)  # root: across the axis
    np.testing.assert_allclose(outline[-1], [0.1, 0.0], atol=1e-15)
    # every outline point lies exactly one radius from its centreline point
    np.testing.assert_allclose(np.linalg.norm(outline[:3] - bent, axis=1), 0.1, rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(outline[3:][::-1] - bent, axis=1), 0.1,
                               rtol=1e-12)
