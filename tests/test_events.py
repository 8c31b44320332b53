"""Discontinuity events of a transient (unsteady/events.py, docs/DESIGN.md "Time") against
independent truths: the crossing times of a sampled sine film, known in closed form (and the
third-order convergence of the integrator's quadratic dense output against the second order
of interpolating the samples), the events' definition on that history (minimum duration,
open at the start and at the end), and one real oscillation end to end, its file checked
for CF units and names as the other transient outputs are."""

import contextlib
import io
import math
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from cfcheck import cf_findings

import lubecontact as lc
from lubecontact.cli.main import main
from lubecontact.unsteady.events import dense_film, locate_events
from lubecontact.unsteady.transient import (ended_in_a_jump, impasse_jumps, jump_share_note, jumps_before,
                                             times_within_jumps)

# film h(t) = H0 + A sin(omega t) on a few nodes; R = R0 exp(h / LENGTH), so R > R0 exp(h*/LENGTH)
# exactly when sin(omega t) > s = (h* - H0) / A: the open intervals are known in closed form
H0, A, LENGTH, R0 = 1.0e-6, 0.5e-6, 0.2e-6, 1.0e-3
OMEGA = 2 * math.pi * 10.0  # 10 Hz: period 0.1 s
NODES = (1, 4)


def resistance_of(film) -> float:
    return R0 * math.exp(float(np.mean(film)) / LENGTH)


def threshold_at(s: float) -> float:
    """The threshold R crosses where sin(omega t) = s."""
    return R0 * math.exp((H0 + A * s) / LENGTH)


def analytic_intervals(s: float, end: float) -> list[tuple[float, float]]:
    """[start, stop] of each interval of [0, end] with sin(omega t) > s."""
    rise, fall = math.asin(s), math.pi - math.asin(s)  # sin > s on (rise, fall) + 2 pi k
    intervals = []
    for k in range(-1, int(OMEGA * end / (2 * math.pi)) + 2):
        start, stop = (rise + 2 * math.pi * k) / OMEGA, (fall + 2 * math.pi * k) / OMEGA
        if stop > 0.0 and start < end:
            intervals.append((max(start, 0.0), min(stop, end)))
    return intervals


