"""A sonic head: the manual-brush head (40 tufts of 37 nylon filaments, 0.2 mm, 10.5 mm
trim length) swung side to side across the handle by ±1.5 mm at 258 Hz (31,000 strokes a
minute) on a slow manual stroke along the handle (±15 mm in 4 s), pressed on a plane at
d = 8.4 mm, for 0.5 s after the approach (docs/motion.md, "The powered-brush cases").
Filaments pass through each other unless contact between them is switched on.

Run: ``python cases/sonic.py [dfm|prb]``; results go to ``results/sonic-MODEL``.
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "sonic")
run.__doc__ = ("Simulate the sonic head on a plane: run(model='dfm', overrides=(), "
               "progress=True).")

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/sonic-{model}')}")
