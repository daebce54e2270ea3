"""One tuft: 37 round nylon filaments (0.2 mm, hexagonal in a 1.6 mm hole, 10.5 mm trim
length) slide 15 mm sin(πt/6) across a plane at d = 8.4 mm, bending far beyond the linear
range. The filaments pass through each other unless contact between them is switched on
(``overrides=("contact.between_bristles=true",)``), which is still slow (docs/tufts.md).

Run: ``python cases/tuft.py [dfm|prb]``; results go to ``results/tuft-MODEL``.
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "tuft")
run.__doc__ = "Simulate one tuft brushing a plane: run(model='dfm', overrides=(), progress=True)."

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/tuft-{model}')}")
