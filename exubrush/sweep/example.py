"""The commented sweep file ``exubrush sweep --example`` prints."""

EXAMPLE = '''\
# exubrush sweep file: one base case, what varies, where the runs are solved.
# Run it with:  exubrush sweep THIS_FILE.toml [--out DIR] [--scheduler tcp://HOST:8786]
# Every run is an ordinary run folder under the sweep folder; summary.csv tabulates them.

[sweep]
name = "length-and-distance"   # names the sweep folder (default: the file's name)
base = "orthogonal"            # a built-in case (orthogonal, parallel) or a TOML case file,
                               # relative to this file
set = ["motion.periods=2"]     # --set overrides applied to every run
seeds = [1]                    # repeat every run once per head.seed (root-tilt directions)
max_runs = 100                 # refuse a sweep that expands to more runs than this

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
[execution]
scheduler = "local"            # a Dask cluster on this machine, or tcp://HOST:PORT
# workers = 2                  # local cluster processes (default: every core)
timeout = "10 s"               # to reach a scheduler
'''
