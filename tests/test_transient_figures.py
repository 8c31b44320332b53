"""The transient figures (lubecontact.plotting.transient) on synthetic series: a title that
fits the figure, series whose markers stay visible where they coincide (issue 29 item 12)."""

import numpy as np
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Text

import lubecontact as lc
from lubecontact.plotting import transient as plots
from lubecontact.plotting.figures import unit_label
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


def test_the_vibration_title_fits_the_figure():
    fig = plots.vibration_figure(series(), "Reciprocating sliding of the Table 1 contact (line contact)")
    FigureCanvasAgg(fig).draw()
    title, = [text for text in fig.findobj(Text) if text.get_text() == fig.get_suptitle()]
    box = title.get_window_extent()
    width = fig.get_window_extent()
    assert box.x0 >= width.x0 and box.x1 <= width.x1
    assert "1 mm at 20 Hz" in fig.get_suptitle() and "open 25 %" in fig.get_suptitle()


def test_coinciding_reconnect_series_stay_visible():
    points = [{"x": x, "series": f, "label": f"F = {f:g} N", "ds": series()} for f in (1.0, 2.0) for x in (0.1, 1.0)]
    fig = plots.reconnect_figure(points, "dynamic viscosity mu", "Pa s", "title")
    lines = [line for line in fig.axes[0].get_lines() if line.get_label().startswith("F =")]
    assert len({line.get_marker() for line in lines}) == 2  # equal times: different markers
    assert lines[1].get_markersize() < lines[0].get_markersize() and lines[1].get_zorder() > lines[0].get_zorder()


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
