"""How far the tips swing when the head vibrates or oscillates (pure; mm, rad, s).

For each sine pose term of a case (``[[motion.sine]]``, exubrush.world.pose), the tips'
steady amplitude at the term's frequency against the head's own: their ratio is the
amplification by which a powered brush's filaments move more (near their resonance) or
less (held by friction on the surface) than the head that drives them. A translation
term's amplitude is measured along its axis, in the surface frame; a rotation term's as the
tip's angle about the term's axis through the pivot.

The amplitude is a least-squares fit of a sine and a cosine at the term's frequency, with
an offset and a linear trend (the slow stroke the vibration rides on), over the whole
cycles after the term's rise and before its fall.
"""

from __future__ import annotations

import math

import numpy as np

# at least this many samples per cycle at the output interval, and cycles in the window
SAMPLES_PER_CYCLE = 4
CYCLES = 2
ROTATION_PLANES = {"rx": (1, 2), "ry": (2, 0), "rz": (0, 1)}  # the plane each turn moves in


def sine_amplitudes(times: np.ndarray, values: np.ndarray, frequency: float) -> np.ndarray:
    """Amplitude of the sine at ``frequency`` [Hz] in each column of ``values`` (n, m) on
    ``times`` (n,) [s]: least squares of a sin ωt + b cos ωt + c + d t, amplitude √(a² + b²)
    in the unit of ``values``."""
    omega = 2.0 * math.pi * frequency
    shifted = times - times[0]
    basis = np.column_stack([np.sin(omega * shifted), np.cos(omega * shifted),
                             np.ones_like(shifted), shifted])
    coefficients, *_ = np.linalg.lstsq(basis, values, rcond=None)
    return np.hypot(coefficients[0], coefficients[1])


def vibration_summary(case, slide_start: float, time: np.ndarray, tip_position: np.ndarray,
                      pivot_track: np.ndarray) -> tuple[list[dict], list[np.ndarray | None]]:
    """One entry per sine term of ``case.motion.sine``: the head's amplitude, the tips'
    (median, least, largest) and the amplification (tips' median over the head's); and
    each term's amplitude of every tip (None where the term was skipped).

    Parameters
    ----------
    slide_start : float
        When the slide starts [s] (the terms' times count from it).
    time : (n,) array
        Sample times [s]; tip_position (n, tips, 3) the tips' centres [mm], surface frame.
    pivot_track : (n, 3) array
        Where the pivot is at each sample [mm] (it moves with the slide and the descent).

    A term whose steady window holds fewer than :data:`CYCLES` cycles, or that the output
    interval samples fewer than :data:`SAMPLES_PER_CYCLE` times a cycle, gets the reason
    instead of figures.
    """
    entries, amplitudes = [], []
    for index, term in enumerate(case.motion.sine):
        ramp = term.ramp_cycles / term.frequency
        first = slide_start + term.start + ramp
        last = (slide_start + term.start + term.duration - ramp if term.duration
                else time[-1] if len(time) else first)
        period = 1.0 / term.frequency
        last = first + math.floor(max(last - first, 0.0) / period) * period  # whole cycles
        entry: dict = {"term": f"motion.sine[{index}]", "axis": term.axis,
                       "frequency_Hz": term.frequency}
        amplitude = None
        window = (time >= first - 1e-12) & (time <= last + 1e-12)
        spacing = float(np.median(np.diff(time))) if len(time) > 1 else math.inf
        if last - first < CYCLES * period - 1e-12:
            entry["skipped"] = (f"fewer than {CYCLES} whole cycles after the rise "
                                f"({max(last - first, 0.0) / period:.3g})")
        elif spacing > period / SAMPLES_PER_CYCLE:
            entry["skipped"] = (f"output.interval {spacing:g} s samples fewer than "
                                f"{SAMPLES_PER_CYCLE} times a cycle of {period:g} s")
        else:
            tips = tip_position[window]
            if term.rotation:
                u, v = ROTATION_PLANES[term.axis]
                arm = tips - pivot_track[window][:, None, :]
                values = np.unwrap(np.arctan2(arm[:, :, v], arm[:, :, u]), axis=0)
                unit = "rad"
            else:
                values = tips[:, :, "xyz".index(term.axis)]
                unit = "mm"
            amplitude = sine_amplitudes(time[window], values, term.frequency)
            median = float(np.median(amplitude))
            entry.update({
                "unit": unit,
                "head_amplitude": term.size,
                "tip_amplitude_median": median,
                "tip_amplitude_least": float(amplitude.min()),
                "tip_amplitude_largest": float(amplitude.max()),
                "amplification_median": median / term.size,
                "window_s": [first, last],
            })
        entries.append(entry)
        amplitudes.append(amplitude)
    return entries, amplitudes
