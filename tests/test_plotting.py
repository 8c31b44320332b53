"""Figure rendering from a collected figure Dataset (lubecontact.plotting.figures), on synthetic data.

Truths used: x quantities recomputed by hand (U/F, mu U/F); where a marked point must sit
(data coordinates of a non-converged point; the top edge, in axes coordinates, for +inf);
the PNG and PDF file signatures.
"""

import numpy as np
import pytest
import xarray as xr
from matplotlib.image import imread

from lubecontact.plotting import figures as plotting

SPEEDS = [1e-3, 1e-2, 1e-1, 1.0]
SIGMAS = [0.5e-6, 1.0e-6]


def figure_dataset():
    """Two curves over four speeds; sigma = 0.5 um is open at 1 m/s and not converged at 0.1 m/s."""
    resistance = np.array([[1e-6, 2e-6, 1e-3, np.inf], [1e-6, 1.5e-6, 1e-5, 1e-2]])
    converged = np.array([[1, 1, 0, 1], [1, 1, 1, 1]], dtype=np.int32)
    dims = ("sigma", "speed")
    return xr.Dataset(
        {
            "contact_resistance": (dims, resistance, {"units": "ohm", "long_name": "electrical contact resistance (Eqs. 15-17)"}),
            "friction_coefficient": (dims, np.array([[0.1, 0.09, 0.05, 0.04], [0.1, 0.095, 0.07, 0.05]]), {"units": "1", "long_name": "friction coefficient"}),
            "converged": (dims, converged, {"units": "1", "long_name": "converged"}),
            "open_circuit": (dims, np.isinf(resistance).astype(np.int32), {"units": "1", "long_name": "open circuit"}),
            "case_id": (dims, np.array([[f"case{i}{j}" for j in range(4)] for i in range(2)])),
        },
        coords={
            "sigma": ("sigma", SIGMAS, {"units": "m", "long_name": "RMS roughness sigma"}),
            "speed": ("speed", SPEEDS, {"units": "m s-1", "long_name": "sliding speed U of the block"}),
            "force": ((), 5.0, {"units": "N", "long_name": "normal force"}),
            "viscosity": ((), 0.1, {"units": "Pa s", "long_name": "viscosity"}),
        },
    )


PLOT = {
    "y": "contact_resistance",
    "x": ["speed", "hersey"],
    "xscale": "log",
    "yscale": "log",
    "legend": {"title": "RMS roughness \u03c3", "label": "{sigma:g} \u00b5m", "units": {"sigma": "\u00b5m"}},
}


def test_x_quantities_are_the_normalisations():
    ds = figure_dataset()
    stribeck = plotting.x_quantity(ds, "speed_per_force")
    hersey = plotting.x_quantity(ds, "hersey")
    np.testing.assert_allclose(stribeck.values, np.array(SPEEDS) / 5.0, rtol=1e-15)
    np.testing.assert_allclose(hersey.values, 0.1 * np.array(SPEEDS) / 5.0, rtol=1e-15)
    assert stribeck.attrs["units"] == "m s-1 N-1" and hersey.attrs["units"] == "m-1"
    with pytest.raises(ValueError, match="unknown x quantity"):
        plotting.x_quantity(ds, "reynolds_number")


def test_axis_labels_carry_units():
    assert plotting.axis_label("electrical contact resistance (Eqs. 15-17)", "ohm") == "electrical contact resistance (\u03a9)"
    assert plotting.axis_label("sliding speed U", "m s-1") == "sliding speed U (m/s)"
    assert plotting.axis_label("friction coefficient", "1") == "friction coefficient (\u2013)"


def test_render_marks_non_converged_and_open_points():
    ds = figure_dataset()
    fig = plotting.render(ds, PLOT, title="test figure")
    axes = fig.axes
    assert len(axes) == 2
    for ax in axes:
        assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
        assert "(" in ax.get_xlabel() and ax.get_xlabel().endswith(")")
    assert axes[0].get_ylabel() == "electrical contact resistance (\u03a9)"
    assert axes[1].get_xlabel() == "Hersey number \u03bcU/F (1/m)"

    speed_panel = axes[0]
    crosses = [l for l in speed_panel.lines if l.get_marker() == "x"]
    assert len(crosses) == 1
    np.testing.assert_allclose(crosses[0].get_xdata(), [1e-1])
    np.testing.assert_allclose(crosses[0].get_ydata(), [1e-3])
    triangles = [l for l in speed_panel.lines if l.get_marker() == "^"]
    assert len(triangles) == 1
    np.testing.assert_allclose(triangles[0].get_xdata(), [1.0])
    np.testing.assert_allclose(triangles[0].get_ydata(), [1.0])  # axes fraction: the top edge
    assert triangles[0].get_transform() == speed_panel.get_xaxis_transform()
    # the curves: the infinite point is not drawn on the line, the finite ones are
    curves = [l for l in speed_panel.lines if l.get_marker() == "o"]
    assert len(curves) == 2
    assert np.isnan(curves[0].get_ydata()[-1]) and np.isfinite(curves[1].get_ydata()).all()

    texts = [t.get_text() for t in fig.axes[-1].get_legend().get_texts()]
    assert texts[:2] == ["0.5 \u00b5m", "1 \u00b5m"]
    assert "not converged" in texts
    assert any("open circuit" in t for t in texts)
    assert fig.axes[-1].get_legend().get_title().get_text() == "RMS roughness \u03c3"


def test_render_linear_axes_without_legend_spec_names_coordinates_with_units():
    ds = figure_dataset()
    fig = plotting.render(ds, {"y": "friction_coefficient", "x": ["speed"], "xscale": "log", "yscale": "linear"})
    ax = fig.axes[0]
    assert ax.get_yscale() == "linear" and ax.get_ylabel() == "friction coefficient (\u2013)"
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts == ["sigma = 5e-07 m", "sigma = 1e-06 m", "not converged"]


def test_render_refuses_nan_and_wrong_legend_units():
    ds = figure_dataset()
    bad = ds.copy(deep=True)
    bad["contact_resistance"][1, 2] = np.nan
    with pytest.raises(ValueError, match="NaN in case.*case12"):
        plotting.render(bad, PLOT)
    with pytest.raises(ValueError, match="does not fit sigma"):
        plotting.render(ds, {**PLOT, "legend": {"label": "{sigma:g} N", "units": {"sigma": "N"}}})


def test_save_writes_png_and_pdf(tmp_path):
    fig = plotting.render(figure_dataset(), PLOT)
    png, pdf = tmp_path / "f.png", tmp_path / "f.pdf"
    plotting.save(fig, [png, pdf])
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    height, width, _ = imread(png).shape
    assert height > 300 and width > 600
    assert pdf.read_bytes()[:5] == b"%PDF-"
