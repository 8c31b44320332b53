"""The transient figures (lubecontact.plotting.transient) on synthetic series: a title that
fits the figure, series whose markers stay visible where they coincide (issue 29 item 12);
the shock figure (issue 28 item 6) on synthetic series and on one real lift-off, and the
shock study's cases (config/transient.yaml) planned by their scene hashes; the grease figure
(issue 28 item 6) on synthetic series against the closed-form stop film, and its cases."""

import math

import numpy as np
import pytest
import xarray as xr
import yaml
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Text
from test_transient import CONFIG_KEY

import lubecontact as lc
from lubecontact.physics.yield_stress_flow import bingham_squeeze_stop_film
from lubecontact.plotting import transient as plots
from lubecontact.plotting.figures import unit_label
from lubecontact.studies import transient_cases as study
from lubecontact.studies.transient_cases import key_words


def series(fraction=0.25):
    scene = lc.load_scene("config/scenes/table1.yaml", {"motion.kind": "oscillation", "motion.amplitude": 1e-3,
                                                        "motion.frequency": 20.0})
    t = np.linspace(0.0, 0.15, 50)
    return xr.Dataset(
        {"speed": ("time", np.abs(np.sin(40 * np.pi * t))), "contact_resistance": ("time", 1e-5 + 20 * np.sin(40 * np.pi * t) ** 2),
         "open_resistance": ((), 10.0), "rest_resistance": ((), 1e-5), "open_fraction": ((), fraction),
         "reconnect_time": ((), 0.01), "converged": ((), 1)},
        coords={"time": t}, attrs={"scene": scene.canonical_yaml()},
    )


def assert_the_title_fits(fig):
    """The figure's suptitle, drawn, lies within the figure's width."""
    FigureCanvasAgg(fig).draw()
    title, = [text for text in fig.findobj(Text) if text.get_text() == fig.get_suptitle()]
    box = title.get_window_extent()
    width = fig.get_window_extent()
    assert box.x0 >= width.x0 and box.x1 <= width.x1


def test_the_vibration_title_fits_the_figure():
    fig = plots.vibration_figure(series(), "Reciprocating sliding of the Table 1 contact (line contact)")
    assert_the_title_fits(fig)
    assert "1 mm at 20 Hz" in fig.get_suptitle() and "open 25 %" in fig.get_suptitle()


def test_coinciding_reconnect_series_stay_visible():
    points = [{"x": x, "series": f, "label": f"F = {f:g} N", "ds": series()} for f in (1.0, 2.0) for x in (0.1, 1.0)]
    fig = plots.reconnect_figure(points, "dynamic viscosity mu", "Pa s", "title")
    lines = [line for line in fig.axes[0].get_lines() if line.get_label().startswith("F =")]
    assert len({line.get_marker() for line in lines}) == 2  # equal times: different markers
    assert lines[1].get_markersize() < lines[0].get_markersize() and lines[1].get_zorder() > lines[0].get_zorder()


def test_a_design_chart_bars_each_reconnect_time_by_its_threshold():
    """Each reconnect time carries a vertical bar from the time with its threshold a tenth
    higher to the time with it a tenth lower (series.threshold_times); a case file written
    before those existed, or one whose lower threshold is never reached, has none."""
    with_bars = series().assign(reconnect_time_higher_threshold=0.008, reconnect_time_lower_threshold=0.015)
    never = series().assign(reconnect_time_higher_threshold=0.008, reconnect_time_lower_threshold=math.inf)
    points = [{"x": 0.1, "series": 1.0, "label": "F = 1 N", "ds": with_bars},
              {"x": 1.0, "series": 1.0, "label": "F = 1 N", "ds": series()},
              {"x": 10.0, "series": 1.0, "label": "F = 1 N", "ds": never}]
    fig = plots.reconnect_figure(points, "dynamic viscosity mu", "Pa s", "title")
    ax = fig.axes[0]
    segments = [seg for coll in ax.collections for seg in coll.get_segments()]
    assert len(segments) == 1  # the one case with both ends finite
    np.testing.assert_allclose(segments[0], [[0.1, 0.008], [0.1, 0.015]])
    assert "threshold 10% higher and lower" in ax.get_title()


