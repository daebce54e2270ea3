"""A DFM nylon filament vibrates as a clamped-free Euler-Bernoulli beam.

One round 0.2 mm filament, 10.5 mm long, of the built-in nylon (E = 2000 MPa, ρ = 1.06e-9
t/mm³), clamped to ground (free decay) or to a rigid handle shaken sideways (base
excitation); no surface, no gravity (exubrush's bodies have none). Its first bending
frequency is 348.6 Hz (exubrush.reference.cantilever_vibration), so a sonic brush's 260 Hz
is at r = 0.75.

The tip sphere is shrunk to 1 µm radius: the reference is a bare beam, and the filaments'
default 0.1 mm sphere is a tip mass of 1.3 % of the filament's, which lowers the frequency
by 2.5 % (test_default_tip_sphere_lowers_the_frequency_as_a_tip_mass).

Measured (N = segments, spp = steps per first-mode period, ρ∞ = spectral radius):

* frequency error, ρ∞ = 0.8, 200 spp: N = 4, 6, 8, 12, 16, 24: +0.19, +0.07, +0.03,
  -0.01, -0.02, -0.02 %; a Hencky chain's 1/N² towards about -0.02 % (shear and the
  section's rotary inertia, ~2e-4, which the Euler-Bernoulli reference leaves out).
* time step, N = 12: ρ∞ = 0 (exubrush's default) at 10, 20, 50, 100, 200 spp gives
  -11, -3.8, -0.70, -0.18, -0.04 % and a numerical damping ratio of 5.5e-2, 1.2e-2,
  9e-4, 1.2e-4, 2e-5; ρ∞ = 0.8 gives -3.2, -0.85, -0.14, -0.03, -0.006 % and |ζ| < 2e-4 at
  any step. So ρ∞ = 0 needs 100 steps per period for the first mode (0.2 % period error,
  ζ 1.2e-4 beside the material's 0.055); these tests take ρ∞ = 0.8, whose numerical
  damping is negligible at 100 steps per period while the unresolved high modes of the
  chain are still damped.
* base excitation, N = 12, 100 spp, ρ∞ = 0.8, τ = 5e-5 s (ζ₁ = 0.055): amplification
  1.1527, 1.5142, 3.6715, 14.316 at r = 0.3, 0.5, 0.8, 1.0; against the one-mode
  reference -0.17, -0.36, -0.35, -0.13 %, against five modes +0.01, +0.02, -0.02, -0.10 %.
"""

import dataclasses
import functools
import math

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
import pytest
from exudyn.rigidBodyUtilities import InertiaCuboid

from exubrush.models.dfm import add_dfm_bristle
from exubrush.models.geometry import BristleGeometry
from exubrush.models.sections import section_properties
from exubrush.parameters.head import BUILT_IN_MATERIALS
from exubrush.parameters.settings import Solver
from exubrush.reference.cantilever_vibration import (
    first_bending_frequency,
    mode_shape,
    mode_slope,
    stiffness_damped_tip_amplification,
    stiffness_proportional_damping_ratio,
    tip_amplification,
)
from exubrush.run.solver import dynamic_settings

LENGTH = 10.5  # mm
DIAMETER = 0.2  # mm
NYLON = BUILT_IN_MATERIALS["nylon"]
SECTION = section_properties("circle", DIAMETER, DIAMETER)
FREQUENCY = first_bending_frequency(LENGTH, NYLON.youngs_modulus, SECTION.second_moment_z,
                                    NYLON.density, SECTION.area)
PERIOD = 1.0 / FREQUENCY
BARE_TIP = 1e-3  # mm: a tip sphere of 1.3e-8 of the filament's mass
# spectral radius of the tests: numerical damping below 2e-4 at 20 steps a period and more,
# against ρ∞ = 0's 1.2e-2 at 20 and 1.2e-4 at 100 (measured, module docstring)
SPECTRAL_RADIUS = 0.8


def _filament(tip_radius: float = BARE_TIP) -> BristleGeometry:
    """The filament along the x axis from the origin; it bends in x-y about z."""
    return BristleGeometry(root=np.zeros(3), frame=np.eye(3), length=LENGTH,
                           tip_radius=tip_radius, section=SECTION, width=DIAMETER,
                           height=DIAMETER, shape="circle")


