"""The block's sliding speed U(t) of a scene's ``motion:`` section (docs/DESIGN.md "Time").

Kinds: ``steady`` (U constant), ``stop`` (U until stop_time, a linear ramp to rest, rest),
``start`` (from rest, a linear ramp up to U from t = 0), ``oscillation`` (reciprocating
sliding from rest, x = A (1 - cos 2 pi f t) for ``cycles`` cycles, U = dx/dt, then rest) and ``table``
(rows (t, U), linear in between, the last U after). A zero ramp is a jump, taken at the
instant just after the breakpoint.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lubecontact.unsteady.dynamics import STEPS_PER_VIBRATION_PERIOD, BaseExcitation

# Steps per oscillation period at most: the integrator must resolve each cycle.
STEPS_PER_PERIOD = 40
MAX_STEPS = 20000  # time steps of one run; a motion that needs more is refused before it starts


@dataclass(frozen=True)
class SpeedHistory:
    """U(t) of one motion, with what the integrator needs to know about it."""

    kind: str
    times: np.ndarray  # breakpoints of a piecewise-linear U (s)
    speeds: np.ndarray  # U at the breakpoints (m/s)
    end: float  # last simulated instant (s)
    rest_from: float | None  # from this instant on U = 0 for good (None: never)
    period: float | None = None  # oscillation period (s)
    amplitude_speed: float = 0.0  # oscillation: 2 pi f A (m/s)

    @classmethod
    def from_scene(cls, scene) -> "SpeedHistory":
        m = scene.motion
        u = scene.operating.speed if m.speed is None else m.speed
        if m.kind == "steady":
            return cls("steady", np.array([0.0]), np.array([u]), m.duration, None if u > 0 else 0.0)
        if m.kind == "stop":
            t0, t1 = m.stop_time, m.stop_time + m.ramp
            return cls("stop", np.array([0.0, t0, t1]), np.array([u, u, 0.0]), m.stop_time + m.duration, t1)
        if m.kind == "start":
            return cls("start", np.array([0.0, m.ramp]), np.array([0.0, u]), m.duration, None if u > 0 else 0.0)
        if m.kind == "oscillation":
            period = 1.0 / m.frequency
            stop = m.cycles * period
            return cls("oscillation", np.array([0.0, stop]), np.array([0.0, 0.0]), max(m.duration, stop), stop,
                       period, 2.0 * math.pi * m.frequency * m.amplitude)
        table = np.asarray(m.table, dtype=float)
        moving = np.flatnonzero(table[:, 1] != 0.0)
        rest = 0.0 if moving.size == 0 else (table[moving[-1] + 1, 0] if moving[-1] + 1 < len(table) else None)
        return cls("table", table[:, 0], table[:, 1], m.duration, rest)

    def speed(self, t: float) -> float:
        """U(t), m/s. At a breakpoint with a jump (zero ramp) the value after it."""
        if self.period is not None:
            if t >= self.rest_from:
                return 0.0
            return self.amplitude_speed * math.sin(2.0 * math.pi * t / self.period)
        i = int(np.searchsorted(self.times, t, side="right"))
        if i == 0:
            return float(self.speeds[0])
        if i == self.times.size:
            return float(self.speeds[-1])
        t0, t1 = self.times[i - 1], self.times[i]
        return float(self.speeds[i - 1] + (t - t0) / (t1 - t0) * (self.speeds[i] - self.speeds[i - 1]))

    def initial_speed(self) -> float:
        """U just before t = 0+ (the steady state the run starts from)."""
        return float(self.speeds[0])

    def peak_speed(self) -> float:
        """Largest |U| of the motion, m/s: the film the mesh's inlet must carry (mesh.py)."""
        if self.period is not None:
            return abs(self.amplitude_speed)
        return float(np.max(np.abs(self.speeds)))

    def reverses(self) -> bool:
        """Whether the sliding runs backwards (U < 0) at some instant: an oscillation, or a
        table with a negative speed."""
        return self.period is not None or bool(np.any(self.speeds < 0.0))

    def breakpoints(self) -> list[float]:
        """Instants where U is not smooth: steps land on them."""
        return sorted({float(t) for t in self.times if 0.0 < t < self.end} | ({self.rest_from} if self.rest_from else set()))

    @property
    def max_step(self) -> float:
        """Largest time step the motion allows while it moves (s)."""
        return self.period / STEPS_PER_PERIOD if self.period is not None else math.inf


