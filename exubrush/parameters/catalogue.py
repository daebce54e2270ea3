"""The built-in cases: the paper's two brushings, surfaces with teeth and the tufted heads.

``exubrush case NAME`` writes one as TOML and ``load_case("NAME")`` reads it; each factory
returns a validated :class:`~exubrush.parameters.case.Case`. The sources of every number
are in docs/model.md ("Default head") and docs/tufts.md.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

from exubrush.parameters.case import Case, SineMotion, Surface
from exubrush.parameters.fields import build
from exubrush.parameters.head import Tuft


def orthogonal_case() -> Case:
    """The paper's orthogonal brushing: x(t) = 15 mm sin(πt/6) across the head's long axis."""
    return build(Case, {})


def parallel_case() -> Case:
    """The paper's parallel brushing: x(t) = 30 mm sin(πt/12) along the head's long axis."""
    base = orthogonal_case()
    return replace(
        base,
        name="parallel",
        motion=replace(base.motion, direction="parallel", amplitude=30.0, period=24.0),
    )


def interdental_case() -> Case:
    """The default head in the orthogonal motion across a row of teeth: 7 mm crowns, 1 mm
    interdental gaps 2 mm deep, top edges rounded with 0.5 mm, the gaps along the head's
    long axis (surface.yaw = 90°) so that the slide crosses them; at the paper's
    d = 4.2 mm a straight tip reaches 1.2 mm below the tooth tops, into a gap. The tip
    contact is the compiled law (contact.backend "paper-compiled": 2.2x faster than the
    symbolic one here, the head's mean force within 0.02 %)."""
    base = orthogonal_case()
    return replace(base, name="interdental",
                   surface=Surface(kind="tooth-row", yaw=math.radians(90.0)),
                   contact=replace(base.contact, backend="paper-compiled"))


def crown_case() -> Case:
    """The default head in the orthogonal motion along a cylinder of 4 mm radius (a tooth
    crown) whose axis lies along the slide; the tip contact the compiled law, as for the
    interdental case."""
    base = orthogonal_case()
    return replace(base, name="crown", surface=Surface(kind="cylinder", radius=4.0),
                   contact=replace(base.contact, backend="paper-compiled"))


def tuft_case() -> Case:
    """One tuft of 37 round nylon filaments (0.2 mm, 10.5 mm trim length, hexagonal in a
    1.6 mm hole) in the orthogonal motion, at d = 8.4 mm: 2.1 mm of interference, a fifth of
    the filaments' reach, so that they bend well beyond the linear range."""
    base = orthogonal_case()
    return replace(base, name="tuft",
                   head=replace(base.head, layout="tufts", tufts=(Tuft(name="tuft"),)),
                   motion=replace(base.motion, interaction_distance=8.4))


# a typical manual toothbrush (docs/tufts.md, "The manual-brush case", gives the sources):
# 4 rows of 10 tufts, each the `tuft` case's 37 nylon filaments of 0.2 mm in a 1.6 mm hole
MANUAL_BRUSH_ROWS, MANUAL_BRUSH_COLUMNS = 4, 10
MANUAL_BRUSH_PITCH = (2.4, 2.3)  # mm, along and across the head (holes 0.8 / 0.7 mm apart)


def manual_brush_case() -> Case:
    """A typical full manual toothbrush head: 40 tufts (4 rows of 10) of 37 round nylon
    filaments each (0.2 mm, 10.5 mm trim length, hexagonal in 1.6 mm holes on a 2.4 x 2.3
    mm pitch), 1,480 filaments, in the orthogonal motion at d = 8.4 mm (the `tuft` case's
    interference) for one slide period. Contact between bristles stays off: every tuft
    reaches its neighbours, so with it the whole head is one system (docs/tufts.md)."""
    base = tuft_case()
    along, across = MANUAL_BRUSH_PITCH
    tufts = tuple(
        Tuft(name=f"r{row + 1}c{column + 1}",
             x=(column - (MANUAL_BRUSH_COLUMNS - 1) / 2) * along,
             y=(row - (MANUAL_BRUSH_ROWS - 1) / 2) * across)
        for row in range(MANUAL_BRUSH_ROWS) for column in range(MANUAL_BRUSH_COLUMNS))
    return replace(base, name="manual-brush", head=replace(base.head, tufts=tufts),
                   motion=replace(base.motion, periods=1.0))


# an oscillating-rotating round head (docs/motion.md, "The powered-brush cases", gives the
# sources and assumptions): the `tuft` case's tufts in rings on an 11 mm disc
ROUND_HEAD_RINGS = ((0.0, 1), (2.0, 6), (3.9, 12))  # (radius [mm], tufts) of each ring
OSCILLATION = (7600.0 / 60.0, math.radians(20.0))  # Hz, amplitude [rad]: ±20° at 7,600/min


def oscillating_rotating_case() -> Case:
    """An oscillating-rotating round head: 19 tufts of the `tuft` case (37 nylon
    filaments of 0.2 mm in 1.6 mm holes) in a centre tuft and rings of 6 and 12 on an 11
    mm disc, pressed on the plane at d = 8.4 mm and turned ±20° about its normal at 7,600
    oscillations a minute for 0.5 s after the approach (no stroke). Its roots tilt away
    from its centre (``head.tilt_pattern = "radial"``): the head stays symmetric under its
    turn, and filaments as far from the centre are twins (exubrush.run.twins)."""
    base = tuft_case()
    tufts = tuple(
        Tuft(name=f"ring{ring}-{k + 1}", x=radius * math.cos(2 * math.pi * k / count),
             y=radius * math.sin(2 * math.pi * k / count))
        for ring, (radius, count) in enumerate(ROUND_HEAD_RINGS) for k in range(count))
    frequency, angle = OSCILLATION
    turn = SineMotion().replace(axis="rz", amplitude=0.0, angle=angle, frequency=frequency)
    return base.replace(
        name="oscillating-rotating",
        head=base.head.replace(tufts=tufts, tilt_pattern="radial"),
        motion=base.motion.replace(profile="none", period=0.1, periods=5.0, sine=(turn,)),
        output=base.output.replace(interval=1e-3, shape_interval=0.01),
    )


# a sonic head (docs/motion.md, "The powered-brush cases", gives the sources): the manual
# head swung side to side, across the handle, at 31,000 strokes a minute
SONIC = (258.0, 1.5)  # Hz, amplitude [mm]: 31,000 strokes (half cycles) a minute, 3 mm side to side
SONIC_STROKE = 4.0  # s, the period of the slow manual stroke along the handle under it


def sonic_case() -> Case:
    """A sonic head: the `manual-brush` head (40 tufts of 37 nylon filaments) swung side to
    side across the handle (y) by ±1.5 mm at 258 Hz (31,000 strokes a minute, two a cycle)
    on a slow manual stroke along the handle (±15 mm in 4 s), pressed on the plane at d =
    8.4 mm, for 0.5 s after the approach. Forces are recorded every 0.25 ms (15 samples a
    cycle), shapes every 10 ms."""
    base = manual_brush_case()
    frequency, amplitude = SONIC
    swing = SineMotion().replace(axis="y", amplitude=amplitude, frequency=frequency)
    return base.replace(
        name="sonic",
        motion=base.motion.replace(direction="parallel", period=SONIC_STROKE,
                                   periods=0.5 / SONIC_STROKE, sine=(swing,)),
        output=base.output.replace(interval=2.5e-4, shape_interval=0.01),
    )


def robot_case() -> Case:
    """The paper's head moved by a robot arm along a rectangle of linear moves with
    right-angle turns (exubrush/data/robot-path.csv, exubrush's illustration: 10 mm/s,
    8 mm x 10 mm, a stop at each corner), pressed on the plane at the paper's d."""
    base = orthogonal_case()
    path = Path(__file__).parents[1] / "data" / "robot-path.csv"
    return base.replace(name="robot", motion=base.motion.replace(
        profile="none", period=4.0, periods=1.0, pose_csv=str(path)))


BUILT_IN_CASES = {"orthogonal": orthogonal_case, "parallel": parallel_case,
                  "interdental": interdental_case, "crown": crown_case, "tuft": tuft_case,
                  "manual-brush": manual_brush_case,
                  "oscillating-rotating": oscillating_rotating_case, "sonic": sonic_case,
                  "robot": robot_case}
