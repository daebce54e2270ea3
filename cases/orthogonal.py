"""Orthogonal brushing (paper case study): slide across the head, 15 mm sin(πt/6).

Run: ``python cases/orthogonal.py [dfm|prb]``; results go to ``results/orthogonal-MODEL``.
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "orthogonal")
run.__doc__ = "Simulate orthogonal brushing: run(model='dfm', overrides=(), progress=True)."

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/orthogonal-{model}')}")
