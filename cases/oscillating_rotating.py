"""An oscillating-rotating round head: 19 tufts of 37 nylon filaments (0.2 mm, 10.5 mm trim
length) in a centre tuft and rings of 6 and 12 on an 11 mm disc, pressed on a plane at
d = 8.4 mm and turned ±20° about its normal at 7,600 oscillations a minute for 0.5 s
(docs/motion.md, "The powered-brush cases"). Filaments pass through each other unless
contact between them is switched on.

Run: ``python cases/oscillating_rotating.py [dfm|prb]``; results go to
``results/oscillating-rotating-MODEL``.
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "oscillating-rotating")
run.__doc__ = ("Simulate the oscillating-rotating head on a plane: run(model='dfm', "
               "overrides=(), progress=True).")

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/oscillating-rotating-{model}')}")
