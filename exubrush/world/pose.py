"""The head's prescribed pose in six degrees of freedom (pure, mm-s-rad units).

A pose is six numbers, ordered as :data:`AXES`: the translation (x, y, z) [mm] of the head
frame from its start, in the surface (global) frame, and Tait-Bryan angles (rx, ry, rz)
[rad]. The head's rotation matrix is

    A = Rx(rx) Ry(ry) Rz(rz),

rotations about the head's own axes applied x, then y, then z (equivalently about the fixed
surface axes z, then y, then x). This is Exudyn's convention for the node type
``NodeRigidBodyRxyz``: ``exudyn.rigidBodyUtilities.RotXYZ2RotationMatrix``. The angular
velocity in the surface frame is ω = G(θ) θ̇ with (Exudyn's ``RotXYZ2G``)

    G = [[1, 0, sin ry], [0, cos rx, -cos ry sin rx], [0, sin rx, cos rx cos ry]],

the columns being the x axis, the once-rotated y axis and the twice-rotated z axis, so that
ω̃ = Ȧ Aᵀ; the angular acceleration is α = G θ̈ + Ġ θ̇. G is singular at ry = ±π/2 (gimbal
lock), which matters only where rates are recovered from ω, not here.

A motion is a sum of terms (:class:`SineTerm`, :class:`TableTerm`), each giving the pose,
its rate and its acceleration at a time. :class:`HeadPose` adds them: translations add,
and so do the angles, as Tait-Bryan coordinates. For rotations about one axis that is
composing the rotations; for rotations about several axes it is not (A(θ₁ + θ₂) differs
from A(θ₁) A(θ₂)), and the axes' order above decides: a term on rz and a term on rx give
A = Rx(rx) Rz(rz), whichever term is listed first.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from exubrush.parameters.choices import POSE_AXES as AXES
from exubrush.util.tables import read_unit_table
from exubrush.world.slide import TabulatedSlide, smooth_step

# internal unit of each pose coordinate
UNITS = {"x": "mm", "y": "mm", "z": "mm", "rx": "rad", "ry": "rad", "rz": "rad"}


def rotation_matrix(angles: Sequence[float] | np.ndarray) -> np.ndarray:
    """A = Rx(rx) Ry(ry) Rz(rz) (3, 3) of Tait-Bryan angles (rx, ry, rz) [rad]."""
    cx, cy, cz = np.cos(angles)
    sx, sy, sz = np.sin(angles)
    rot_x = np.array([[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]])
    rot_y = np.array([[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]])
    rot_z = np.array([[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]])
    return rot_x @ rot_y @ rot_z


def g_matrix(angles: Sequence[float] | np.ndarray) -> np.ndarray:
    """G(θ) (3, 3), ω = G θ̇ in the surface frame."""
    (cx, cy, _), (sx, sy, _) = np.cos(angles), np.sin(angles)
    return np.array([[1.0, 0.0, sy], [0.0, cx, -cy * sx], [0.0, sx, cx * cy]])


def angular_velocity(angles: Sequence[float] | np.ndarray,
                     rates: Sequence[float] | np.ndarray) -> np.ndarray:
    """Angular velocity ω = G(θ) θ̇ [rad/s] (3,) in the surface frame, of angles θ [rad]
    changing at rates θ̇ [rad/s]."""
    return g_matrix(angles) @ np.asarray(rates, dtype=float)


def angular_acceleration(angles: Sequence[float] | np.ndarray,
                         rates: Sequence[float] | np.ndarray,
                         accelerations: Sequence[float] | np.ndarray) -> np.ndarray:
    """Angular acceleration α = G θ̈ + Ġ θ̇ [rad/s²] (3,) in the surface frame."""
    (cx, cy, _), (sx, sy, _) = np.cos(angles), np.sin(angles)
    theta_dot = np.asarray(rates, dtype=float)
    dx, dy, _ = theta_dot
    g_dot = np.array([
        [0.0, 0.0, cy * dy],
        [0.0, -sx * dx, sy * sx * dy - cy * cx * dx],
        [0.0, cx * dx, -sx * cy * dx - cx * sy * dy],
    ])
    return g_matrix(angles) @ np.asarray(accelerations, dtype=float) + g_dot @ theta_dot


@dataclass(frozen=True)
class SineTerm:
    """A sine on one pose coordinate, value(t) = e(t) a sin(2π f (t - start) + φ) for
    start <= t <= end and 0 outside.

    The envelope e rises from 0 to 1 over ``ramp`` seconds after ``start`` along the
    quintic smooth step of :func:`exubrush.world.slide.smooth_step` and falls back to 0
    over the ``ramp`` seconds before ``end`` (none with an infinite end), so value, rate and
    acceleration are continuous. With ``ramp`` = 0 there is no envelope: the rate jumps at
    ``start`` (a sine starts at its peak rate) and at a finite ``end``, and a nonzero phase
    makes the value jump at ``start`` too.

    Attributes
    ----------
    axis : str
        One of :data:`AXES`.
    amplitude : float
        a [mm] for x, y, z; [rad] for rx, ry, rz; not negative.
    frequency : float
        f [Hz], positive.
    phase : float
        φ [rad].
    start, end : float
        The term acts for start <= t <= end [s]; end may be infinite.
    ramp : float
        Length of the envelope's rise and of its fall [s]; 2 ramp <= end - start.
    """

    axis: str
    amplitude: float
    frequency: float
    phase: float = 0.0
    start: float = 0.0
    end: float = math.inf
    ramp: float = 0.0

    def __post_init__(self) -> None:
        if self.axis not in AXES:
            raise ValueError(f"SineTerm.axis must be one of {', '.join(AXES)}, not {self.axis!r}")
        for name in ("amplitude", "frequency", "phase", "start", "end", "ramp"):
            value = getattr(self, name)
            if not (math.isfinite(value) or (name == "end" and value == math.inf)):
                allowed = "finite or inf" if name == "end" else "finite"
                raise ValueError(f"SineTerm.{name} must be {allowed}, not {value!r}")
        if self.frequency <= 0.0:
            raise ValueError(f"SineTerm.frequency must be positive, not {self.frequency!r} Hz")
        if self.amplitude < 0.0:
            raise ValueError(f"SineTerm.amplitude must not be negative, not {self.amplitude!r}"
                             "; shift the phase by π to reverse the sine")
        if self.ramp < 0.0:
            raise ValueError(f"SineTerm.ramp must not be negative, not {self.ramp!r} s")
        if self.end <= self.start:
            raise ValueError(f"SineTerm.end ({self.end!r} s) must be after start "
                             f"({self.start!r} s)")
        if 2.0 * self.ramp > self.end - self.start:
            raise ValueError(f"SineTerm.ramp ({self.ramp!r} s) must be at most half of "
                             f"end - start ({self.end - self.start!r} s)")

    @property
    def end_time(self) -> float:
        """Time after which the term is zero [s] (``end``, possibly infinite)."""
        return self.end

    @property
    def peak_rate(self) -> np.ndarray:
        """Upper bound of |rate| per coordinate (6,) [mm/s, rad/s]: a (2π f + 15/(8 ramp)),
        15/8 being the smooth step's largest slope; without a ramp a 2π f, reached where
        the sine passes zero within [start, end]."""
        omega = 2.0 * math.pi * self.frequency
        peak = np.zeros(6)
        peak[AXES.index(self.axis)] = self.amplitude * (
            omega + (15.0 / (8.0 * self.ramp) if self.ramp > 0.0 else 0.0)
        )
        return peak

    @property
    def peak_acceleration(self) -> np.ndarray:
        """Upper bound of |acceleration| per coordinate (6,) [mm/s², rad/s²]: of
        e'' g + 2 e' g' + e g'' with |g| <= a, |g'| <= a 2π f, |g''| <= a (2π f)² and the
        smooth step's largest slope 15/8 and curvature 10/√3 over ``ramp``; without a
        ramp a (2π f)², reached at the sine's peaks."""
        omega = 2.0 * math.pi * self.frequency
        ramp = (2.0 * 15.0 / (8.0 * self.ramp) * omega + 10.0 / math.sqrt(3.0) / self.ramp**2
                if self.ramp > 0.0 else 0.0)
        peak = np.zeros(6)
        peak[AXES.index(self.axis)] = self.amplitude * (omega**2 + ramp)
        return peak

    def _envelope(self, t: float) -> tuple[float, float, float]:
        """e, e' [1/s] and e'' [1/s²] at t [s]: the rising step in the first half of the
        term, the falling one in the second (2 ramp <= end - start: they never overlap)."""
        if self.ramp == 0.0:
            return 1.0, 0.0, 0.0
        if t - self.start <= self.end - t:
            s, ds, dds = smooth_step((t - self.start) / self.ramp)
        else:
            s, ds, dds = smooth_step((self.end - t) / self.ramp)
            ds = -ds  # d/dt of (end - t) / ramp
        return s, ds / self.ramp, dds / self.ramp**2

    def evaluate(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Pose, rate and acceleration (6,) each at time t [s] (mm, rad; per s; per s²)."""
        pose, rate, acceleration = np.zeros(6), np.zeros(6), np.zeros(6)
        if not self.start <= t <= self.end:
            return pose, rate, acceleration
        omega = 2.0 * math.pi * self.frequency
        phase = omega * (t - self.start) + self.phase
        g = self.amplitude * math.sin(phase)
        dg = self.amplitude * omega * math.cos(phase)
        ddg = -omega**2 * g
        e, de, dde = self._envelope(t)
        k = AXES.index(self.axis)
        pose[k] = e * g
        rate[k] = de * g + e * dg
        acceleration[k] = dde * g + 2.0 * de * dg + e * ddg
        return pose, rate, acceleration


class TableTerm:
    """Pose coordinates from samples, each interpolated by a monotone cubic (PCHIP) as
    :class:`exubrush.world.slide.TabulatedSlide` does: never outside the range of its
    data, velocity continuous, acceleration jumping at the samples.

    Each coordinate starts at 0 (its first sample is taken as the origin) at ``start`` [s]
    and is held at its last value after the table's end. Before ``start`` and after the end
    the rate is 0: it jumps there unless the table's end slope is 0, which PCHIP gives where
    the first (last) two samples are equal.

    Parameters
    ----------
    times : (n,) array
        Sample times [s], strictly increasing, n >= 2; only their differences matter.
    values : mapping
        Coordinate (one of :data:`AXES`) -> its samples (n,) [mm or rad]; coordinates not
        given are 0.
    start : float
        When the table's first sample is reached [s].
    """

    def __init__(self, times: np.ndarray, values: Mapping[str, np.ndarray], start: float = 0.0):
        times = np.asarray(times, dtype=float)
        unknown = sorted(set(values) - set(AXES))
        if unknown or not values:
            raise ValueError(f"a pose table takes samples of some of {', '.join(AXES)}, "
                             f"got {', '.join(unknown) or 'none'}")
        if times.ndim != 1 or times.size < 2 or any(
            np.shape(v) != times.shape for v in values.values()
        ):
            raise ValueError("a pose table needs at least two samples, as many of each "
                             "coordinate as of the times")
        if not math.isfinite(start):
            raise ValueError(f"a pose table's start must be finite, not {start!r}")
        self.start = float(start)
        self._slides = {AXES.index(axis): TabulatedSlide(times, np.asarray(v, dtype=float),
                                                         axis, UNITS[axis])
                        for axis, v in values.items()}
        self.duration = float(times[-1] - times[0])

    @property
    def end_time(self) -> float:
        """Time after which the pose is held [s]."""
        return self.start + self.duration

    @property
    def digest(self) -> str:
        """SHA-256 of the coordinates' interpolants, in axis order (equal for equal
        tables, whatever else the file holds)."""
        return hashlib.sha256("".join(
            f"{AXES[k]}:{slide.digest};" for k, slide in sorted(self._slides.items())
        ).encode()).hexdigest()

    @property
    def peak_rate(self) -> np.ndarray:
        """Largest |rate| per coordinate (6,) [mm/s, rad/s], exact
        (:attr:`TabulatedSlide.peak_speed`)."""
        peak = np.zeros(6)
        for k, slide in self._slides.items():
            peak[k] = slide.peak_speed
        return peak

    @property
    def peak_acceleration(self) -> np.ndarray:
        """Largest |acceleration| per coordinate (6,) [mm/s², rad/s²], exact
        (:attr:`TabulatedSlide.peak_acceleration`)."""
        peak = np.zeros(6)
        for k, slide in self._slides.items():
            peak[k] = slide.peak_acceleration
        return peak

    def evaluate(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Pose, rate and acceleration (6,) each at time t [s] (mm, rad; per s; per s²)."""
        values = np.zeros((3, 6))
        tau = t - self.start
        if tau < 0.0:
            return values[0], values[1], values[2]
        for k, slide in self._slides.items():
            values[:, k] = slide.evaluate(min(tau, self.duration))
        if tau > self.duration:
            values[1:] = 0.0
        return values[0], values[1], values[2]


