"""The head's slide along one axis (pure, mm-s units): a sine, a table read from a CSV
(interpolated by a monotone cubic), or none; and the quintic smooth step that the approach
and the pose terms' ramps share.

Each gives position, velocity and acceleration consistently, so the Exudyn drive and the
inertia correction of the handle force use the same motion. The head's whole motion
(approach, hold, slide, pose terms) is :class:`exubrush.world.motion.HeadMotion`.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from exubrush.util.tables import check_time_axis, read_unit_table


def smooth_step(tau: float) -> tuple[float, float, float]:
    """Quintic step s(τ) = 10τ³ - 15τ⁴ + 6τ⁵ clamped to [0, 1], with s' and s''."""
    if tau <= 0.0:
        return 0.0, 0.0, 0.0
    if tau >= 1.0:
        return 1.0, 0.0, 0.0
    return (
        tau**3 * (10.0 - 15.0 * tau + 6.0 * tau**2),
        30.0 * tau**2 * (1.0 - tau) ** 2,
        60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau),
    )


@dataclass(frozen=True)
class SineSlide:
    """Slide s(τ) = A sin(2π τ / T) for ``periods`` periods.

    Attributes
    ----------
    amplitude : float
        A [mm].
    period : float
        T [s].
    periods : float
        Number of periods simulated [-].
    """

    amplitude: float
    period: float
    periods: float

    @property
    def duration(self) -> float:
        """Slide duration [s]."""
        return self.period * self.periods

    @property
    def peak_speed(self) -> float:
        """Largest slide speed, 2π A / T [mm/s]."""
        return 2.0 * math.pi * self.amplitude / self.period

    @property
    def peak_acceleration(self) -> float:
        """Largest slide acceleration, A (2π / T)² [mm/s²]."""
        return self.amplitude * (2.0 * math.pi / self.period) ** 2

    def velocities(self, taus: np.ndarray) -> np.ndarray:
        """Velocity [mm/s] at each slide time τ [s] of ``taus`` (element-wise)."""
        omega = 2.0 * math.pi / self.period
        return self.amplitude * omega * np.cos(omega * np.asarray(taus, dtype=float))

    def evaluate(self, tau: float) -> tuple[float, float, float]:
        """Position [mm], velocity [mm/s] and acceleration [mm/s²] at slide time τ [s]."""
        omega = 2.0 * math.pi / self.period
        return (
            self.amplitude * math.sin(omega * tau),
            self.amplitude * omega * math.cos(omega * tau),
            -self.amplitude * omega**2 * math.sin(omega * tau),
        )


# What a table (a slide CSV, a pose table's column) may ask of a brush head, in internal
# units: beyond it a row is a typo or damage, not a motion, and would end in a solver
# failure instead of a refusal (a cell of 1e300 mm did). A head held by a hand or a robot
# arm stays within its reach of about 1 m; 10 m is the bound. Turning, it may spin for a
# long run: 10,000 rad (1,600 turns). Its speed: 100 m/s, forty times a sonic head's swing
# (2.4 m/s, the fastest head of docs/motion.md); its turning rate 100,000 rad/s, more than
# twice a dental turbine's 400,000 rpm (the oscillating-rotating head peaks at 280 rad/s).
TABLE_REACH = {"mm": 1e4, "rad": 1e4}  # from the table's first row [mm, rad]
TABLE_RATE = {"mm": 1e5, "rad": 1e5}  # [mm/s, rad/s]