def test_a_temperature_chart_keeps_zero_celsius_on_a_linear_axis():
    """The temperature design chart (config/transient.yaml figures.temperature): a cold start at
    0 C cannot sit on a log axis; the unit is written as C, not as the key's 'degC'."""
    points = [{"x": t, "series": 5.0, "label": "F = 5 N", "ds": series()} for t in (0.0, 20.0, 45.0)]
    fig = plots.reconnect_figure(points, key_words("operating.temperature"), unit_label("degC"), "title", log_x=False)
    ax = fig.axes[0]
    assert ax.get_xscale() == "linear" and ax.get_yscale() == "log"
    assert ax.get_xlabel() == "temperature of the oil (\u00b0C)"
    line, = [line for line in ax.get_lines() if line.get_label() == "F = 5 N"]
    assert list(line.get_xdata()) == [0.0, 20.0, 45.0]


def test_a_design_chart_title_of_any_length_stays_inside_the_figure():
    """transient_temperature's title (config/transient.yaml) was cut at 'line contact)': a long
    title is broken into lines, every character kept, none outside the figure."""
    title = ("Time to reconnect after a stop from 1 m/s against temperature (Table 1 contact, ISO VG 100 oil, "
             "line contact)")
    points = [{"x": t, "series": 5.0, "label": "F = 5 N", "ds": series()} for t in (0.0, 20.0, 45.0)]
    fig = plots.reconnect_figure(points, key_words("operating.temperature"), unit_label("degC"), title, log_x=False)
    FigureCanvasAgg(fig).draw()
    text = fig.axes[0].title
    assert text.get_text().split("\n\u25b2")[0].replace("\n", " ") == title
    box, width = text.get_window_extent(), fig.get_window_extent()
    assert box.x0 >= width.x0 and box.x1 <= width.x1


G = 9.80665  # standard gravity, m/s^2
# the shock figure's contact (config/transient.yaml figures.shock), without its peak
SHOCK = {"mesh.ny": 1, "operating.speed": 0.0, "operating.force": 0.5, "motion.kind": "steady",
         "motion.duration": 0.05, "motion.mass": 1e-3, "motion.spring_stiffness": 2000.0,
         "motion.vibration": "half_sine_shock", "motion.shock_duration": 0.011}


def struck(peak_g, resistance, events=()):
    """A synthetic shock series: ``resistance`` on 0..50 ms, ``events`` (start, duration) in s."""
    scene = lc.load_scene("config/scenes/table1.yaml", {**SHOCK, "motion.vibration_acceleration": -peak_g * G})
    t = np.linspace(0.0, 0.05, len(resistance))
    starts, durations = zip(*events) if events else ((), ())
    return xr.Dataset(
        {"contact_resistance": ("time", np.asarray(resistance, dtype=float)),
         "min_film_thickness": ("time", np.full(len(resistance), 0.7e-6)),
         "open_resistance": ((), 10.0), "event_count": ((), len(events)), "event_open_time": ((), sum(durations)),
         "event_start": ("event", np.array(starts, dtype=float)), "event_duration": ("event", np.array(durations, dtype=float)),
         "event_open_at_end": ("event", np.zeros(len(events), dtype=bool))},
        coords={"time": t}, attrs={"scene": scene.canonical_yaml()},
    )


def shock_cases():
    """A 30 g shock that stays closed, a 100 g one that lifts (R infinite on 20..30 ms, one
    event 18..32 ms) and comes back."""
    closed = struck(30, np.full(51, 1e-4))
    lifted = np.full(51, 1e-4)
    lifted[18:33] = 1e3
    lifted[20:31] = np.inf
    return [("30 g peak", closed), ("100 g peak", struck(100, lifted, events=[(0.018, 0.014)]))]