def read_pose_csv(path: str | Path, start: float = 0.0) -> TableTerm:
    """Read a pose table: a CSV with a ``time [s]`` column and any of ``x [mm]``,
    ``y [mm]``, ``z [mm]``, ``rx [deg]``, ``ry [deg]``, ``rz [deg]`` (at least one),
    started at ``start`` [s].

    Other columns and ``#`` comment lines are ignored; each column's unit is converted
    (``[ms]``, ``[m]``, ``[rad]``...; angles come out in rad), and a column without a unit
    is refused (:func:`exubrush.util.tables.read_unit_table`).
    """
    name = f"pose CSV {str(path)!r}"
    data = read_unit_table(path, {"time": "s", **UNITS}, "pose CSV", optional=AXES)
    times = data.pop("time")
    if not data:
        written = {"mm": "mm", "rad": "deg"}
        columns = ", ".join(f"'{axis} [{written[UNITS[axis]]}]'" for axis in AXES)
        raise ValueError(f"{name} has none of the pose columns {columns}")
    try:
        return TableTerm(times, data, start)
    except ValueError as err:
        raise ValueError(f"{name}: {err}") from None


class HeadPose:
    """The head's pose: the sum of its terms' poses, about a pivot fixed to the head.

    Parameters
    ----------
    terms : sequence of SineTerm or TableTerm
        Their poses, rates and accelerations add (angles as Tait-Bryan coordinates, see the
        module's docstring). No terms: the head rests.
    pivot : (3,) array
        A point fixed to the head, given in the surface frame at t = 0 [mm]; the head
        rotates about it and it moves with the translation.
    """

    def __init__(self, terms: Sequence[SineTerm | TableTerm], pivot: Sequence[float] | np.ndarray):
        self.terms = tuple(terms)
        self.pivot = np.asarray(pivot, dtype=float)
        if self.pivot.shape != (3,) or not np.all(np.isfinite(self.pivot)):
            raise ValueError(f"the pivot must be three finite coordinates [mm], not {pivot!r}")

    @property
    def table(self) -> TableTerm | None:
        """The tabulated term (a pose CSV), if there is one."""
        return next((term for term in self.terms if isinstance(term, TableTerm)), None)

    def acts_between(self, t0: float, t1: float) -> bool:
        """Whether any term moves the head at some time of [t0, t1] [s]."""
        return any(term.start <= t1 and term.end_time >= t0 for term in self.terms)

    @property
    def end_time(self) -> float:
        """Time after which no term changes [s] (0 without terms)."""
        return max((term.end_time for term in self.terms), default=0.0)

    @property
    def turns(self) -> bool:
        """Whether any term ever turns the head (a rate on rx, ry or rz; every term starts
        at 0, so without one the angles stay 0)."""
        return bool(np.any(self.peak_rate[3:] > 0.0))

    @property
    def peak_rate(self) -> np.ndarray:
        """Upper bound of |rate| per coordinate (6,) [mm/s, rad/s]: the sum of the terms'
        (exact for a single term whose own is)."""
        return sum((term.peak_rate for term in self.terms), np.zeros(6))

    @property
    def peak_acceleration(self) -> np.ndarray:
        """Upper bound of |acceleration| per coordinate (6,) [mm/s², rad/s²]: the sum of
        the terms'."""
        return sum((term.peak_acceleration for term in self.terms), np.zeros(6))

    def evaluate(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Pose, rate and acceleration (6,) each at time t [s] (mm, rad; per s; per s²)."""
        total = np.zeros((3, 6))
        for term in self.terms:
            total += term.evaluate(t)
        return total[0], total[1], total[2]

    def _arms(self, points0: np.ndarray, pose: np.ndarray) -> np.ndarray:
        """A (p₀ - pivot) (n, 3) [mm] of points p₀ (n, 3) at the ``pose``'s angles."""
        return (np.asarray(points0, dtype=float) - self.pivot) @ rotation_matrix(pose[3:]).T

    def point_position(self, points0: np.ndarray, t: float) -> np.ndarray:
        """Positions [mm] (n, 3) at time t [s] of points fixed to the head, given by their
        positions (n, 3) at t = 0 in the surface frame: :meth:`point_motion`'s first part."""
        pose = self.evaluate(t)[0]
        return self.pivot + pose[:3] + self._arms(points0, pose)

    def point_motion(self, points0: np.ndarray,
                     t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions [mm], velocities [mm/s] and accelerations [mm/s²] (n, 3) at time t [s]
        of points fixed to the head, given by their positions (n, 3) at t = 0 in the
        surface frame.

        With pivot p, translation u, r = A (p₀ - p): x = p + u + r, v = u̇ + ω × r,
        a = ü + α × r + ω × (ω × r).
        """
        pose, rate, acceleration = self.evaluate(t)
        arm = self._arms(points0, pose)
        omega = angular_velocity(pose[3:], rate[3:])
        alpha = angular_acceleration(pose[3:], rate[3:], acceleration[3:])
        return (
            self.pivot + pose[:3] + arm,
            rate[:3] + np.cross(omega, arm),
            acceleration[:3] + np.cross(alpha, arm) + np.cross(omega, np.cross(omega, arm)),
        )
