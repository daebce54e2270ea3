"""The repository's first conftest, loaded before pytest-xdist starts its workers: one BLAS
thread per test process.

The suite runs two workers on the two cores. OpenBLAS gives every process as many threads
as there are cores, and their spinning threads then compete: a touching-cantilevers
reference solve (scipy SLSQP and NNLS) took 3 s alone and 25-35 s beside another worker.
The workers, their notebook kernels and the command lines they start inherit these
variables; one already set is kept.
"""

import os

for variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(variable, "1")