class TabulatedSlide:
    """Slide read from measured samples, interpolated by a monotone cubic (PCHIP).

    Between two samples the slider moves monotonically from one to the other, so it never
    leaves the range of the data (a C² spline through a 0 -> 10 mm step in 1 s samples
    reaches 11.08 mm and -1.08 mm, and rings after a corner). The price: velocity is
    continuous but acceleration jumps at the samples, and the velocity is zero wherever the
    data have a local extremum. The interpolant starts at position 0 (the first sample is
    taken as the origin); its first derivative is the drive velocity, so position and
    velocity agree.

    A table that moves the head further from its first sample than :data:`TABLE_REACH` or
    faster than :data:`TABLE_RATE` is refused (ValueError naming ``label``), as is one
    whose times do not increase or that holds a number that is not finite.

    Parameters
    ----------
    times, positions : (n,) arrays
        Samples [s] and [``unit``], n >= 2.
    label, unit : str
        The column's name, for messages, and its unit: "mm" (a slide, a translation) or
        "rad" (a turn).
    """

    def __init__(self, times: np.ndarray, positions: np.ndarray,
                 label: str = "slider_position", unit: str = "mm"):
        times = np.asarray(times, dtype=float)
        positions = np.asarray(positions, dtype=float)
        if times.ndim != 1 or times.shape != positions.shape or times.size < 2:
            raise ValueError("a slide table needs at least two (time, position) rows")
        check_time_axis(times, positions)
        with np.errstate(over="ignore"):  # 1e308 - -1e308: inf, refused
            reach = np.abs(positions - positions[0])
        far = np.flatnonzero(reach > TABLE_REACH[unit])
        if far.size:
            k = far[0]
            raise ValueError(f"'{label}' is {reach[k]:.3g} {unit} from its first row at sample "
                             f"{k + 1} (t = {times[k]:g} s), beyond the {TABLE_REACH[unit]:g} "
                             f"{unit} a brush head can move (docs/motion.md, 'Pose tables')")
        from scipy.interpolate import PchipInterpolator  # 0.4-1 s of import: tables only

        self._t0 = float(times[0])
        # slopes between samples a denormal apart overflow PCHIP's harmonic mean to a slope
        # of 0, which is right; numpy would warn
        with np.errstate(over="ignore", divide="ignore"):
            self._spline = PchipInterpolator(times - times[0], positions - positions[0])
        self.duration = float(times[-1] - times[0])
        rate = self.peak_speed
        if not rate <= TABLE_RATE[unit]:
            raise ValueError(f"'{label}' changes at up to {rate:.3g} {unit}/s, faster than the "
                             f"{TABLE_RATE[unit]:g} {unit}/s a brush head can move "
                             "(docs/motion.md, 'Pose tables'); check the times and values")

    def evaluate(self, tau: float) -> tuple[float, float, float]:
        """Position [mm], velocity [mm/s] and acceleration [mm/s²] at slide time τ [s]."""
        tau = min(max(tau, 0.0), self.duration)
        return tuple(float(self._spline(tau, k)) for k in range(3))

    def velocities(self, taus: np.ndarray) -> np.ndarray:
        """Velocity [mm/s] at each slide time τ [s] of ``taus`` (element-wise, held at the
        table's ends as :meth:`evaluate`)."""
        return self._spline(np.clip(np.asarray(taus, dtype=float), 0.0, self.duration), 1)

    @property
    def peak_speed(self) -> float:
        """Largest slide speed [mm/s], exact: on each interval the interpolant's speed is a
        quadratic 3a x² + 2b x + c (x from the interval's start), largest in size at an
        end or at its vertex x = -b / (3a)."""
        a, b, c = self._spline.c[:3]
        width = np.diff(self._spline.x)
        with np.errstate(divide="ignore", invalid="ignore"):
            vertex = np.where(a != 0.0, -b / (3.0 * a), 0.0)
        vertex = np.clip(vertex, 0.0, width)
        speeds = [3.0 * a * x * x + 2.0 * b * x + c for x in (0.0, width, vertex)]
        return float(np.max(np.abs(speeds)))

    @property
    def peak_acceleration(self) -> float:
        """Largest |slide acceleration| [mm/s²], exact: on each interval the interpolant's
        acceleration 6a x + 2b is linear, largest in size at one of its ends."""
        a, b = self._spline.c[:2]
        width = np.diff(self._spline.x)
        return float(max(np.max(np.abs(2.0 * b)), np.max(np.abs(6.0 * a * width + 2.0 * b))))

    @property
    def digest(self) -> str:
        """SHA-256 of the interpolant (sample times and polynomial coefficients): equal for
        equal profiles, whatever else the file holds (comments, other columns)."""
        spline = self._spline
        return hashlib.sha256(spline.x.tobytes() + spline.c.tobytes()).hexdigest()

    def largest_speed_change(self, window: float) -> tuple[float, float]:
        """Largest change of the slide speed [mm/s] within any interval of ``window`` [s],
        and the slide time τ [s] where that interval starts.

        The speed is sampled at a quarter of ``window`` (at most a million samples: a longer
        profile is sampled more coarsely, which can only overstate the change). Not the peak
        acceleration times the window: at a local extremum of finely sampled data the
        monotone cubic's acceleration spikes within one sample interval, while the speed
        hardly changes.
        """
        spacing = max(window / 4.0, self.duration / 1e6)
        times = np.arange(0.0, self.duration + spacing, spacing)
        speeds = self.velocities(times)
        span = max(1, round(window / spacing))
        changes = np.abs(speeds[span:] - speeds[:-span])
        if changes.size == 0:
            return float(abs(speeds[-1] - speeds[0])), 0.0
        worst = int(np.argmax(changes))
        return float(changes[worst]), float(times[worst])


def read_slide_csv(path: str | Path) -> TabulatedSlide:
    """Read a slide profile CSV with header ``time [s]`` and ``slider_position [mm]``.

    Other columns and ``#`` comment lines are ignored; the unit in each header is
    converted (e.g. ``[ms]``, ``[m]``), and a header without a unit is refused
    (:func:`exubrush.util.tables.read_unit_table`).
    """
    name = f"slide CSV {str(path)!r}"
    data = read_unit_table(path, {"time": "s", "slider_position": "mm"}, "slide CSV")
    try:
        return TabulatedSlide(data["time"], data["slider_position"])
    except ValueError as err:
        raise ValueError(f"{name}: {err}") from None


@dataclass(frozen=True)
class RestingSlide:
    """No slide: the head stays where the approach left it for ``duration`` [s]
    (motion.profile "none": a head moved by its pose terms only)."""

    duration: float
    peak_speed = 0.0
    peak_acceleration = 0.0

    def velocities(self, taus: np.ndarray) -> np.ndarray:
        """Zero velocity [mm/s] at each slide time of ``taus``."""
        return np.zeros(np.shape(taus))

    def evaluate(self, tau: float) -> tuple[float, float, float]:
        """Position, velocity and acceleration: all zero."""
        return 0.0, 0.0, 0.0