def _solve(mbs, tip_node, steps_per_period: int, spectral_radius: float,
           end_time: float) -> tuple[np.ndarray, np.ndarray]:
    """Exubrush's dynamic settings at a step of PERIOD / ``steps_per_period``; the tip's
    lateral position y [mm] at every step, against time [s]."""
    sensor = mbs.AddSensor(eii.SensorNode(nodeNumber=tip_node, storeInternal=True,
                                          outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    step = PERIOD / steps_per_period
    solver = dataclasses.replace(Solver(), step_size=step, spectral_radius=spectral_radius)
    mbs.SolveDynamic(dynamic_settings(solver, end_time, step))
    data = mbs.GetSensorStoredData(sensor)
    return data[:, 0], data[:, 2]


def _free_decay(segments: int, steps_per_period: int = 200,
                spectral_radius: float = SPECTRAL_RADIUS, damping_time: float = 0.0,
                periods: int = 6, tip_radius: float = BARE_TIP):
    """Tip y(t) of the filament clamped to ground and released straight with the first
    mode's velocity field: v_y = V φ₁(s/L) and ω_z = V φ₁'(s/L)/L at each node, V = 50 mm/s
    (a tip amplitude of 0.045 mm, 0.4 % of the length: linear), so that the higher modes
    start almost at rest."""
    material = dataclasses.replace(NYLON, damping_time=damping_time)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    items = add_dfm_bristle(mbs, ground, _filament(tip_radius), material, segments)
    speed = 50.0  # mm/s
    for i, node in enumerate(items.nodes, start=1):
        s = i / segments
        velocity = speed * float(mode_shape(s))
        spin = speed * float(mode_slope(s)) / LENGTH
        # Euler parameters at the reference rotation (identity): ṗ = (0, ω/2)
        mbs.SetNodeParameter(node, "initialVelocities",
                             [0.0, velocity, 0.0, 0.0, 0.0, 0.0, 0.5 * spin])
    return _solve(mbs, items.nodes[-1], steps_per_period, spectral_radius, periods * PERIOD)


def _frequency_and_damping(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Frequency [Hz] from the downward zero crossings (linear interpolation between
    steps) and damping ratio [-] from the logarithmic decrement of the troughs between
    them."""
    k = np.nonzero((y[:-1] > 0.0) & (y[1:] <= 0.0))[0]
    crossings = t[k] + (t[k + 1] - t[k]) * y[k] / (y[k] - y[k + 1])
    frequency = (len(crossings) - 1) / (crossings[-1] - crossings[0])
    troughs = np.array([-y[(t > a) & (t < b)].min()
                        for a, b in zip(crossings[:-1], crossings[1:], strict=True)])
    decrement = math.log(troughs[0] / troughs[-1]) / (len(troughs) - 1)
    return frequency, decrement / math.hypot(2.0 * math.pi, decrement)


@functools.cache
def _frequency_error(segments: int, steps_per_period: int = 200,
                     spectral_radius: float = SPECTRAL_RADIUS) -> tuple[float, float]:
    """(f/f₁ − 1, numerical damping ratio) of the undamped filament's free decay."""
    frequency, damping = _frequency_and_damping(
        *_free_decay(segments, steps_per_period, spectral_radius))
    return frequency / FREQUENCY - 1.0, damping


def test_reference_frequency_of_the_filament():
    # the "near 350 Hz"; the exact value is in the module docstring
    assert FREQUENCY == pytest.approx(348.6, abs=0.05)


@pytest.mark.parametrize("segments", [4, 6, 8, 12, 16])
def test_first_frequency(segments):
    # the issue asks for 2 %; measured: at most +0.19 % (N = 4), so 0.3 %
    error, damping = _frequency_error(segments)
    assert abs(error) < 3e-3
    assert abs(damping) < 2e-4  # no material damping; ρ∞ = 0.8's at 200 spp is ~1e-6


def test_first_frequency_converges_as_one_over_n_squared():
    # Hencky chain: (error(N) - e∞) ∝ 1/N²; measured against N = 24, the ratio of the
    # errors of N = 4 and 8 is 4.3 (4.4 for an exact 1/N² with e∞ = e(24))
    limit = _frequency_error(24)[0]
    assert abs(limit) < 5e-4  # measured -0.024 %: shear and rotary inertia, ~2e-4
    ratio = (_frequency_error(4)[0] - limit) / (_frequency_error(8)[0] - limit)
    assert 3.5 < ratio < 5.5


@pytest.mark.parametrize(("steps_per_period", "largest_error", "largest_damping"), [
    (20, 0.045, 0.015),  # measured -3.8 %, ζ 0.0115: a fifth of the material's 0.055
    (100, 0.0025, 2e-4),  # measured -0.18 %, ζ 1.2e-4
])
def test_spectral_radius_zero_needs_a_hundred_steps_a_period(steps_per_period,
                                                             largest_error, largest_damping):
    # exubrush's default ρ∞ = 0 lengthens the period and damps the mode at coarse steps;
    # the limits are the measured values plus ~20 %
    error, damping = _frequency_error(12, steps_per_period, 0.0)
    assert -largest_error < error < 0.0
    assert 0.0 < damping < largest_damping
    if steps_per_period == 20:  # too coarse for the 2 % the issue asks
        assert error < -0.02


def test_material_damping_ratio_is_stiffness_proportional():
    # C = τK damps the first mode with ζ = τω₁/2 = 0.0548 (τ = 5e-5 s, nylon's default);
    # measured 0.0547 from ten troughs, and the damped frequency f₁√(1 - ζ²) within 0.01 %
    tau = NYLON.damping_time
    t, y = _free_decay(12, damping_time=tau, periods=10)
    frequency, damping = _frequency_and_damping(t, y)
    zeta = stiffness_proportional_damping_ratio(tau, FREQUENCY)
    assert damping == pytest.approx(zeta, rel=0.01)  # 1 %: measured 0.2 %
    assert frequency / math.sqrt(1.0 - damping**2) == pytest.approx(FREQUENCY, rel=1e-3)


def test_default_tip_sphere_lowers_the_frequency_as_a_tip_mass():
    # a filament's default 0.1 mm tip sphere, M = 1.3 % of the filament's mass m at the tip:
    # f ≈ f₁ / √(1 + M / (33/140 m)) (Rayleigh, the static tip-load shape), -2.59 %;
    # measured -2.46 % at N = 12 (0.14 % above the estimate). 0.3 %: the Rayleigh
    # estimate's own error, the sphere's rotary inertia and the model's -0.01 %
    radius = 0.1
    t, y = _free_decay(12, tip_radius=radius)
    frequency, _ = _frequency_and_damping(t, y)
    ratio = 4.0 / 3.0 * math.pi * radius**3 / (SECTION.area * LENGTH)  # M / m
    assert frequency == pytest.approx(FREQUENCY / math.sqrt(1.0 + ratio * 140.0 / 33.0),
                                      rel=3e-3)
    assert frequency < 0.98 * FREQUENCY


def _base_excitation(frequency_ratio: float, segments: int = 12, steps_per_period: int = 100,
                     settle_periods: int = 25, measured_periods: int = 4,
                     amplitude: float = 0.01) -> float:
    """Steady tip amplitude over base amplitude [-] of the filament on a handle whose y
    coordinate is prescribed as ``amplitude`` sin(ωt) [mm], ω = r ω₁.

    The handle is a rigid body whose six coordinates are held by coordinate constraints to
    ground, as exubrush.run.scene drives the head: the lateral constraint's offset is set in
    the pre-step function. Handle and filament start with the base's initial velocity, so
    the transient is only the mode's response to the acceleration; 25 first-mode periods
    at ζ₁ = 0.055 leave 2e-4 of it (e^{-2πζ₁·25}). The amplitude is fitted as a sine and
    cosine at ω (with a constant) to the tip's y over the last ``measured_periods``
    periods of the excitation.
    """
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    omega = 2.0 * math.pi * FREQUENCY * frequency_ratio
    handle = mbs.CreateRigidBody(
        referencePosition=[0.0, 0.0, 0.0], inertia=InertiaCuboid(1.2e-9, [2.0, 2.0, 2.0]),
        nodeType=exu.NodeType.RotationRxyz, gravity=[0.0, 0.0, 0.0],
        initialVelocity=[0.0, amplitude * omega, 0.0], returnDict=True)
    ground_node = mbs.AddNode(eii.NodePointGround())
    ground_marker = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))
    constraints = []
    for axis in range(6):
        marker = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=handle["nodeNumber"],
                                                        coordinate=axis))
        constraints.append(mbs.AddObject(eii.ObjectConnectorCoordinate(
            markerNumbers=[ground_marker, marker])))
    items = add_dfm_bristle(mbs, handle["bodyNumber"], _filament(), NYLON, segments)
    for node in items.nodes:
        mbs.SetNodeParameter(node, "initialVelocities",
                             [0.0, amplitude * omega, 0.0, 0.0, 0.0, 0.0, 0.0])

    def shake(mbs, t):
        mbs.SetObjectParameter(constraints[1], "offset", amplitude * math.sin(omega * t))
        return True

    mbs.SetPreStepUserFunction(shake)
    excitation = 2.0 * math.pi / omega
    end = settle_periods * PERIOD + measured_periods * excitation
    t, y = _solve(mbs, items.nodes[-1], steps_per_period, SPECTRAL_RADIUS, end)
    window = t >= end - measured_periods * excitation - 1e-12
    basis = np.column_stack([np.cos(omega * t[window]), np.sin(omega * t[window]),
                             np.ones(int(window.sum()))])
    (cosine, sine, _), *_ = np.linalg.lstsq(basis, y[window], rcond=None)
    return math.hypot(cosine, sine) / amplitude


ZETA = stiffness_proportional_damping_ratio(NYLON.damping_time, FREQUENCY)  # 0.0548


@pytest.mark.parametrize("frequency_ratio", [
    0.3, 0.5, 0.8,
    pytest.param(1.0, marks=pytest.mark.slow),  # 0.9-1.1 s alone: the longest run
])
def test_base_excitation_amplifies_the_tip_as_the_beam(frequency_ratio):
    amplification = _base_excitation(frequency_ratio)
    # against the one-mode reference, 0.6 %: measured -0.17, -0.36, -0.35, -0.13 %, nearly
    # all of it the second mode's quasi-static share the reference leaves out (-0.17,
    # -0.37, -0.39, -0.03 %)
    assert amplification == pytest.approx(tip_amplification(frequency_ratio, ZETA), rel=6e-3)
    # against five stiffness-damped modes, 0.2 %: measured +0.01, +0.02, -0.02, -0.10 %,
    # the model's frequency error times d ln A / d ln r (3.6 at r = 0.8) and the numerical
    # damping's share of ζ₁ at resonance
    assert amplification == pytest.approx(
        stiffness_damped_tip_amplification(frequency_ratio, ZETA), rel=2e-3)
