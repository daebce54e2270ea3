"""Parallel brushing (paper case study): slide along the head, 30 mm sin(πt/12).

Run: ``python cases/parallel.py [dfm|prb]``; results go to ``results/parallel-MODEL``.
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "parallel")
run.__doc__ = "Simulate parallel brushing: run(model='dfm', overrides=(), progress=True)."

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/parallel-{model}')}")
