"""Shared test helpers."""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from exubrush.output.experiment import ForceSeries

OMEGA = math.pi / 6.0  # rad/s, the orthogonal case's slide: x = 15 mm sin(ω t)


def _sine_run(t0=1.2, t_end=25.2, dt=0.01, scale=1.0):
    """A slide with a flat force level and a bump at every reversal (synthetic)."""
    t = np.arange(0.0, t_end + dt / 2, dt)
    tau = np.clip(t - t0, 0.0, None)
    x = 15.0 * np.sin(OMEGA * tau)
    v = 15.0 * OMEGA * np.cos(OMEGA * tau) * (t > t0)
    bump = np.exp(-(v / 2.0) ** 2) * (t > t0)
    normal = scale * (1.0 + 0.5 * bump)
    tangential = scale * 0.7 * np.tanh(v)
    return ForceSeries(t, x, normal, tangential)



@pytest.fixture
def sine_run():
    """Factory of a synthetic sine slide with flat forces and a bump at each reversal."""
    return _sine_run


BENCHMARKS = Path(__file__).parents[1] / "validation" / "benchmarks"


@pytest.fixture
def benchmark_script(monkeypatch):
    """Loader of a script of validation/benchmarks by name (e.g. "split_rates"), with its
    folder on the import path for its sibling modules (benchmark.py, one_bristle.py)."""

    def load(name):
        monkeypatch.syspath_prepend(str(BENCHMARKS))
        spec = importlib.util.spec_from_file_location(name, BENCHMARKS / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module

    return load
