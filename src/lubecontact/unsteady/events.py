"""Discontinuity events of a transient (docs/DESIGN.md "Time"): the intervals during which
the contact resistance stays above a threshold for at least a minimum duration, as a
connector discontinuity test counts them (EIA-364-87: events of 1 us and longer).

An event's edges are where R crosses the threshold between two accepted levels. They are
located on the integrator's own dense output, not by interpolating the sampled R: on
(t_{i-1}, t_i] the film is the Lagrange polynomial through the levels i - p .. i, p the BDF
order of step i (integrator.lagrange, the polynomial the integrator's predictor extrapolates
and whose slope at t_i its BDF formula takes), and R of that film is the electrical path of
the instant (physics/electrical/path.py, what model/outputs.point_outputs reports). The
resistance depends on the state only through the film (asperity contact and film
conduction), so no Reynolds solve is needed at a trial time. The edge is the root of
log R - log threshold there (scipy.optimize.brentq; the transient path alone imports it, so
a steady solve does not pay for it: tests/test_startup.py).

An event missed between two levels (R above the threshold only between them) is not seen:
the integrator's error control keeps the film, and so R, smooth on the scale of a step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from lubecontact.physics.electrical.path import electrical_path
from lubecontact.unsteady.integrator import film_on, lagrange

# |log R| beyond this is R = 0 or inf (exp(700) overflows nowhere before it): brentq needs finite values
LOG_LIMIT = 700.0
EDGE_TOLERANCE = 1.0e-10  # an edge is located to this fraction of its step


@dataclass(frozen=True)
class Event:
    """One interval with R above the threshold (s, s, ohm)."""

    start: float  # the time R rises above the threshold (0: open from the start of the run)
    end: float  # the time R falls back, or the run's last time when still open there
    peak_resistance: float  # the largest R at the accepted levels within the event
    open_at_end: bool  # still open when the run ended: ``end - start`` is a lower bound

    @property
    def duration(self) -> float:
        return self.end - self.start


@dataclass(frozen=True)
class Events:
    """The events of one run above one threshold, at least ``min_duration`` long."""

    threshold: float  # ohm
    min_duration: float  # s
    events: tuple[Event, ...]

    @property
    def count(self) -> int:
        return len(self.events)

    @property
    def open_time(self) -> float:
        """Total duration of the events (s)."""
        return float(sum(event.duration for event in self.events))

    @property
    def longest(self) -> float:
        """Duration of the longest event (s); 0 without events."""
        return max((event.duration for event in self.events), default=0.0)

    def open_time_until(self, end: float) -> float:
        """Duration of the events within [0, end] (s)."""
        return float(sum(max(0.0, min(event.end, end) - event.start) for event in self.events))


def dense_film(times, films, orders, step: int, t: float) -> np.ndarray:
    """The film at t in [times[step - 1], times[step]]: the polynomial of that BDF step
    through the levels step - order .. step (integrator.lagrange); ``films`` of those levels
    on one mesh (the step's: dense_resistance carries the levels before the mesh at rest onto
    it as the step read them), the others not read."""
    used = slice(max(step - max(orders[step], 1), 0), step + 1)
    return lagrange(list(times[used]), list(films[used]), t)


def log_excess(resistance: float, threshold: float) -> float:
    """log(R / threshold), held within +-LOG_LIMIT so that R = 0 and R = inf keep their sign."""
    if resistance <= 0.0:
        return -LOG_LIMIT
    if math.isinf(resistance):
        return LOG_LIMIT
    return min(max(math.log(resistance / threshold), -LOG_LIMIT), LOG_LIMIT)


def crossing_time(times, resistance, threshold: float, step: int, resistance_at) -> float:
    """The time in [times[step - 1], times[step]] where R crosses ``threshold``, R being
    ``resistance_at(step, t)`` between the levels and the levels' own values at them."""
    a, b = float(times[step - 1]), float(times[step])
    ends = {a: log_excess(resistance[step - 1], threshold), b: log_excess(resistance[step], threshold)}

    def excess(t: float) -> float:
        return ends[t] if t in ends else log_excess(resistance_at(step, t), threshold)

    return float(brentq(excess, a, b, xtol=EDGE_TOLERANCE * (b - a)))


def locate_events(times, resistance, threshold: float, min_duration: float, resistance_at) -> Events:
    """Every interval with R > ``threshold`` lasting at least ``min_duration`` (an event
    still open at the end of the run is kept whatever its length so far). ``times`` and
    ``resistance``: the accepted levels; ``resistance_at(step, t)``: R on the dense output of
    the step ending at ``times[step]``, for t between ``times[step - 1]`` and it."""
    times, resistance = np.asarray(times, dtype=float), np.asarray(resistance, dtype=float)
    above = resistance > threshold
    events, start, first = [], float(times[0]), 0  # open from the start when above[0]
    for i in range(1, times.size):
        if above[i] == above[i - 1]:
            continue
        edge = crossing_time(times, resistance, threshold, i, resistance_at)
        if above[i]:
            start, first = edge, i
        else:
            events.append(Event(start, edge, float(resistance[first:i].max()), False))
    if above[-1]:
        events.append(Event(start, float(times[-1]), float(resistance[first:].max()), True))
    kept = tuple(event for event in events if event.open_at_end or event.duration >= min_duration)
    return Events(threshold, min_duration, kept)


def dense_resistance(levels):
    """``resistance_at(step, t)``: R on the dense output of the step ending at
    levels[step] (integrator.Level), the film of dense_film through that instant's
    electrical path."""
    times = [level.time for level in levels]
    orders = [level.order for level in levels]

    def resistance_at(step: int, t: float) -> float:
        model = levels[step].model
        first = max(step - max(orders[step], 1), 0)
        films = [None] * first + [film_on(level, model) for level in levels[first:step + 1]]
        film = dense_film(times, films, orders, step, t)
        return electrical_path(model.scene, model.mesh, model.contact, film).contact_resistance

    return resistance_at


def level_events(levels, resistance, threshold: float, min_duration: float) -> Events:
    """The events of a transient's accepted levels (integrator.Level) above ``threshold``,
    R between levels from the dense output (dense_resistance)."""
    return locate_events([level.time for level in levels], resistance, threshold, min_duration,
                         dense_resistance(levels))