def shaded(ax):
    """The shaded spans of an axes, each a box in data coordinates (x: ms)."""
    return [p.get_path().get_extents(p.get_patch_transform() + p.get_data_transform() - ax.transData)
            for p in ax.patches]


def test_the_shock_figure_shades_each_event_where_the_data_put_it():
    fig = plots.shock_figure(shock_cases(), "A struck contact")
    base, middle, bottom = fig.axes
    spans = shaded(middle)
    assert len(spans) == 1  # the closed contact has none
    np.testing.assert_allclose([spans[0].x0, spans[0].x1], [18.0, 32.0])  # ms
    legend = [text.get_text() for text in middle.get_legend().get_texts()]
    assert "30 g peak: no event" in legend and "100 g peak: 1 event(s), open 14 ms in all" in legend
    threshold, = [line for line in middle.get_lines() if line.get_label().startswith("open threshold")]
    assert threshold.get_linestyle() == "--" and list(threshold.get_ydata()) == [10.0, 10.0]
    assert threshold.get_label() == "open threshold 10 \u03a9"
    # top: the base acceleration away from the block in g, each shock's peak at 5.5 ms
    peaks = [max(line.get_ydata()) for line in base.get_lines()]
    np.testing.assert_allclose(peaks, [30.0, 100.0], rtol=1e-4)


def test_the_shock_figure_marks_an_infinite_resistance_on_the_top_edge():
    fig = plots.shock_figure(shock_cases(), "A struck contact")
    middle = fig.axes[1]
    top = middle.get_ylim()[1]
    markers = [line for line in middle.get_lines() if line.get_marker() == "^" and len(line.get_xdata())]
    assert len(markers) == 1  # only the lifted contact
    np.testing.assert_allclose(markers[0].get_xdata(), np.linspace(0.0, 50.0, 51)[20:31])
    assert set(markers[0].get_ydata()) == {top}
    # its line runs along the edge there, not dropped
    lifted_line = next(line for line in middle.get_lines() if line.get_label().startswith("100 g peak"))
    assert np.isfinite(lifted_line.get_ydata()).all() and lifted_line.get_ydata()[25] == top
    assert any("lift-off" in text.get_text() for text in middle.get_legend().get_texts())


def test_the_shock_figure_speaks_in_words_and_units_within_its_width():
    fig = plots.shock_figure(shock_cases(), "A connector contact struck by half-sine shocks away from the block")
    assert_the_title_fits(fig)
    texts = [text.get_text() for text in fig.findobj(Text) if text.get_text()]
    assert not [text for text in texts if CONFIG_KEY.search(text)]
    title = fig.get_suptitle()
    for words in ("spring preload 0.5 N", "moving mass 0.001 kg", "spring stiffness 2000 N/m",
                  "lubricant viscosity 0.1 Pa s"):
        assert words in title.replace("\n", " ")
    labels = [ax.get_ylabel() for ax in fig.axes] + [fig.axes[-1].get_xlabel()]
    assert all(label.endswith(")") and "(" in label for label in labels)  # each with its unit


def test_a_real_lift_off_is_drawn_with_its_events():
    """The test configuration's 100 g shock (config/test.yaml): a rigid 31-node line lifts."""
    scene = lc.load_scene("config/scenes/table1.yaml", {**SHOCK, "mesh.nx": 31, "effects.elastic_deformation": False,
                                                        "motion.tolerance": 1e-2, "motion.vibration_acceleration": -100 * G})
    ds = lc.transient(scene, progress=False)
    assert ds["event_count"].item() >= 1 and np.isinf(ds["contact_resistance"].values).any()
    middle = plots.shock_figure([("100 g peak", ds)], "A struck contact").axes[1]
    spans = shaded(middle)
    ends = ds["event_start"].values + ds["event_duration"].values
    np.testing.assert_allclose([(b.x0, b.x1) for b in spans], np.c_[ds["event_start"].values, ends] * 1e3)
    marked, = [line for line in middle.get_lines() if line.get_marker() == "^" and len(line.get_xdata())]
    assert len(marked.get_xdata()) == np.isinf(ds["contact_resistance"].values).sum()
    # the legend says when it came back, counted from the shock's end (11 ms)
    recon = ds["reconnect_time"].item()
    assert 0.0 < recon and any(f"reconnected {recon * 1e3:.3g} ms after the shock" in text.get_text()
                               for text in middle.get_legend().get_texts())


