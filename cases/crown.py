"""Crown brushing: the default head slides 15 mm sin(πt/6) along a cylinder of 4 mm radius
(a tooth crown).

Run: ``python cases/crown.py [dfm|prb]``; results go to ``results/crown-MODEL``.
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "crown")
run.__doc__ = "Simulate crown brushing: run(model='dfm', overrides=(), progress=True)."

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/crown-{model}')}")
