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

Base excitations, as connector vibration and shock tests give them (EIA-364-28 sine
vibration, EIA-364-27 half-sine mechanical shock): ``sine`` a_b = A sin(2 pi f t) and
``half_sine_shock`` a_b = A sin(pi t / T) for 0 <= t <= T, zero after.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# Steps per period of a sine excitation at most (as motion.STEPS_PER_PERIOD for sliding), and
# across a half-sine shock at least.
STEPS_PER_VIBRATION_PERIOD = 40
STEPS_PER_SHOCK = 20


@dataclass(frozen=True)
class BaseExcitation:
    """a_b(t) of a scene's motion.vibration (m/s^2, toward the block positive)."""

    kind: str  # none | sine | half_sine_shock
    acceleration: float  # peak, m/s^2 (toward the block positive)
    frequency: float  # Hz (sine)
    duration: float  # s (half_sine_shock)

    @classmethod
    def from_scene(cls, scene) -> "BaseExcitation":
        m = scene.motion
        return cls(m.vibration, m.vibration_acceleration, m.vibration_frequency, m.shock_duration)

    def acceleration_at(self, t: float) -> float:
        if self.kind == "sine":
            return self.acceleration * math.sin(2.0 * math.pi * self.frequency * t)
        if self.kind == "half_sine_shock" and 0.0 <= t <= self.duration:
            return self.acceleration * math.sin(math.pi * t / self.duration)
        return 0.0

    def breakpoints(self) -> list[float]:
        """Instants where a_b(t) is not smooth (steps land on them)."""
        return [self.duration] if self.kind == "half_sine_shock" else []

    def max_step(self, t: float) -> float:
        """Largest time step at t that resolves the excitation (s)."""
        if self.kind == "sine":
            return 1.0 / (self.frequency * STEPS_PER_VIBRATION_PERIOD)
        if self.kind == "half_sine_shock" and t < self.duration:
            return self.duration / STEPS_PER_SHOCK
        return math.inf


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