@pytest.mark.parametrize("empty", [{"values": []}, {"series": {"operating.force": []}}])
def test_a_design_chart_of_no_case_is_refused_naming_the_figure_and_the_list(empty):
    """An empty list drew empty axes without a word (a config's `values: []`)."""
    spec = study.study_spec("config/transient.yaml", {"figures": {"reconnect": empty}})
    with pytest.raises(ValueError, match=r"transient figure 'reconnect': '(values|series operating.force)' is empty"):
        study.figure_cases(spec)


@pytest.mark.parametrize("overrides, words", [
    ({"sett": {"mesh.nx": 21}}, "unknown key 'sett'; allowed: base, figures, set"),
    ({"figures": {"stop": {"curves": []}}}, "transient figure 'stop': 'curves' is empty"),
    ({"figures": {"stop": {"curves": [{"label": "a", "set": {}}, {"label": "a", "sett": {}}]}}},
     "transient figure 'stop': curve label 'a' given twice"),
    ({"figures": {"stop": {"curves": [{"label": "a", "sett": {}}]}}}, "curve 1: unknown key 'sett'"),
    ({"figures": {"reconnect": {"values": [0.1, 0.1]}}}, "transient figure 'reconnect': value 0.1 of 'values' given twice"),
    ({"figures": {"stopp": {"titel": "x"}}}, "transient figure 'stopp' (single case): unknown key 'titel'"),
])
def test_a_transient_study_refuses_what_it_would_ignore_or_draw_empty(overrides, words):
    # found by a hostile run (thirtieth session): each was accepted; a misspelt key was
    # ignored, empty curves drew empty axes
    with pytest.raises(ValueError, match="config/transient.yaml") as refused:
        study.study_spec("config/transient.yaml", overrides)
    assert words in str(refused.value)


def test_a_bad_scene_key_of_a_transient_curve_names_the_figure_and_the_curve():
    spec = study.study_spec("config/transient.yaml", {"figures": {"stop": {"curves": [
        {"label": "thick oil", "set": {"lubricant.viscosty": 1.0}}]}}})
    with pytest.raises(lc.SceneError, match=r"transient figure 'stop', 'thick oil'.*\n.*did you mean lubricant.viscosity"):
        study.figure_cases(spec)


@pytest.mark.parametrize("overrides", [None, "config/test.yaml"])
def test_the_shock_study_plans_one_case_per_shock_by_its_scene(overrides):
    """Each shock is the scene of the study's set, the figure's set and its peak, named by its
    hash; at least one peak stays below the spring's preload over the mass (quasi-static
    lift-off) and one exceeds it."""
    extra = yaml.safe_load(open(overrides))["transient"] if overrides else None
    spec = study.study_spec("config/transient.yaml", extra)
    cases = study.figure_cases(spec)["shock"]
    figure = spec["figures"]["shock"]
    scenes = [lc.load_scene(spec["base"], {**spec["set"], **figure["set"], **curve["set"]}) for curve in figure["curves"]]
    assert [c["id"] for c in cases] == [s.hash for s in scenes] and len(set(c["id"] for c in cases)) == len(cases)
    assert [c["label"] for c in cases] == [curve["label"] for curve in figure["curves"]]
    pull = [-s.motion.mass * s.motion.vibration_acceleration / s.operating.force for s in scenes]
    assert min(pull) < 1.0 < max(pull)
    assert all(s.mesh.ny == 1 and s.motion.vibration == "half_sine_shock" and s.motion.shock_duration == 0.011
               for s in scenes)


