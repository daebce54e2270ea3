"""Measured brushing forces: reading, aligning with a simulation, comparing (pure).

Measured CSV schema (one row per sample, units in the header, ``#`` lines are comments)::

    time [s], slider_position [mm], normal_force [N], tangential_force [N]

Any unit pint converts is accepted (``[ms]``, ``[m]``, ``[mN]``...). The forces are those
the load cells between slider and head read, with exubrush's sign conventions (normal
positive when the head presses; tangential along the +slide axis); ``Alignment`` flips a
channel that was recorded the other way.

Comparison (the paper's): the slide is cut into strokes at the reversals of the simulated
slider. In each stroke the *flat zone* is where the slide speed is at least
``flat_speed_fraction`` of the stroke's peak speed; the *reversal zone* between two strokes
is the rest. Per stroke: mean F_n, mean |F_t| and μ_eff = mean |F_t| / mean F_n over the flat
zone, for the simulation and the measurement, on the same samples (the measured ones; the
simulation is interpolated linearly onto them). Per reversal: the peak F_n and peak |F_t|.
Relative differences are (simulation - measurement) / measurement.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exubrush.util.tables import check_time_axis, read_unit_table

MEASURED_COLUMNS = {
    "time": "s",
    "slider_position": "mm",
    "normal_force": "N",
    "tangential_force": "N",
}


@dataclass(frozen=True)
class ForceSeries:
    """Slider position and head forces over time (s, mm, N)."""

    time: np.ndarray
    slider_position: np.ndarray
    normal_force: np.ndarray
    tangential_force: np.ndarray

    @classmethod
    def from_results(cls, results) -> ForceSeries:
        """The forces of a simulation (:class:`exubrush.output.results.Results`)."""
        return cls(results.time, results.slider_position, results.normal_force,
                   results.tangential_force)

    @property
    def slide_velocity(self) -> np.ndarray:
        """Slider velocity [mm/s] by finite differences."""
        return np.gradient(self.slider_position, self.time)


def declares_model_output(path) -> bool:
    """Whether the file's ``#`` header says it is not measured (e.g. exubrush's demo file)."""
    with open(path, encoding="utf-8", errors="replace") as handle:
        for line in handle:
            if not line.lstrip().startswith("#"):
                return False
            if "not measured" in line.lower() or "model output" in line.lower():
                return True
    return False


def read_measured_csv(path) -> ForceSeries:
    """Read a measured CSV (:data:`MEASURED_COLUMNS`); ValueError names what is wrong."""
    data = read_unit_table(path, MEASURED_COLUMNS, "measured CSV")
    try:
        check_time_axis(data["time"], *(data[k] for k in MEASURED_COLUMNS if k != "time"))
    except ValueError as err:
        raise ValueError(f"measured CSV {str(path)!r}: {err}") from None
    return ForceSeries(**data)


@dataclass(frozen=True)
class Alignment:
    """How measured samples map onto the simulation.

    Attributes
    ----------
    time_offset : float
        Added to the measured time to get simulation time [s]. With ``by_position`` it is
        the starting guess of the search.
    by_position : bool
        Fit the time offset so that the measured slider position matches the simulated one
        in the least-squares sense (searched within ±``search_window`` of ``time_offset``).
    search_window : float
        Half width of the offset search [s].
    signs : dict
        Factor (+1 or -1) applied to the measured ``slider_position``, ``normal_force``,
        ``tangential_force`` before comparing.
    """

    time_offset: float = 0.0
    by_position: bool = False
    search_window: float = 6.0
    signs: tuple[tuple[str, float], ...] = ()

    def sign(self, channel: str) -> float:
        """The factor applied to a measured channel."""
        return dict(self.signs).get(channel, 1.0)


@dataclass(frozen=True)
class Aligned:
    """Simulation and measurement on the measured samples inside the simulated span."""

    time_offset: float
    simulated: ForceSeries
    measured: ForceSeries

    @property
    def time(self) -> np.ndarray:
        """Common sample times [s] (simulation time)."""
        return self.simulated.time

    @property
    def slider_position(self) -> np.ndarray:
        """Simulated slider position on the common samples [mm]."""
        return self.simulated.slider_position


def _position_misfit(offset: float, simulated: ForceSeries, measured: ForceSeries,
                     sign: float) -> float:
    t = measured.time + offset
    inside = (t >= simulated.time[0]) & (t <= simulated.time[-1])
    if inside.sum() < 2:
        return np.inf
    sim = np.interp(t[inside], simulated.time, simulated.slider_position)
    return float(np.mean((sim - sign * measured.slider_position[inside]) ** 2))


def fit_time_offset(simulated: ForceSeries, measured: ForceSeries, alignment: Alignment) -> float:
    """Time offset [s] that best matches the slider positions (grid search, then Brent)."""
    sign = alignment.sign("slider_position")
    centre, half = alignment.time_offset, alignment.search_window
    step = max(float(np.median(np.diff(simulated.time))), half / 2000.0)
    grid = np.arange(centre - half, centre + half + step, step)
    misfit = [_position_misfit(o, simulated, measured, sign) for o in grid]
    best = grid[int(np.argmin(misfit))]
    from scipy.optimize import minimize_scalar  # 0.6 s of import: position alignment only

    refined = minimize_scalar(_position_misfit, bounds=(best - step, best + step),
                              args=(simulated, measured, sign), method="bounded",
                              options={"xatol": 1e-6})
    return float(refined.x)


def align(simulated: ForceSeries, measured: ForceSeries, alignment: Alignment) -> Aligned:
    """Put the simulation on the measured samples that fall inside the simulated span.

    Raises
    ------
    ValueError
        If fewer than two measured samples overlap the simulation.
    """
    offset = (fit_time_offset(simulated, measured, alignment) if alignment.by_position
              else alignment.time_offset)
    t = measured.time + offset
    inside = (t >= simulated.time[0]) & (t <= simulated.time[-1])
    if inside.sum() < 2:
        raise ValueError(
            f"the measurement ({t[0]:g} to {t[-1]:g} s after the offset of {offset:g} s) does "
            f"not overlap the simulation ({simulated.time[0]:g} to {simulated.time[-1]:g} s); "
            "set the time offset or align by slider position")
    t = t[inside]

    def on_grid(values):
        return np.interp(t, simulated.time, values)

    measured_inside = ForceSeries(
        t,
        alignment.sign("slider_position") * measured.slider_position[inside],
        alignment.sign("normal_force") * measured.normal_force[inside],
        alignment.sign("tangential_force") * measured.tangential_force[inside],
    )
    simulated_on_grid = ForceSeries(t, on_grid(simulated.slider_position),
                                    on_grid(simulated.normal_force),
                                    on_grid(simulated.tangential_force))
    return Aligned(offset, simulated_on_grid, measured_inside)


@dataclass(frozen=True)
class Stroke:
    """One stroke of the simulated slide and its flat zone [s]."""

    index: int
    direction: int
    start: float
    end: float
    flat_start: float
    flat_end: float


def strokes(time: np.ndarray, velocity: np.ndarray, flat_speed_fraction: float) -> list[Stroke]:
    """Cut a slide into strokes at velocity sign changes; flat zone by speed fraction.

    Samples at rest (|v| below 1e-9 of the peak speed, e.g. the approach) belong to no
    stroke. Only whole strokes count, from one reversal to the next (a rest at a reversal
    is allowed): the first movement after the approach starts from upright bristles and a
    stroke cut off by the end of the run is incomplete, so both are left out.
    """
    if not 0.0 < flat_speed_fraction < 1.0:
        raise ValueError(f"the flat-zone speed fraction must lie in (0, 1), got "
                         f"{flat_speed_fraction:g}")
    speed = np.abs(velocity)
    if speed.size == 0 or speed.max() == 0.0:
        return []
    moving = speed > 1e-9 * speed.max()
    direction = np.where(moving, np.sign(velocity), 0).astype(int)
    edges = np.flatnonzero(np.diff(direction) != 0) + 1
    segments = [seg for seg in np.split(np.arange(time.size), edges)
                if direction[seg[0]] != 0 and seg.size >= 2]
    found = []
    for before, segment, after in zip(segments, segments[1:], segments[2:], strict=False):
        sense = direction[segment[0]]
        if direction[before[0]] != -sense or direction[after[0]] != -sense:
            continue  # not bounded by two reversals (rests between moving strokes aside)
        peak = speed[segment].max()
        flat = segment[speed[segment] >= flat_speed_fraction * peak]
        found.append(Stroke(len(found), int(sense), float(time[segment[0]]),
                            float(time[segment[-1]]), float(time[flat[0]]),
                            float(time[flat[-1]])))
    return found


def reversal_zones(time: np.ndarray, velocity: np.ndarray,
                   flat_speed_fraction: float) -> list[tuple[float, float]]:
    """Time spans [s] around each slide reversal where the speed is below the flat zone's.

    A zone is a run of samples with |v| < ``flat_speed_fraction`` x the peak speed whose two
    sides move in opposite directions (a rest at the start or the end is no reversal).
    """
    speed = np.abs(velocity)
    if speed.size == 0 or speed.max() == 0.0:
        return []
    slow = speed < flat_speed_fraction * speed.max()
    edges = np.flatnonzero(np.diff(slow.astype(int)) != 0) + 1
    zones = []
    for run in np.split(np.arange(time.size), edges):
        if not slow[run[0]] or run[0] == 0 or run[-1] == time.size - 1:
            continue
        if np.sign(velocity[run[0] - 1]) == -np.sign(velocity[run[-1] + 1]) != 0:
            zones.append((float(time[run[0]]), float(time[run[-1]])))
    return zones


def _relative(simulated: float, measured: float) -> float:
    return (simulated - measured) / abs(measured) if measured != 0.0 else float("nan")


def _flat_means(series: ForceSeries, mask: np.ndarray) -> dict:
    normal = float(np.mean(series.normal_force[mask]))
    tangential = float(np.mean(np.abs(series.tangential_force[mask])))
    return {"normal_force": normal, "tangential_force": tangential,
            "friction_coefficient": tangential / normal if normal > 0.0 else float("nan")}


def stroke_flat_means(series: ForceSeries, flat_speed_fraction: float) -> list[dict]:
    """Flat-zone means of every whole stroke of ``series`` (one simulation or measurement on
    its own samples): a list of {index, direction, normal_force, tangential_force,
    friction_coefficient} (N, N, -), in stroke order (see :func:`strokes`)."""
    rows = []
    for stroke in strokes(series.time, series.slide_velocity, flat_speed_fraction):
        mask = (series.time >= stroke.flat_start) & (series.time <= stroke.flat_end)
        if mask.sum() >= 2:
            rows.append({"index": stroke.index, "direction": stroke.direction,
                         **_flat_means(series, mask)})
    return rows


def compare(aligned: Aligned, simulated_strokes: list[Stroke]) -> dict:
    """Per-stroke flat-zone means and per-reversal peaks, simulation against measurement.

    A stroke counts only if the measurement covers its whole flat zone; a reversal only if
    it covers the zone between two counted flat zones.

    Returns
    -------
    dict
        ``strokes``: list of {index, direction, start, end, flat_start, flat_end, samples,
        simulated, measured, relative_difference} (means in N and -); ``reversals``: list of
        {after_stroke, start, end, simulated, measured, ratio} (peak F_n and |F_t|, N);
        ``largest_flat_difference``: per quantity, the relative difference of the stroke means
        that is largest in magnitude (with its sign).
    """
    t = aligned.time
    covered = [s for s in simulated_strokes if t[0] <= s.flat_start and s.flat_end <= t[-1]]
    stroke_rows = []
    for stroke in covered:
        mask = (t >= stroke.flat_start) & (t <= stroke.flat_end)
        if mask.sum() < 2:
            continue
        sim = _flat_means(aligned.simulated, mask)
        meas = _flat_means(aligned.measured, mask)
        stroke_rows.append({
            "index": stroke.index, "direction": stroke.direction,
            "start": stroke.start, "end": stroke.end,
            "flat_start": stroke.flat_start, "flat_end": stroke.flat_end,
            "samples": int(mask.sum()), "simulated": sim, "measured": meas,
            "relative_difference": {k: _relative(sim[k], meas[k]) for k in sim},
        })
    reversal_rows = []
    for before, after in zip(covered, covered[1:], strict=False):
        if after.index != before.index + 1:
            continue
        mask = (t > before.flat_end) & (t < after.flat_start)
        if not mask.any():
            continue
        peaks = {}
        for label, series in (("simulated", aligned.simulated), ("measured", aligned.measured)):
            peaks[label] = {"normal_force": float(np.max(series.normal_force[mask])),
                            "tangential_force": float(np.max(np.abs(
                                series.tangential_force[mask])))}
        reversal_rows.append({
            "after_stroke": before.index, "start": before.flat_end, "end": after.flat_start,
            **peaks,
            "ratio": {k: (peaks["simulated"][k] / peaks["measured"][k]
                          if peaks["measured"][k] != 0.0 else float("nan"))
                      for k in peaks["simulated"]},
        })
    largest = {
        key: max((row["relative_difference"][key] for row in stroke_rows), key=abs,
                 default=None)
        for key in ("normal_force", "tangential_force", "friction_coefficient")
    }
    return {"strokes": stroke_rows, "reversals": reversal_rows,
            "largest_flat_difference": largest}
