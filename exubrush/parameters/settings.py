"""The numerical settings of a case: Exudyn's solver, what is recorded and the limits of
the work a run may ask (sections of :class:`exubrush.parameters.case.Case`).
"""

from __future__ import annotations

from dataclasses import dataclass

from exubrush.parameters.fields import Parameters, param


@dataclass(frozen=True)
class Solver(Parameters):
    """Exudyn implicit solver settings (generalized-alpha with automatic step reduction).

    The defaults are the ``balanced`` preset (exubrush.presets); why each is what it is,
    with measurements, is in the decision records docs/decisions/ (index in
    validation/benchmarks/README.md).
    """

    RENAMED = {
        "user_functions": "renamed contact.backend: 'symbolic' is now 'paper-symbolic', "
                          "'python' 'paper-python', 'builtin' 'exudyn-builtin'",
    }

    step_size: float = param(2e-3, "largest time step (the step is cut where Newton fails)",
                             "s", "ms", above=0.0)
    sliding_step_factor: float = param(
        5.0, "while the head slides at sliding_speed_fraction of its peak speed or faster "
             "over a plane, cylinder or sphere (a tooth row: with every tip over a flat top), "
             "the step may grow to this multiple of step_size, at most output.interval (1: "
             "step_size throughout; docs/model.md, 'Steps in the middle of a stroke')",
        minimum=1.0, below=100.0,
    )
    sliding_speed_fraction: float = param(
        0.3, "the head slides 'in the middle of a stroke' (sliding_step_factor) at this "
             "fraction of its peak speed or faster, and at 1.5 contact.dynamic_velocity or "
             "faster", above=0.0, below=1.0,
    )
    friction_drop: str = param(
        "lagged",
        "how a step takes the friction law's fall from mu_s to mu_d: lagged = at the slip "
        "speed of the step's start, the rise to mu_s within Newton; implicit = all within "
        "Newton (Newton fails where the falling friction outweighs a small tip's inertia; "
        "docs/model.md, 'The friction drop, one step behind')",
        "text", choices=("lagged", "implicit"),
    )
    step_cut: float = param(
        0.25, "factor by which a step is cut after Newton fails (Exudyn's "
              "adaptiveStepDecrease; Exudyn's default 0.5): a snapping tip's microsecond "
              "steps are reached in fewer failed tries (docs/decisions/0016)",
        above=0.0, below=1.0,
    )
    minimum_step_size: float = param(1e-9, "smallest step of the automatic step reduction",
                                     "s", above=0.0)
    spectral_radius: float = param(
        0.0, "generalized-alpha spectral radius at infinity (0 = most damping)", minimum=0.0
    )
    # below 1: at 1 or more Newton takes a step's first guess as converged, and the run
    # failed later with a misleading cause
    relative_tolerance: float = param(1e-6, "Newton relative tolerance", above=0.0, below=1.0)
    touching_relative_tolerance: float = param(
        1e-5, "Newton relative tolerance of a group of bristles that touch each other "
              "(contact.between_bristles)", above=0.0, below=1.0,
    )
    absolute_tolerance: float = param(1e-10, "Newton absolute tolerance (residual)", above=0.0)
    # below 1e-2: larger ones move the flat-zone forces, and a tolerance near the buckling
    # load itself accepts any first guess, so that a run "completes" with wrong forces
    # (docs/model.md, "Newton's tolerance"; docs/decisions/0013)
    force_tolerance: float = param(
        5e-4, "Newton also accepts a step whose residual is below this fraction of the Euler "
              "buckling load of the weakest bristle solved with it (0: off; "
              "docs/model.md, 'Newton's tolerance')", minimum=0.0, below=1e-2,
    )
    modified_newton: bool = param(True, "reuse the Jacobian between Newton iterations and "
                                        "steps (false: a fresh Jacobian every iteration)")
    newton_contractivity: float = param(
        0.5, "modified Newton makes a new Jacobian when an iteration shrinks the residual by "
             "less than this factor (Exudyn's modifiedNewtonContractivity); 1 was faster on "
             "the interdental case but moved the forces (docs/decisions/0018)",
        above=0.0, below=10.0,
    )
    # below 10, one-bristle solves failed at a reversal (docs/decisions/0002, 0007)
    newton_iterations: int = param(
        12, "Newton iterations before a step is given up and cut", minimum=10,
    )
    touching_give_up: float = param(
        0.1, "in a group of bristles that touch each other, a step attempt whose Newton "
             "residual after two updates or more is still above this share of its first is "
             "given up and the step cut at once, instead of after newton_iterations; so is "
             "one that Exudyn restarts from its third iteration on; never at the minimum "
             "step (0: never; runs where the line search runs; docs/decisions/0026)",
        minimum=0.0, below=1.0,
    )
    line_search: str = param(
        "auto",
        "shorten Newton's updates until the residual falls (a backtracking line search): "
        "always = at every iteration, after-cut = while the step is below its largest after "
        "a cut, off = Exudyn's full updates, auto = always in a group of touching bristles, "
        "off elsewhere and on rotation-vector nodes (docs/decisions/"
        "0001-newton-line-search.md)",
        "text", choices=("auto", "always", "after-cut", "off"),
    )
    linear_solver: str = param(
        "auto",
        "linear solver of Newton's steps: auto = EigenDense for one bristle, EigenSparse for "
        "a coupled head",
        "text", choices=("auto", "EigenDense", "EXUdense", "EigenSparse"),
    )
    steps_per_cycle: int = param(
        160, "while a [[motion.sine]] term acts, the step is at most its cycle over this: "
             "20 resolve the drive, 160 what a stuck tip and the head's moment do under a "
             "turn (docs/motion.md, 'How many steps a cycle')", minimum=4,
    )
    step_recovery_steps: int = param(
        4, "successful steps after a step reduction before the step may grow again (Exudyn's "
           "default 10; docs/decisions/0016)",
        minimum=1,
    )
    partition: str = param(
        "per-bristle",
        "per-bristle: each bristle its own system, solved in parallel processes (bristles do "
        "not touch each other); coupled: the whole head as one system",
        "text", choices=("per-bristle", "coupled"),
    )
    share_identical: bool = param(
        True, "solve once the bristles that differ only by where their roots sit, on a plane "
              "and a head that does not turn, without contact between bristles (a tuft's "
              "filaments; exubrush.run.twins)")
    threads: int = param(
        1, "Exudyn threads for a coupled head (needs contact.backend exudyn-builtin)",
        minimum=1,
    )

    def check(self) -> None:
        """Spectral radius within [0, 1]; minimum step below the step; threads only for a
        coupled head."""
        if self.spectral_radius > 1.0:
            raise ValueError(f"spectral_radius {self.spectral_radius:g} must be <= 1")
        if self.minimum_step_size > self.step_size:
            raise ValueError("minimum_step_size must not exceed step_size")
        if self.threads > 1 and self.partition != "coupled":
            raise ValueError(
                f"threads = {self.threads} needs partition 'coupled': per-bristle already "
                "solves one bristle per process on every core"
            )


