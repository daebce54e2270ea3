"""The commented sweep file ``exubrush sweep --example`` prints.

Its [sweep] and [execution] tables are written from their parameter dataclasses
(exubrush.sweep.settings) the way ``exubrush case`` writes a case, so every key carries its
help text and unit; what varies ([grid], [sample]) is written out here.
"""

from exubrush.parameters.fields import to_toml
from exubrush.sweep.settings import Execution, SweepSettings

HEADER = """\
# exubrush sweep file: one base case, what varies, where the runs are solved.
# Run it with:  exubrush sweep THIS_FILE.toml [--out DIR] [--scheduler tcp://HOST:8786]
# Every run is an ordinary run folder under the sweep folder; summary.csv tabulates them.
"""

VARIED = """
# [grid]: every combination of these values is run (here 2 x 3 = 6 runs).
# A value carries its unit wherever the parameter has one ('exubrush case orthogonal'
# lists every parameter with its unit).
[grid]
"head.bristle.length" = ["4.5 mm", "5 mm"]
"motion.interaction_distance" = { from = "4.0 mm", to = "4.4 mm", count = 3 }
# a logarithmic range:
# "head.material.youngs_modulus" = { from = "5 MPa", to = "20 MPa", count = 3, scale = "log" }
# text parameters take lists:
# "model.kind" = ["dfm", "prb"]

# [sample]: a seeded Latin hypercube over ranges (scipy.stats.qmc), crossed with the grid.
# [sample]
# count = 8
# seed = 1
# [sample.ranges]
# "contact.dynamic_friction" = { from = 0.6, to = 0.76 }
# "head.material.youngs_modulus" = { from = "5 MPa", to = "20 MPa", scale = "log" }

# [execution]: where the runs are solved (the command line's --scheduler and --workers win).
"""

EXAMPLE_SWEEP = SweepSettings(name="length-and-distance", base="orthogonal",
                              set=("motion.periods=2",), seeds=(1,), max_runs=100)

EXAMPLE = (f"{HEADER}\n[sweep]\n{to_toml(EXAMPLE_SWEEP)}{VARIED}[execution]\n"
           f"{to_toml(Execution())}")
