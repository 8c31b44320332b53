"""The contact as a mass on its spring, driven by the base it is mounted on (docs/physics.md
section 22; docs/DESIGN.md "Time").

The cylinder (the moving contact, mass m) is pressed toward the block by the connector's
spring, preloaded by operating.force F0 at the start and of stiffness k_s; block and spring
housing are mounted on one base, whose normal acceleration a_b(t) (toward the block
positive) drives the contact in the base's frame. With z the separation (film h = h_o + z +
delta, Eq. 3), Newton's second law for the cylinder,

    m (z'' + a_b) = F_fluid + F_contact - F0 - k_s (z - z0),

is the force balance of the massless model (Eq. 18) with the applied force replaced by

    F(z) = F0 + k_s (z - z0) + m (z'' + a_b(t)),                               (22.1)

damped by the film itself (its squeeze term). z'' is the variable-step BDF formula applied
twice, to z and to v = z' (the first-order system (z, v)): v = c0 z + sum_j c_j z_{n+1-j}, z'' =
c0 v + sum_j c_j v_{n+1-j}, so dF/dz = k_s + m c0^2 at the new level. With m = 0 and k_s = 0
F is F0: the massless model.

Base excitations, as connector vibration and shock tests give them (EIA-364-28 sine and
random vibration, EIA-364-27 half-sine mechanical shock):

- ``sine``: a_b = A sin(2 pi f t);
- ``sine_sweep``: a_b = A sin(phi(t)), the frequency rising logarithmically from f1 to f2
  over the run's duration D, f(t) = f1 (f2/f1)^(t/D), phi(t) = 2 pi f1 D (k^(t/D) - 1)/ln k
  with k = f2/f1 (phi' = 2 pi f(t));
- ``random``: a flat acceleration spectral density S = A_rms^2/(f2 - f1) over [f1, f2] (a
  random vibration profile), synthesised as the sum of sines at every multiple of 1/D in the
  band (N of them, about (f2 - f1) D), each of amplitude A_rms sqrt(2/N) and a random phase
  from the seed: over the run its mean square is exactly A_rms^2 (Parseval: each sine at a
  whole number of periods has mean square amplitude^2/2);
- ``half_sine_shock``: a_b = A sin(pi t / T) for 0 <= t <= T, zero after.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

# Steps per period of a sine excitation at most (as motion.STEPS_PER_PERIOD for sliding), and
# across a half-sine shock at least.
STEPS_PER_VIBRATION_PERIOD = 40
STEPS_PER_SHOCK = 20
# base excitations that shake the contact to the end of the run (motion.vibration)
CONTINUOUS_VIBRATIONS = ("sine", "sine_sweep", "random")


@dataclass(frozen=True)
class BaseExcitation:
    """a_b(t) of a scene's motion.vibration (m/s^2, toward the block positive; module docstring)."""

    kind: str  # none | sine | sine_sweep | random | half_sine_shock
    acceleration: float  # peak (random: RMS), m/s^2, toward the block positive
    frequency: float  # Hz: sine; the lowest of a sweep or a random band
    duration: float  # s: half_sine_shock's T; sine_sweep's and random's D, the run's duration
    frequency_end: float = math.inf  # Hz: the highest of a sweep or a random band
    seed: int = 0  # random: the phases' seed

    @classmethod
    def from_scene(cls, scene) -> "BaseExcitation":
        m = scene.motion
        duration = m.shock_duration if m.vibration == "half_sine_shock" else m.stop_time + m.duration
        return cls(m.vibration, m.vibration_acceleration, m.vibration_frequency, duration, m.vibration_frequency_end,
                   m.vibration_seed)

    def acceleration_at(self, t: float) -> float:
        if self.kind == "sine":
            return self.acceleration * math.sin(2.0 * math.pi * self.frequency * t)
        if self.kind == "sine_sweep":
            ratio = self.frequency_end / self.frequency
            phase = 2.0 * math.pi * self.frequency * self.duration * (ratio ** (t / self.duration) - 1.0) / math.log(ratio)
            return self.acceleration * math.sin(phase)
        if self.kind == "random":
            frequencies, amplitudes, phases = self.random_components
            return float(np.sum(amplitudes * np.sin(2.0 * math.pi * frequencies * t + phases)))
        if self.kind == "half_sine_shock" and 0.0 <= t <= self.duration:
            return self.acceleration * math.sin(math.pi * t / self.duration)
        return 0.0

    @cached_property
    def random_components(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(frequencies Hz, amplitudes m/s^2, phases) of the random excitation's sines: the N
        multiples of 1/D in [f1, f2], each of amplitude A_rms sqrt(2/N), so that their mean
        square over D is A_rms^2 and the density A_rms^2 D/N ~ A_rms^2/(f2 - f1)."""
        spacing = 1.0 / self.duration
        frequencies = spacing * np.arange(math.ceil(self.frequency / spacing), math.floor(self.frequency_end / spacing) + 1)
        phases = np.random.default_rng(self.seed).uniform(0.0, 2.0 * math.pi, frequencies.size)
        return frequencies, np.full(frequencies.size, abs(self.acceleration) * math.sqrt(2.0 / frequencies.size)), phases

    def highest_frequency(self) -> float:
        """Hz: the fastest the excitation changes (0 for none, 1/(2T) for a shock)."""
        return {"none": 0.0, "sine": self.frequency, "half_sine_shock": 0.5 / self.duration}.get(self.kind,
                                                                                               self.frequency_end)

    def quiet_from(self) -> float | None:
        """The instant from which the base stands still (s): 0 without an excitation, the end
        of a half-sine shock, None for the CONTINUOUS_VIBRATIONS, which last the whole run."""
        if self.kind in CONTINUOUS_VIBRATIONS:
            return None
        return self.duration if self.kind == "half_sine_shock" else 0.0

    def breakpoints(self) -> list[float]:
        """Instants where a_b(t) is not smooth (steps land on them)."""
        return [self.duration] if self.kind == "half_sine_shock" else []

    def max_step(self, t: float) -> float:
        """Largest time step at t that resolves the excitation (s)."""
        if self.kind == "half_sine_shock":
            return self.duration / STEPS_PER_SHOCK if t < self.duration else math.inf
        if self.kind == "none":
            return math.inf
        return 1.0 / (self.highest_frequency() * STEPS_PER_VIBRATION_PERIOD)


@dataclass(frozen=True)
class Dynamics:
    """The contact's mass and spring (scene.motion.mass, spring_stiffness) and its base."""

    mass: float  # kg
    spring_stiffness: float  # N/m
    preload: float  # F0, N
    base: BaseExcitation

    @classmethod
    def from_scene(cls, scene) -> "Dynamics | None":
        """None for the massless contact under a constant force (today's model)."""
        m = scene.motion
        if m.mass == 0.0 and m.spring_stiffness == 0.0:
            return None
        return cls(m.mass, m.spring_stiffness, scene.operating.force, BaseExcitation.from_scene(scene))

    def shortest_step(self, z: float, force_resolution: float) -> float:
        """The shortest time step (s) at which the force balance can see the inertial force
        m z'' at position ``z`` (m) to ``force_resolution`` (N). z'' is a BDF difference of
        positions, c0 (c0 z + ...) + ..., with c0 <= 1.5/dt (BDF2): z held to its float spacing
        u = spacing(|z|) moves it by m u c0^2, and the differences' own rounding by as much
        again, so dt >= 1.5 sqrt(2 m u / resolution). 0 without mass. (A 1 g contact at
        z = 4.8 um, resolving 5e-8 N: 8.7e-9 s.)"""
        if self.mass == 0.0:
            return 0.0
        return 1.5 * math.sqrt(2.0 * self.mass * float(np.spacing(abs(z))) / force_resolution)

    def load(self, t: float, z0: float, coefficients: list[float], positions: list[float],
             velocities: list[float]) -> "SpringLoad":
        """The applied force (22.1) of a step to time t: ``coefficients`` the step's BDF
        coefficients [c0, c1, ...], ``positions`` and ``velocities`` z and v at the levels
        n, n-1, ... (as many as coefficients after c0), z0 the position at the start."""
        c = coefficients
        return SpringLoad(
            preload=self.preload, spring_stiffness=self.spring_stiffness, z0=z0, mass=self.mass,
            rate=c[0], position_history=float(np.dot(c[1:], positions)),
            velocity_history=float(np.dot(c[1:], velocities)), base_acceleration=self.base.acceleration_at(t),
        )


@dataclass(frozen=True)
class SpringLoad:
    """F(z) of (22.1) at one time step (model/model.Model.load)."""

    preload: float  # F0, N
    spring_stiffness: float  # k_s, N/m
    z0: float  # m
    mass: float  # kg
    rate: float  # c0, 1/s
    position_history: float  # sum_j c_j z_{n+1-j}, m/s
    velocity_history: float  # sum_j c_j v_{n+1-j}, m/s^2
    base_acceleration: float  # a_b(t), m/s^2

    def velocity(self, z: float) -> float:
        """v = z' at the new level for position z, m/s."""
        return self.rate * z + self.position_history

    def force(self, z: float) -> tuple[float, float]:
        """(F(z), dF/dz) of (22.1), N and N/m."""
        acceleration = self.rate * self.velocity(z) + self.velocity_history
        spring = self.preload + self.spring_stiffness * (z - self.z0)
        return spring + self.mass * (acceleration + self.base_acceleration), self.spring_stiffness + self.mass * self.rate**2