def grease_scenes(overrides=None):
    """label -> scene of each curve of the grease figure (config/transient.yaml)."""
    spec = study.study_spec("config/transient.yaml", overrides)
    cases = study.figure_cases(spec)["grease"]
    full = study.case_overrides(spec, {"grease": cases})
    return {case["label"]: lc.load_scene(spec["base"], full[case["id"]]) for case in cases}


def stopped(scene, film, resistance, reconnect):
    """A synthetic stop of ``scene``: ``film`` (m) and ``resistance`` (ohm) on 0..30 s, at rest
    from 1 ms (the study's ramp)."""
    t = np.concatenate([[0.0, 1e-3], np.logspace(-2.9, np.log10(30.0), len(film) - 2)])
    return xr.Dataset(
        {"contact_resistance": ("time", np.asarray(resistance, dtype=float)),
         "min_film_thickness": ("time", np.asarray(film, dtype=float)),
         "rest_resistance": ((), 8.4e-5), "open_resistance": ((), 10.0), "reconnect_time": ((), reconnect),
         "converged": ((), 1)},
        coords={"time": t}, attrs={"scene": scene.canonical_yaml()},
    )


def grease_cases():
    """The figure's four curves as synthetic stops: the oil and the 1 kPa grease reconnect,
    the 3 kPa one stops at 2.4 sigma (closed, never reconnected), the 5 kPa one at its
    closed-form film (open throughout)."""
    scenes = grease_scenes()
    falling = np.linspace(0.0, 1.0, 12)
    shapes = [(4.1e-6, 0.65e-6, 1e3, 8.4e-5, 3.3e-3), (4.6e-6, 0.76e-6, 1e4, 1.3e-4, 8.2e-3),
              (5.9e-6, 1.2e-6, 1e12, 9.7e-4, math.inf), (7.5e-6, 4.47e-6, 1e26, 5.6e11, math.inf)]
    return [(label, stopped(scene, h0 + (h1 - h0) * falling, r0 * (r1 / r0) ** falling, recon))
            for (label, scene), (h0, h1, r0, r1, recon) in zip(scenes.items(), shapes)]


def test_the_grease_figure_draws_the_closed_form_stop_only_where_it_holds():
    cases = grease_cases()
    fig = plots.grease_stop_figure(cases, "A stop with a Bingham grease")
    film, resistance = fig.axes
    dashed = [line for line in film.get_lines() if line.get_linestyle() == "--"]
    # only the 5 kPa grease: 1 kPa's stop film (0.19 nm) and 3 kPa's (0.79 um) lie below 3 sigma
    scene = lc.load_scene(yaml.safe_load(cases[3][1].attrs["scene"]))
    h_stop = bingham_squeeze_stop_film(0.5, 1e-3, 0.01, 1e-3, 5000.0)  # F, L, R, a, tau_y
    assert h_stop == pytest.approx(4.47e-6, rel=1e-3)
    line, = dashed
    assert list(line.get_ydata()) == pytest.approx([h_stop * 1e6] * 2)
    curve = next(l for l in film.get_lines() if l.get_linestyle() == "-" and l.get_color() == line.get_color())
    assert curve.get_ydata()[-1] == pytest.approx(4.47)  # the 5 kPa curve, in its colour
    assert plots.closed_form_stop_film(scene, 7.5e-6) == h_stop
    assert plots.closed_form_stop_film(scene, 4.0e-6) is None  # the stop leaves a thinner film: no squeeze to it
    for off in ({"motion.spring_stiffness": 2000.0}, {"mesh.x_min": -2e-3}, {"mesh.x_min": "auto", "mesh.x_max": "auto"}):
        assert plots.closed_form_stop_film(lc.load_scene(scene, off), 7.5e-6) is None, off
    sigma, = [l for l in film.get_lines() if l.get_linestyle() == ":"]
    assert list(sigma.get_ydata()) == [0.5, 0.5] and "0.5 \u00b5m" in sigma.get_label()
    threshold, = [l for l in resistance.get_lines() if l.get_label().startswith("open threshold")]
    assert list(threshold.get_ydata()) == [10.0, 10.0] and threshold.get_linestyle() == "--"
    assert film.get_yscale() == resistance.get_yscale() == resistance.get_xscale() == "log"


