"""The validation notebooks that take longest (tens of seconds each on 2 cores, and
shear_beam.ipynb's 4-6 s) belong to the slow tier; ``python -m pytest -m "not slow"`` leaves
them out."""

import pytest

SLOW_NOTEBOOKS = {"howell_parameters.ipynb", "sliding_bristle.ipynb", "surfaces.ipynb",
                  "bristle_contact.ipynb", "head_contact.ipynb", "elastica_convergence.ipynb",
                  "shear_beam.ipynb", "reversal_peaks.ipynb"}


def pytest_collection_modifyitems(items):
    for item in items:
        if item.path.name in SLOW_NOTEBOOKS:
            item.add_marker(pytest.mark.slow)