def sampled_history(steps_per_period: int, end: float):
    """Levels of a variable-step BDF2 run through the sine film: uneven steps, orders
    1, 2, 2, ... and a first-order step again halfway (as after a breakpoint of the motion)."""
    base = 2 * math.pi / OMEGA / steps_per_period
    times = [0.0]
    while times[-1] < end:
        times.append(min(times[-1] + base * (1.0 + 0.4 * math.sin(37.0 * times[-1])), end))  # smoothly uneven
    times = np.array(times)
    films = [np.full(NODES, H0 + A * math.sin(OMEGA * t)) for t in times]
    orders = [0, 1] + [2] * (times.size - 2)
    orders[times.size // 2] = 1
    resistance = np.array([resistance_of(film) for film in films])
    return times, films, orders, resistance


def events_of(history, threshold, min_duration=0.0):
    times, films, orders, resistance = history

    def resistance_at(step, t):
        return resistance_of(dense_film(times, films, orders, step, t))

    return locate_events(times, resistance, threshold, min_duration, resistance_at)


def log_linear_edges(history, threshold) -> list[float]:
    """Crossings by interpolating log R linearly between the samples (what reconnect_time does)."""
    times, _, _, resistance = history
    above = resistance > threshold
    edges = []
    for i in np.flatnonzero(above[1:] != above[:-1]) + 1:
        r0, r1 = math.log(resistance[i - 1]), math.log(resistance[i])
        edges.append(times[i - 1] + (math.log(threshold) - r0) / (r1 - r0) * (times[i] - times[i - 1]))
    return edges


def located_edges(events) -> list[float]:
    return [edge for event in events.events for edge in (event.start, event.end) if edge > 0.0 and not (
        event.open_at_end and edge == event.end)]


def analytic_edges(s, end) -> list[float]:
    return [edge for interval in analytic_intervals(s, end) for edge in interval if 0.0 < edge < end]


def test_dense_output_goes_through_the_levels():
    times, films, orders, _ = sampled_history(40, 0.1)
    for step in (1, 2, 7, len(times) // 2, len(times) - 1):
        np.testing.assert_allclose(dense_film(times, films, orders, step, times[step]), films[step], rtol=1e-14)
        np.testing.assert_allclose(dense_film(times, films, orders, step, times[step - 1]), films[step - 1], rtol=1e-14)


def test_edges_match_the_closed_form_crossings_at_third_order():
    # twelve thresholds from near the trough to near the crest (none crossed at the run's end),
    # 40 to 60 edges in all: the largest error over them against the step
    end, period = 0.25, 2 * math.pi / OMEGA
    errors, sample_errors = [], []
    for steps in (80, 160):
        history = sampled_history(steps, end)
        located, sampled, truth = [], [], []
        for s in np.linspace(-0.9, 0.9, 12):
            threshold = threshold_at(s)
            located += located_edges(events_of(history, threshold))
            sampled += log_linear_edges(history, threshold)
            truth += analytic_edges(s, end)
        assert len(located) == len(sampled) == len(truth) > 40
        errors.append(np.max(np.abs(np.array(located) - truth)))
        sample_errors.append(np.max(np.abs(np.array(sampled) - truth)))
    assert errors[1] < 3e-6 * period  # steps of 1/160 of the period: each edge within 1/300 000 of it
    assert sample_errors[1] > 20 * errors[1]  # interpolating the samples is measurably worse (62 x)
    # the quadratic dense output converges as dt^3 (measured 2.99), interpolating the samples
    # as dt^2 (2.15)
    assert math.log2(errors[0] / errors[1]) > 2.7
    assert 1.7 < math.log2(sample_errors[0] / sample_errors[1]) < 2.5


def test_events_open_from_the_start_and_at_the_end_and_their_totals():
    end = 0.23  # the run ends during the third interval above s = -0.6
    s = -0.6
    history = sampled_history(80, end)
    events = events_of(history, threshold_at(s))
    truth = analytic_intervals(s, end)
    assert events.count == len(truth) == 3
    first, last = events.events[0], events.events[-1]
    assert first.start == 0.0 and not first.open_at_end  # open from t = 0: sin 0 > -0.6
    assert last.open_at_end and last.end == end and not any(e.open_at_end for e in events.events[:-1])
    open_time = sum(stop - start for start, stop in truth)
    assert events.open_time == pytest.approx(open_time, abs=1e-6)
    assert events.longest == pytest.approx(max(stop - start for start, stop in truth), abs=1e-6)
    # the open time within a window is the events' overlap with it (the open fraction's numerator)
    assert events.open_time_until(end) == pytest.approx(events.open_time, rel=1e-15)
    window = 0.1
    within = sum(max(0.0, min(stop, window) - start) for start, stop in truth)
    assert events.open_time_until(window) == pytest.approx(within, abs=1e-6)
    # the peak: the largest sampled R in each event, near R at the crest of the sine
    crest = R0 * math.exp((H0 + A) / LENGTH)
    assert all(crest * 0.99 < e.peak_resistance <= crest for e in events.events)


def test_events_shorter_than_the_minimum_duration_are_dropped_but_an_open_end_is_kept():
    s, end = 0.3, 0.23  # closed events last (pi - 2 asin s) / omega; the run ends inside the third
    duration = (math.pi - 2 * math.asin(s)) / OMEGA
    history = sampled_history(80, end)
    threshold = threshold_at(s)
    kept = events_of(history, threshold, min_duration=0.999 * duration)
    assert kept.count == 3 and kept.events[-1].open_at_end
    assert [e.duration for e in kept.events[:2]] == pytest.approx([duration] * 2, abs=1e-6)
    dropped = events_of(history, threshold, min_duration=1.001 * duration)
    assert dropped.count == 1 and dropped.events[0].open_at_end  # still open at the end: not judged short
    assert dropped.events[0].duration < duration


def test_no_crossing_and_an_infinite_threshold_give_no_events():
    history = sampled_history(40, 0.2)
    assert events_of(history, threshold_at(1.2)).count == 0  # above the crest
    assert events_of(history, math.inf).count == 0  # no contact at rest: the relative threshold
    everything = events_of(history, threshold_at(-1.2))  # below the trough: open the whole run
    assert everything.count == 1 and everything.events[0].duration == pytest.approx(0.2, rel=1e-15)


# The vibration case of config/transient.yaml as a rigid 31-node line contact over 0.15 s of
# oscillation (three cycles at 20 Hz, peak 0.13 m/s) and 0.15 s at rest; the open resistance
# is set between the resting and the sliding resistance (1.5 and 10.7 micro-ohm) so that the
# contact opens near the peak speed of each stroke: six events
VIBRATION = ["--set", "motion.kind=oscillation", "--set", "motion.amplitude=1e-3", "--set", "motion.frequency=20",
             "--set", "motion.cycles=3", "--set", "motion.duration=0.3", "--set", "mesh.ny=1", "--set", "mesh.nx=31",
             "--set", "motion.tolerance=1e-2", "--set", "effects.elastic_deformation=false",
             "--set", "interface.open_resistance=6e-6"]


# what the CF checker says of every transient's ``time`` (s since the motion starts, no date)
TIME_COORDINATE = ("time must be in a valid units format <unit> since <epoch> not s",
                   "time does not have correct time units", 'Time coordinate variable "time" should have a string')


@pytest.fixture(scope="module")
def vibration(tmp_path_factory):
    """(exit code, the file, what the CLI printed)"""
    out = tmp_path_factory.mktemp("events") / "vibration.nc"
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        code = main(["transient", "config/scenes/table1.yaml", *VIBRATION, "--out", str(out)])
    return code, out, printed.getvalue()


def test_a_real_oscillation_reports_its_events_end_to_end(vibration):
    code, out, printed = vibration
    assert code == 0
    with xr.open_dataset(out) as ds:
        assert ds["converged"].item() == 1
        assert ds["event_count"].item() == 6 == ds.sizes["event"]  # one per stroke, two strokes a cycle
        starts, durations = ds["event_start"].values, ds["event_duration"].values
        stroke = 1 / 40  # each stroke's speed peaks at (k + 1/2) / 40 s: each event holds one
        assert np.all((starts < (np.arange(6) + 0.5) * stroke) & ((np.arange(6) + 0.5) * stroke < starts + durations))
        assert ds["event_open_at_end"].values.tolist() == [0] * 6
        # each edge lies between the two levels where the sampled R crosses the threshold
        t, r, threshold = ds["time"].values, ds["contact_resistance"].values, ds["open_resistance"].item()
        for edge in np.concatenate([starts, starts + durations]):
            i = np.searchsorted(t, edge)
            assert (r[i - 1] > threshold) != (r[i] > threshold)
        assert np.all(ds["event_peak_resistance"].values > threshold)
        assert ds["event_open_time"].item() == pytest.approx(durations.sum(), rel=1e-12)
        assert ds["longest_event"].item() == durations.max()
        # open_fraction comes from the same edges: the open time within the oscillation (0.15 s)
        # = open_fraction x 0.15 (the last stroke's event outlasts the motion while the film drains)
        within = np.minimum(starts + durations, 0.15) - np.minimum(starts, 0.15)
        assert within.sum() == pytest.approx(ds["open_fraction"].item() * 0.15, rel=1e-12)
        # above 2 x rest the contact is open from the first stroke until it reconnects at rest:
        # the event ends where reconnect_time (on the same dense output) says, within a step
        assert ds["relative_event_count"].item() == 1
        assert ds["relative_threshold"].item() == pytest.approx(2 * ds["rest_resistance"].item(), rel=1e-15)
        j = np.flatnonzero(r > ds["relative_threshold"].item())[0]  # the event starts in [t[j - 1], t[j]]
        duration = ds["longest_relative_event"].item()
        assert ds["relative_event_open_time"].item() == duration
        reconnected = 0.15 + ds["reconnect_time"].item()
        i = np.searchsorted(t, reconnected)  # reconnect_time lies in [t[i - 1], t[i]]
        assert t[j - 1] + duration <= t[i] and t[i - 1] <= t[j] + duration
        # CF names and units on every variable, as the other transient outputs
        assert all("units" in ds[name].attrs and "long_name" in ds[name].attrs for name in ds.variables)
        assert ds["event"].attrs["units"] == "1" and ds["min_event_duration"].item() == 1e-6
    # the checker's only findings are the time coordinate's (seconds from the motion's start,
    # not a date: no epoch or calendar), as for every transient file so far
    assert [f for f in cf_findings(out) if not any(known in f for known in TIME_COORDINATE)] == []
    assert "above 6e-06 ohm (interface.open_resistance): 6 event(s), open" in printed
    assert "above 3.02e-06 ohm (2 x rest_resistance, motion.reconnect_factor): 1 event(s)" in printed


def test_the_default_threshold_says_why_there_are_no_events(tmp_path, capsys):
    """No event: the dimension is empty and the CLI says why, in words."""
    out = tmp_path / "none.nc"
    assert main(["transient", "config/scenes/table1.yaml", *VIBRATION[:-2], "--set", "motion.cycles=1",
                 "--out", str(out)]) == 0
    assert "above 10 ohm (interface.open_resistance): none: contact_resistance never exceeded it" in capsys.readouterr().out
    with xr.open_dataset(out) as ds:
        assert ds.sizes["event"] == 0 and ds["event_count"].item() == 0 and ds["longest_event"].item() == 0.0
        assert ds["open_fraction"].item() == 0.0


def test_the_minimum_duration_keeps_every_old_hash():
    table1 = lc.load_scene("config/scenes/table1.yaml")
    assert "min_event_duration" not in table1.canonical_yaml()
    assert lc.load_scene("config/scenes/table1.yaml", {"interface.min_event_duration": 1e-6}).hash == table1.hash
    shorter = lc.load_scene("config/scenes/table1.yaml", {"interface.min_event_duration": 1e-9})
    assert shorter.hash != table1.hash and lc.load_scene(shorter) == shorter
    with pytest.raises(lc.SceneError, match=r"interface.min_event_duration = -1: out of range; allowed: a finite number >= 0"):
        lc.load_scene("config/scenes/table1.yaml", {"interface.min_event_duration": -1})


def test_a_time_located_within_an_impasse_jump_is_said_to_be_uncertain_by_it():
    """transient.times_within_jumps: a step that jumped over an impasse (accepted without the
    error test) carries a crossing found on its dense output only to within its length;
    times outside every jump, and at a jump's ends (the levels themselves), say nothing."""
    levels = [SimpleNamespace(time=t, impasse=impasse) for t, impasse in
              ((0.0, ""), (1e-3, ""), (1.2e-3, "x = 0 mm"), (2e-3, ""), (12e-3, "x = 0.1 mm"))]
    jumps = impasse_jumps(levels)
    assert [(before.time, level.time) for before, level in jumps] == [(1e-3, 1.2e-3), (2e-3, 12e-3)]
    note = times_within_jumps(jumps, {"the reconnection": 5e-3, "event 1's start": 0.5e-3,
                                      "event 1's end": 1.2e-3, "event 2's start": 1.1e-3})
    assert "the reconnection at t = 0.005 s, within the jump from 0.002 to 0.012 s" in note
    assert "event 2's start at t = 0.0011 s, within the jump from 0.001 to 0.0012 s" in note
    assert "event 1" not in note
    assert times_within_jumps(jumps, {"the reconnection": 1.5e-3}) == ""
    assert times_within_jumps([], {"the reconnection": 5e-3}) == ""


def test_a_run_that_ends_in_a_jump_without_reconnecting_says_so():
    """transient.ended_in_a_jump: where the last step jumped over an impasse and the contact
    did not reconnect, the end is the jump's landing, not the path: the note says from when to
    when; a run that reconnected, or whose last step is an ordinary one, says nothing."""
    levels = [SimpleNamespace(time=t, impasse=impasse) for t, impasse in
              ((0.0, ""), (0.6, ""), (4.1, "x = 0 mm"), (10.0, "x = 0.1 mm"))]
    jumps = impasse_jumps(levels)
    note = ended_in_a_jump(jumps, levels, math.inf)
    assert "jumped over an impasse from t = 4.1 s to its end at 10 s" in note
    assert ended_in_a_jump(jumps, levels, 3.4) == ""
    ordinary = levels + [SimpleNamespace(time=12.0, impasse="")]
    assert ended_in_a_jump(impasse_jumps(ordinary), ordinary, math.inf) == ""
    assert ended_in_a_jump([], levels[:2], math.inf) == ""


def test_a_reconnection_after_impasse_jumps_carries_their_length():
    """transient.jumps_before and jump_share_note: the jumps that start before the reconnection
    (absolute time) add up, by hand here, to the uncertainty reconnect_time carries (a time
    after a jump inherits where the state went within it); the note speaks where that exceeds
    motion.tolerance of the reconnect time, and says nothing below it, without a jump or
    without a reconnection; where a jump started while the contact still moved, at any share.
    """
    levels = [SimpleNamespace(time=t, impasse=impasse) for t, impasse in
              ((0.0, ""), (1e-3, ""), (1.2e-3, "x = 0 mm"), (2e-3, ""), (12e-3, "x = 0.1 mm"), (20e-3, ""),
               (21e-3, "x = 0.2 mm"))]
    jumps = impasse_jumps(levels)
    assert jumps_before(jumps, 15e-3) == pytest.approx(0.2e-3 + 10e-3, rel=1e-12)  # the third starts after
    assert jumps_before(jumps, 1.5e-3) == pytest.approx(0.2e-3, rel=1e-12)
    assert jumps_before(jumps, 0.5e-3) == 0.0 and jumps_before([], 15e-3) == 0.0
    assert math.isnan(jumps_before(jumps, math.inf))
    # reconnected 14 ms after the rest began at 1 ms: 10.2 ms of jumps are 73 % of it
    note = jump_share_note(jumps_before(jumps, 15e-3), 14e-3, 1e-3)
    assert "impasse jumps of 0.0102 s in all (73 % of it)" in note and "reconnect_time_jumps" in note
    assert jump_share_note(1e-8, 14e-3, 1e-3) == ""  # within the accuracy asked for
    assert jump_share_note(0.0, 14e-3, 1e-3) == "" and jump_share_note(math.nan, math.inf, 1e-3) == ""
    # a jump while the contact still moved: its length bounds nothing, so the note says so at
    # any share and no longer claims the jumps' length as the uncertainty
    moving = jump_share_note(jumps_before(jumps, 1.5e-3), 14e-3, 1e-3, moving=jumps_before(jumps, 1.1e-3))
    assert "0.0002 s of them while the contact still moved" in moving and "does not bound" in moving
    assert "motion.error_bar" in moving and "carries their length" not in moving
    assert "(1.4 % of it)" in jump_share_note(0.2e-3, 14e-3, 0.1, moving=0.2e-3)  # below the tolerance's share too
    assert jump_share_note(0.0, 14e-3, 1e-3, moving=0.0) == ""