@dataclass(frozen=True)
class Output(Parameters):
    """What is recorded."""

    interval: float = param(0.01, "force output interval", "s", above=0.0)
    shape_interval: float = param(0.1, "bristle shape output interval", "s", above=0.0)
    solution_file: bool = param(
        False, "also keep every node's coordinates at shape_interval, for Exudyn's "
        "SolutionViewer (exubrush view)")

    @property
    def shape_stride(self) -> int:
        """Force samples per shape sample: shapes are every this many force samples from
        the first [-]."""
        return max(1, round(self.shape_interval / self.interval))

    def shape_samples(self, samples: int) -> int:
        """Shape samples among ``samples`` force samples: every :attr:`shape_stride`-th
        from the first [-]."""
        return -(-samples // self.shape_stride)

    def check(self) -> None:
        """Shapes are sampled from the force output, so not more often than it."""
        if self.shape_interval < self.interval:
            raise ValueError(f"shape_interval ({self.shape_interval:g} s) must not be shorter "
                             f"than interval ({self.interval:g} s)")


@dataclass(frozen=True)
class Limits(Parameters):
    """Bounds on the work a run may take on, checked before anything is built
    (exubrush.run.budget). Generous for real studies; raise them to run bigger ones. They do
    not change results, so a run that only raises a limit resumes its checkpoint."""

    bristles: int = param(10_000, "most bristles in a head", above=0)
    segments: int = param(200, "most DFM bodies per bristle", above=0)
    steps: int = param(
        20_000_000, "most time steps per solved system at solver.step_size (end time / step)",
        above=0)
    memory: float = param(8e9, "most memory the recorded results may take (estimate)", "B",
                          "GB", above=0.0)
    term_evaluations: float = param(
        1e7, "most evaluations of the pose terms per solved system: (motion.sine terms + a "
             "pose table) x time steps; each is evaluated in Python at every step (its cost: "
             "docs/runs.md)", above=0.0)