def motion_problems(scene) -> list[str]:
    """Why the transient cannot follow ``scene``'s motion (empty when it can): checks of the
    scene that only the time model makes, shared by ``transient`` and ``lubecontact show``."""
    problems = []
    if not scene.effects.asperity_contact and SpeedHistory.from_scene(scene).initial_speed() <= 0.0:
        problems.append(
            f"motion.kind = {scene.motion.kind!r}: smooth surfaces (effects.asperity_contact = false) cannot carry "
            "the load at rest, where this motion starts; allowed: enable asperity_contact, or a motion that starts sliding"
        )
    history = SpeedHistory.from_scene(scene)
    if history.period is not None:
        moving = history.rest_from if history.rest_from is not None else history.end
        needed = moving / history.max_step
        if needed > MAX_STEPS:
            problems.append(
                f"motion.cycles = {scene.motion.cycles} at motion.frequency = {scene.motion.frequency:g} Hz needs at "
                f"least {needed:.3g} time steps ({STEPS_PER_PERIOD} a period); allowed: at most {MAX_STEPS} steps, "
                f"about {MAX_STEPS // STEPS_PER_PERIOD} cycles"
            )
    if scene.lubricant.rheology != "newtonian" and scene.motion.kind != "steady" and scene.mesh.ny > 1:
        problems.append(
            f"lubricant.rheology = {scene.lubricant.rheology!r} with a motion on a 2-D mesh: a grease's time steps "
            "fail there where the plug forms at rest (the connector's Bingham stop on 21 x 21 at t = 6.3 s, a "
            "Newton step finding no descent) or take minutes (on 51 x 51, 0.1 s of it in 3 min; docs/physics.md "
            "section 21); allowed: mesh.ny = 1, or a 'newtonian' lubricant"
        )
    m = scene.motion
    if m.vibration in ("sine_sweep", "random") and not m.vibration_frequency_end > m.vibration_frequency:
        problems.append(
            f"motion.vibration = {m.vibration!r} runs from motion.vibration_frequency = {m.vibration_frequency:g} Hz to "
            f"motion.vibration_frequency_end = {m.vibration_frequency_end:g} Hz; allowed: an end above the start"
        )
    elif m.vibration != "none":
        highest = BaseExcitation.from_scene(scene).highest_frequency()
        needed = (m.stop_time + m.duration) * highest * STEPS_PER_VIBRATION_PERIOD
        if needed > MAX_STEPS:
            problems.append(
                f"motion.vibration = {m.vibration!r} up to {highest:g} Hz "
                f"for motion.duration = {m.duration:g} s needs at least {needed:.3g} time steps "
                f"({STEPS_PER_VIBRATION_PERIOD} a period); allowed: at most {MAX_STEPS} steps"
            )
    if m.vibration != "none" and (m.mass == 0.0 or m.vibration_acceleration == 0.0):
        problems.append(
            f"motion.vibration = {m.vibration!r} acts on the contact through its mass: it needs motion.mass > 0 "
            f"(is {m.mass:g} kg) and motion.vibration_acceleration not 0 (is {m.vibration_acceleration:g} m/s^2)"
        )
    if m.vibration == "none" and m.vibration_acceleration != 0.0:
        problems.append(
            f"motion.vibration_acceleration = {m.vibration_acceleration:g} m/s^2 with motion.vibration = 'none': there "
            "is no excitation to apply it to; allowed: a motion.vibration (sine, sine_sweep, random, "
            "half_sine_shock) with motion.mass > 0, or no motion.vibration_acceleration"
        )
    return problems