def test_the_grease_figure_says_which_cases_reconnect_in_words_within_its_width():
    fig = plots.grease_stop_figure(grease_cases(), "A stop with a Bingham grease: Table 1 contact at 0.5 N, "
                                                   "stopped from 1 m/s (line contact)")
    assert_the_title_fits(fig)
    legend = [text.get_text() for text in fig.legends[0].get_texts()]
    assert legend[0].endswith(": reconnects 3.3 ms after the stop")
    assert legend[2].endswith(": not reconnected 30 s after the stop")  # closed (1e-3 ohm) but above 2 x rest
    assert legend[3].endswith(": not reconnected 30 s after the stop, open (above 10 \u03a9) throughout")
    texts = [text.get_text() for text in fig.findobj(Text) if text.get_text()]
    assert not [text for text in texts if CONFIG_KEY.search(text)]
    labels = [ax.get_ylabel() for ax in fig.axes] + [fig.axes[-1].get_xlabel()]
    assert all(label.endswith(")") and "(" in label for label in labels)  # each with its unit


@pytest.mark.parametrize("overrides", [None, "config/test.yaml"])
def test_the_grease_study_has_a_grease_that_never_touches(overrides):
    """The grease figure's cases (and the test configuration's): line contacts on a domain
    symmetric about the contact, the oil and Bingham greases of its viscosity, one of them with
    its closed-form stop film in the full film (the one tests/test_grease_stop.py runs)."""
    extra = yaml.safe_load(open(overrides))["transient"] if overrides else None
    scenes = list(grease_scenes(extra).values())
    assert all(s.mesh.ny == 1 and s.mesh.x_min == -s.mesh.x_max for s in scenes)
    greases = [s for s in scenes if s.lubricant.rheology == "bingham"]
    assert greases and all(s.lubricant.viscosity == scenes[0].lubricant.viscosity for s in greases)
    stops = [bingham_squeeze_stop_film(s.operating.force, s.geometry.length, s.geometry.radius, s.mesh.x_max,
                                       s.lubricant.yield_stress) / s.roughness.sigma for s in greases]
    assert max(stops) > plots.FULL_FILM_RATIO and min(stops) < 1.0  # one never touches, one reconnects


def test_the_stop_figure_marks_each_jump_over_an_impasse_and_says_what_the_bars_are():
    """A step that jumped over an impasse at a sealing pocket (impasse_jump) is a vertical bar at
    its end on the resistance, in its case's colour, and the title says what the bars are; a
    stop without one draws no bar and says nothing of them."""
    scene = next(iter(grease_scenes().values()))
    falling = np.linspace(0.0, 1.0, 12)
    plain = stopped(scene, 4e-6 - 3e-6 * falling, 1e-3 * 0.1 ** falling, 5e-3)
    jumped = plain.copy()
    jumped["impasse_jump"] = ("time", np.where(np.arange(12) == 7, 1, 0))
    fig = plots.stop_figure([("jumped", jumped), ("plain", plain)], "A stop")
    resistance = fig.axes[0]
    bars = [line for line in resistance.get_lines() if line.get_marker() == "|"]
    bar, = bars
    t_after = jumped["time"].values[7] - scene.motion.stop_time - scene.motion.ramp
    assert list(bar.get_xdata()) == pytest.approx([t_after])
    assert list(bar.get_ydata()) == pytest.approx([jumped["contact_resistance"].values[7]])
    assert bar.get_color() == "C0"
    assert "bars: a step the state jumped over where a pocket of the film sealed" in resistance.get_title().replace("\n", " ")
    fig = plots.stop_figure([("plain", plain)], "A stop")
    assert not [line for line in fig.axes[0].get_lines() if line.get_marker() == "|"]
    assert "bars" not in fig.axes[0].get_title()
