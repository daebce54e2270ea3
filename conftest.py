"""The repository's first conftest, loaded before pytest-xdist starts its workers: one BLAS
thread per test process, and the files in the order the workers should take them.

The suite runs two workers on the two cores. OpenBLAS gives every process as many threads
as there are cores, and their spinning threads then compete: a touching-cantilevers
reference solve (scipy SLSQP and NNLS) took 3 s alone and 25-35 s beside another worker.
The workers, their notebook kernels and the command lines they start inherit these
variables; one already set is kept.
"""

import os

import pytest

for variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(variable, "1")


@pytest.hookimpl(trylast=True)  # after validation/conftest.py has marked its notebooks slow
def pytest_collection_modifyitems(items):
    """Files with slow tests first, the notebooks first of all; the rest keep their order.

    A worker takes a whole file at a time (--dist loadfile) and is handed its next one
    before it has finished the one it has. A notebook is a single test of up to 2.5 min, a
    slow file up to 2.5 min of fits or runs. Put last, as pytest-xdist's own order (files
    by their number of tests, most first) puts the notebooks, one of them kept one worker
    busy for the last 136-140 s of a 596-606 s full run while the other had nothing left.
    Put first, they leave the fast tier's 900 short tests (about 90 s of work) to fill in
    whichever worker is done first: 520-542 s.
    """
    slow_files = {item.path for item in items if item.get_closest_marker("slow")}
    items.sort(key=lambda item: (item.path not in slow_files, item.path.suffix != ".ipynb"))
