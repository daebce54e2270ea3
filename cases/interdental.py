"""Interdental brushing: the default head slides 15 mm sin(πt/6) across a row of teeth
with 1 mm gaps.

Run: ``python cases/interdental.py [dfm|prb]``; results go to ``results/interdental-MODEL``.
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "interdental")
run.__doc__ = "Simulate interdental brushing: run(model='dfm', overrides=(), progress=True)."

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/interdental-{model}')}")
