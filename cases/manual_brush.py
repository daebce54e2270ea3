"""A typical manual toothbrush: 40 tufts (4 rows of 10) of 37 round nylon filaments each
(0.2 mm, hexagonal in 1.6 mm holes, 10.5 mm trim length), 1,480 filaments, slide 15 mm
sin(πt/6) across a plane at d = 8.4 mm for one period. Every filament is its own system
(contact between bristles off: with it the whole head would be one system, docs/tufts.md).

Run: ``python cases/manual_brush.py [dfm|prb]``; results go to ``results/manual-brush-MODEL``.
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "manual-brush")
run.__doc__ = ("Simulate a full manual toothbrush head brushing a plane: "
               "run(model='dfm', overrides=(), progress=True).")

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/manual-brush-{model}')}")
